"""Moving pictures (``validate --dynamics --video DIR``, ``render --video FILE``; robodesc.view.video).

The fast tests simulate tiny hand-written robots in MuJoCo for 0.2 s (11 frames) and decode what was
written: the frame count and size, pixels that change as the robot moves and stay equal when it does
not, the root pose each engine reports. The slow one runs PhysX and Newton where their interpreters
exist. Nothing is timed."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import robodesc
from robodesc.validation.dynamics import DynamicsOptions, DynamicsReport, run_dynamics
from robodesc.view import video
from robodesc.view.video import read_frames, write_dynamics_clips

from ..conftest import EXAMPLES, ROOT

SECONDS = 0.2
FRAMES = round(SECONDS / video.FRAME_DT) + 1  # the start pose, then one every 20 ms

# A horizontal arm on a hinge: with kp 0.05 N·m/rad it sags under gravity in the hold.
ARM = """<robot name="{name}">
  <link name="world"/>
  <joint name="weld" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>
  </link>
  <joint name="hinge" type="{kind}">
    <parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="100" velocity="10"/>
  </joint>
  <link name="arm">
    <inertial><origin xyz="0.25 0 0"/><mass value="1"/>
      <inertia ixx="0.001" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><origin xyz="0.25 0 0"/><geometry><box size="0.5 0.05 0.05"/></geometry>
      <material name="red"><color rgba="0.8 0.1 0.1 1"/></material></visual>
    <collision><origin xyz="0.25 0 0"/><geometry><box size="0.5 0.05 0.05"/></geometry></collision>
  </link>
</robot>
"""

# A plate on three feet, each on a hinge: it stands on three links, so the drop runs.
_FOOT = """  <joint name="leg{i}" type="revolute">
    <parent link="base"/><child link="foot{i}"/><origin xyz="{x} {y} -0.05"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="50" velocity="10"/>
  </joint>
  <link name="foot{i}">
    <inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><sphere radius="0.03"/></geometry></visual>
    <collision><geometry><sphere radius="0.03"/></geometry></collision>
  </link>
"""
TRIPOD = (
    """<robot name="tripod">
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><box size="0.3 0.3 0.04"/></geometry></visual>
    <collision><geometry><box size="0.3 0.3 0.04"/></geometry></collision>
  </link>
