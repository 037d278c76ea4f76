"""Paths and files that are not the user's (issue 34): messages name the path the user gave, not a
temporary one; ``-o`` an existing folder suggests the name the command writes; a replaced link to a
folder leaves nothing behind; ``batch`` says which files it passed over, and why."""

from __future__ import annotations

import json
import os
import shutil
import sys
from pathlib import Path

import pytest

from robodesc.cli import main

SEEDS = Path(__file__).parent / "seeds"
ARM = str(SEEDS / "arm.urdf")


@pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="needs /proc")
@pytest.mark.parametrize("command", [["compile", ARM], ["render", ARM], ["view", ARM]])
def test_unwritable_output_names_the_users_path(command: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    suffix = {"compile": ".urdf", "render": ".png", "view": ".html"}[command[0]]
    assert main([*command, "-o", f"/proc/robodesc-x{suffix}"]) == 2
    err = capsys.readouterr().err
    assert f"/proc/robodesc-x{suffix}" in err and ".robodesc-" not in err and "Traceback" not in err


@pytest.mark.parametrize(
    ("command", "example"),
    [
        (["compile", ARM], "robot.urdf"),
        (["compile", ARM, "-t", "mjcf"], "robot.xml"),
        (["compile", ARM, "-t", "sdf"], "robot.sdf"),
        (["view", ARM], "robot.html"),
        (["render", ARM], "robot.png"),
    ],
)
def test_existing_folder_message_suggests_the_commands_file(
    command: list[str], example: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main([*command, "-o", str(tmp_path)]) == 2
    assert f"(e.g. {os.path.join(str(tmp_path), example)})" in capsys.readouterr().err


def test_replacing_a_linked_folder_leaves_no_stray_link(tmp_path: Path) -> None:
    (tmp_path / "real").mkdir()
    (tmp_path / "real" / "keep.txt").write_text("the link's target is not written through\n")
    os.symlink("real", tmp_path / "link")
    assert main(["compile", ARM, "--isaac-sim", "-o", str(tmp_path / "link"), "--no-validate", "-q"]) == 0
    assert sorted(os.listdir(tmp_path)) == ["link", "real"]
    assert not os.path.islink(tmp_path / "link") and os.listdir(tmp_path / "real") == ["keep.txt"]


def test_batch_lists_what_it_skipped_and_why(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    robots = tmp_path / "robots"
    shutil.copytree(SEEDS, robots, ignore=shutil.ignore_patterns("*.holo", "*.yaml", "*.xacro"))
    os.mkfifo(robots / "pipe.urdf")
    (robots / "comp.py").write_text("import robodesc\n\n\ndef build():\n    raise ValueError\n")
    os.symlink("nowhere.urdf", robots / "dangling.urdf")
    os.symlink("/etc/passwd", robots / "system.urdf")
    os.symlink(str(tmp_path), robots / "up")
    out = tmp_path / "out"
    assert main(["batch", str(robots), "-o", str(out), "--no-validate", "-j", "1"]) == 0
    err = capsys.readouterr().err
    summary = json.loads((out / "summary.json").read_text())
    why = {os.path.basename(s["path"]): s["why"] for s in summary["skipped"]}
    assert why == {
        "pipe.urdf": "a named pipe, not a regular file: never opened",
        "comp.py": "a Python composition: it runs when read, so only with --run-python",
        "dangling.urdf": "a dangling link",
        "system.urdf": "not a urdf robot (no robot found in it)",
        "up": "a link to a folder: not followed",
    }
    assert "skipped 5 file(s)" in err
    assert "| skipped | why |" in (out / "summary.md").read_text()


def test_validation_leaves_nothing_in_the_working_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """MuJoCo appends its warnings to MUJOCO_LOG.TXT in the working folder unless they are taken:
    an unstable source (damping -1e30, an inertia of 1e30) warns in every step."""
    source = tmp_path / "arm.urdf"
    shutil.copytree(SEEDS / "meshes", tmp_path / "meshes")
    text = (SEEDS / "arm.urdf").read_text().replace('damping="0.1"', 'damping="-1e30"')
    source.write_text(text.replace('izz="0.001"', 'izz="1e30"'))
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    assert main(["compile", str(source), "-t", "mjcf", "-o", str(tmp_path / "o" / "robot.xml"), "-q"]) == 0
    assert main(["validate", str(source), "--dynamics", "--engines", "mujoco"]) == 0
    assert os.listdir(work) == []


def test_engine_workers_leave_nothing_in_the_working_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Newton's solver is MuJoCo: an unstable run in its worker (``validate -t usd --dynamics
    --engines newton`` of an arm of 1e-9 kg driven at kp 1e15) left MUJOCO_LOG.TXT in the user's
    folder. Every worker now starts in a scratch folder. Shown with MuJoCo in this interpreter, as
    the Newton worker runs it, so that no Newton venv is needed."""
    from robodesc.validation.worker import run_worker

    script = tmp_path / "unstable_worker.py"
    script.write_text(
        "import json, os, sys\n"
        "import mujoco\n"
        "json.loads(sys.stdin.read())\n"
        "m = mujoco.MjModel.from_xml_string('<mujoco><worldbody><body><joint/><geom size=\".1\"/></body></worldbody></mujoco>')\n"
        "d = mujoco.MjData(m)\n"
        "d.qvel[0] = float('inf')\n"
        "mujoco.mj_step(m, d)\n"
        "print(json.dumps({'cwd': os.getcwd(), 'warnings': int(d.warning[mujoco.mjtWarning.mjWARN_BADQVEL].number)}))\n"
    )
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    done = run_worker(sys.executable, str(script), {}, 120.0, "test")
    assert done.answer is not None, done.failure
    assert done.answer["warnings"] == 1  # MuJoCo did warn, and wrote its log where the worker started
    assert os.listdir(work) == []
    assert not os.path.exists(done.answer["cwd"])  # the scratch folder went with the worker