"""
    + "".join(_FOOT.format(i=i, x=x, y=y) for i, (x, y) in enumerate(((0.1, 0.0), (-0.05, 0.09), (-0.05, -0.09))))
    + "</robot>\n"
)


@pytest.fixture
def gl_here(gl: str, monkeypatch: pytest.MonkeyPatch) -> str:
    monkeypatch.setenv("MUJOCO_GL", gl)
    return gl


def _report(path: Path, **kw: Any) -> DynamicsReport:
    robot = robodesc.load(str(path))
    opts = DynamicsOptions(engines=("mujoco",), duration=SECONDS, record=True, **kw)
    return run_dynamics(robot, {"urdf": str(path)}, opts)


def _differ(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a.astype(int) - b.astype(int)).mean())


def test_a_sagging_arm_moves_and_a_fixed_one_does_not(tmp_path: Path, gl_here: str) -> None:
    moving, fixed = tmp_path / "moving.urdf", tmp_path / "fixed.urdf"
    moving.write_text(ARM.format(name="moving", kind="revolute"))
    fixed.write_text(ARM.format(name="fixed", kind="fixed"))
    out = tmp_path / "clips"
    clips = write_dynamics_clips(_report(moving, stiffness=0.05, damping=0.01), str(out), fmt="gif")
    clips += write_dynamics_clips(_report(fixed), str(out), fmt="gif")
    # The arm has no floating base: only the hold is drawn, one clip per robot.
    assert [(c.scenario, Path(c.path).name) for c in clips] == [
        ("hold-fixed", "moving_hold-fixed.gif"),
        ("hold-fixed", "fixed_hold-fixed.gif"),
    ]
    for clip in clips:
        frames = read_frames(clip.path)
        assert len(frames) == clip.frames == FRAMES
        assert frames[0].shape == (video.PANEL[1], video.PANEL[0], 3) == (clip.height, clip.width, 3)
        assert clip.panels == ["mujoco (urdf)"]
    sag, still = read_frames(clips[0].path), read_frames(clips[1].path)
    # The label's time changes in every clip: compare below it.
    body = slice(24, None)
    assert _differ(sag[0][body], sag[-1][body]) > 0.5  # the arm swung down
    assert all(_differ(still[0][body], f[body]) == 0.0 for f in still)
    assert sorted(os.listdir(out)) == ["fixed_hold-fixed.gif", "moving_hold-fixed.gif"]  # no temporary left


@pytest.mark.skipif(not video.encoder_available(), reason="imageio-ffmpeg is not installed (robodesc[video])")
def test_the_tripod_drop_as_mp4_follows_the_reported_root(tmp_path: Path, gl_here: str) -> None:
    path = tmp_path / "tripod.urdf"
    path.write_text(TRIPOD)
    report = _report(path)
    drop = next(r for r in report.runs if r.scenario == "drop")
    # The root's pose at every 10 ms sample: it falls from the spawn height and lands.
    assert len(drop.root) == len(drop.trajectory) == round(SECONDS / 0.01)
    spawn = report.info["setup"]["stand_height"] + report.info["setup"]["drop_clearance"]
    assert drop.root[0][1][2] < spawn and drop.root[-1][1][2] == pytest.approx(drop.height, abs=1e-9)
    assert drop.root[-1][1][2] < spawn - 0.03
    assert np.linalg.norm(drop.root[-1][1][3:]) == pytest.approx(1.0, abs=1e-6)  # a unit quaternion
    clips = write_dynamics_clips(report, str(tmp_path / "clips"))
    assert [c.scenario for c in clips] == ["hold-fixed", "drop"] and {c.format for c in clips} == {"mp4"}
    frames = read_frames(clips[1].path)
    assert len(frames) == FRAMES and frames[0].shape == (240, 320, 3)
    assert _differ(frames[0][24:], frames[-1][24:]) > 0.5


def test_runs_without_video_record_no_root_pose(tmp_path: Path) -> None:
    path = tmp_path / "tripod.urdf"
    path.write_text(TRIPOD)
    robot = robodesc.load(str(path))
    report = run_dynamics(robot, {"urdf": str(path)}, DynamicsOptions(engines=("mujoco",), duration=SECONDS))
    drop = next(r for r in report.runs if r.scenario == "drop")
    assert drop.trajectory and drop.root == []
    assert "record" not in report.info["setup"]  # the report's setup is as before


def test_panels_hold_a_failed_runs_last_pose() -> None:
    from robodesc.validation.dynamics.result import Run

    report = DynamicsReport("r", info={"setup": {"duration": 0.1, "pose": {"a": 0.0}}})
    good = Run("mujoco", "urdf", "hold-fixed", trajectory=[(0.01 * k, {"a": 0.1 * k}) for k in range(1, 11)])
    bad = Run("drake", "sdf", "hold-fixed", ok=False, trajectory=[(0.01, {"a": 5.0}), (0.02, {"a": 6.0})])
    panels = video.scenario_panels(report, "hold-fixed")
    assert panels == []  # a report with runs only counts them: none yet
    report.runs += [good, bad]
    panels = video.scenario_panels(report, "hold-fixed")
    assert [p.label for p in panels] == ["mujoco (urdf)", "drake (sdf)"]
    assert [round(t, 2) for t, _, _ in panels[0].frames] == [0.0, 0.02, 0.04, 0.06, 0.08, 0.1]
    assert [q["a"] for _, _, q in panels[0].frames] == pytest.approx([0.0, 0.2, 0.4, 0.6, 0.8, 1.0])
    assert [q["a"] for _, _, q in panels[1].frames] == [0.0, 6.0, 6.0, 6.0, 6.0, 6.0]
    assert panels[1].note == "failed at 0.02 s"


def test_render_video_sweeps_the_joints(tmp_path: Path, gl_here: str) -> None:
    out = tmp_path / "arm.gif"
    clip = video.render_video(str(EXAMPLES / "urdf/gripper_arm.urdf"), str(out), size=(100, 70))
    frames = read_frames(str(out))
    assert (clip.width, clip.height) == (96, 64)  # rounded down to multiples of 16
    assert len(frames) == clip.frames == round(video.SWEEP_SECONDS * video.FPS) + 1
    # Home at both ends, the lower limit a quarter in: the first and last frames are alike.
    assert _differ(frames[0][24:], frames[-1][24:]) == pytest.approx(0.0, abs=0.05)
    assert _differ(frames[0][24:], frames[len(frames) // 4][24:]) > 1.0


def test_sweep_goes_to_each_limit_and_back() -> None:
    robot = robodesc.load(str(EXAMPLES / "urdf/gripper_arm.urdf"))
    panel = video.sweep_panel(robot, seconds=1.0, frame_dt=0.25)
    joints = robot.joint_map()
    q = [frame[2] for frame in panel.frames]
    for name, values in ((n, [f[n] for f in q]) for n in q[0]):
        lim = joints[name].limit
        # A joint without limits (the continuous wrist) turns a quarter each way.
        lower = lim.lower if lim is not None and lim.lower is not None else -math.pi / 2
        upper = lim.upper if lim is not None and lim.upper is not None else math.pi / 2
        home = min(max(0.0, lower), upper)
        assert values == pytest.approx([home, lower, home, upper, home], abs=1e-9)
    assert len(q[0]) == len([j for j in robot.joints if j.type.dof == 1 and j.mimic is None])


def _cli(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    return subprocess.run(
        [sys.executable, "-m", "robodesc", *args], capture_output=True, text=True, cwd=cwd, env=env, check=False
    )


def test_cli_refuses_a_video_folder_it_cannot_use(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from robodesc.cli import main

    monkeypatch.chdir(tmp_path)
    arm = tmp_path / "arm.urdf"
    arm.write_text(ARM.format(name="arm", kind="revolute"))
    (tmp_path / "afile").write_text("x")
    for args, says in (
        (("validate", "arm.urdf", "--dynamics", "--video", "afile"), "--video afile: is an existing file"),
        (("validate", "arm.urdf", "--video", "clips"), "--video DIR draws the runs of --dynamics: add --dynamics"),
        (("validate", "arm.urdf", "--dynamics", "--video-format", "gif"), "add --video DIR"),
        (("validate", "arm.urdf", "--dynamics", "--video", "afile/clips"), "afile is a file"),
        (("render", "arm.urdf", "--video", "arm.avi"), ".mp4 or .gif"),
        (("render", "arm.urdf"), "-o FILE.png, --video FILE.mp4, or both"),
    ):
        assert main(list(args)) == 2, args
        err = capsys.readouterr().err
        assert says in err and "Traceback" not in err, err
    # Refused before any work: nothing written, and no MUJOCO_LOG.TXT.
    assert sorted(os.listdir(tmp_path)) == ["afile", "arm.urdf"]


def test_a_failed_clip_leaves_earlier_files_as_they_were(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The encoder writes a hidden file beside the clip, renamed into place: a failure leaves the
    earlier file byte-identical and no temporary; a symlink where a clip goes is replaced, never
    written through. (Encoded here, with frames made up: a render may run in a child process.)"""
    out = tmp_path / "clips"
    out.mkdir()
    earlier = out / "arm_hold-fixed.gif"
    earlier.write_bytes(b"an earlier clip")
    outside = tmp_path / "outside.gif"
    outside.write_bytes(b"not robodesc's")
    (out / "arm_drop.gif").symlink_to(outside)
    frames = [np.full((48, 64, 3), level, dtype=np.uint8) for level in (0, 128, 255)]

    def broken(frames: list[np.ndarray], path: str, fps: int) -> None:
        Path(path).write_bytes(b"half")
        raise OSError("disk full")

    with monkeypatch.context() as patch:
        patch.setattr(video, "_write_gif", broken)
        with pytest.raises(OSError, match="disk full"):
            video.encode(frames, str(earlier), "gif")
    assert earlier.read_bytes() == b"an earlier clip"
    assert sorted(os.listdir(out)) == ["arm_drop.gif", "arm_hold-fixed.gif"]  # the temporary removed
    video.encode(frames, str(out / "arm_drop.gif"), "gif")
    assert outside.read_bytes() == b"not robodesc's" and not (out / "arm_drop.gif").is_symlink()
    decoded = read_frames(str(out / "arm_drop.gif"))
    assert [int(f.mean()) for f in decoded] == [0, 128, 255]


def test_validate_video_on_the_command_line(
    tmp_path: Path, gl_here: str, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """The CLI's path end to end, in process, with the runs cut to 0.4 s (the flag has no duration;
    at 0.2 s the slide's block would not yet have slid its 5 cm)."""
    import dataclasses

    from robodesc import check_dynamics
    from robodesc.cli import main

    given = check_dynamics.dynamics_options
    monkeypatch.setattr(
        check_dynamics, "dynamics_options", lambda *a: dataclasses.replace(given(*a), duration=2 * SECONDS)
    )
    monkeypatch.chdir(tmp_path)
    (tmp_path / "arm.urdf").write_text(ARM.format(name="arm", kind="revolute"))
    code = main(["validate", "arm.urdf", "--dynamics", "--engines", "mujoco", "--video", "clips", "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 0, [c for c in doc["dynamics"]["checks"] if c["status"] != "pass"]
    (clip,) = doc["videos"]
    frames = round(2 * SECONDS / video.FRAME_DT) + 1
    assert clip["scenario"] == "hold-fixed" and clip["frames"] == frames
    assert clip["panels"] == ["mujoco (urdf)", "mujoco (source)"]  # the output, and its source beside it
    assert (clip["width"], clip["height"]) == (2 * video.PANEL[0], video.PANEL[1])
    assert len(read_frames(clip["path"])) == frames
    assert sorted(os.listdir(tmp_path)) == ["arm.urdf", "clips"]  # nothing else in the working folder
    assert os.listdir(tmp_path / "clips") == [
        "arm_hold-fixed.mp4" if video.encoder_available() else "arm_hold-fixed.gif"
    ]


def test_help_explains_the_video_options(capsys: pytest.CaptureFixture[str]) -> None:
    from robodesc.cli import main

    for command, says in (
        ("validate", ["--video DIR", "--video-format", "imageio-ffmpeg", "GIF", "one panel per engine"]),
        ("render", ["--video FILE.mp4", "swept", "lower limit", ".gif"]),
    ):
        with pytest.raises(SystemExit):
            main([command, "--help"])
        text = " ".join(capsys.readouterr().out.split())
        assert all(s in text for s in says), (command, text)


def test_a_clip_into_a_new_folder_makes_it(tmp_path: Path) -> None:
    """The README's ``render --video out/quadruped.mp4`` on a fresh checkout: ``out/`` is made, as
    every output's folder is (the clip's hidden file once had nowhere to go: exit 2)."""
    from robodesc.view.video import encode

    frames = [np.zeros((16, 16, 3), dtype=np.uint8), np.full((16, 16, 3), 255, dtype=np.uint8)]
    out = tmp_path / "new" / "deeper" / "clip.gif"
    encode(frames, str(out), "gif")
    assert out.is_file() and [p.name for p in out.parent.iterdir()] == ["clip.gif"]
