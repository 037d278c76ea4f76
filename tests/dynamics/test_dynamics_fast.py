"""The fast CI case of ``validate --dynamics`` (#28): MuJoCo only, one arm and one quadruped, and the
verdict rules on hand-made runs. Numbers are compared with tolerances (they may move in the last
digits with the CPU's BLAS kernel); nothing here is timed."""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest

import robodesc
from robodesc.validation.dynamics import DynamicsOptions, Run, home_pose, run_dynamics
from robodesc.validation.dynamics.result import DynamicsReport
from robodesc.validation.dynamics.scenarios import Setup, Thresholds, make_setup, stand_height
from robodesc.validation.dynamics.verdict import judge
from robodesc.validation.report import Status

from ..conftest import EXAMPLES, ROOT

ARM = str(EXAMPLES / "urdf/gripper_arm.urdf")
QUAD = str(EXAMPLES / "quadruped.yaml")
MUJOCO = {"engines": ("mujoco",)}
# A bent shoulder, so gravity loads the drives (the arm stands straight up at zero).
ARM_POSE = {"shoulder_pitch": 0.8, "elbow": 0.5}


def _rows(report: DynamicsReport, name: str) -> list[Status]:
    return [c.status for c in report.checks if c.name == name]


def test_arm_holds_and_behaves_as_its_source_in_mujoco() -> None:
    result = robodesc.check(ARM, "urdf", dynamics={**MUJOCO, "pose": ARM_POSE})
    dyn = result.dynamics
    assert dyn is not None and dyn.ok, dyn.to_text()
    hold = next(r for r in dyn.runs if r.file == "urdf" and r.scenario == "hold-fixed")
    # kp 100 against the arm's gravity torque: a small, non-zero sag (steady state tau / kp).
    assert 1e-3 < (hold.drift or 0.0) < 0.2  # 0.08 rad at the shoulder
    assert _rows(dyn, "source:hold-fixed") == [Status.PASS]
    slide = next(r for r in dyn.runs if r.scenario == "slide")
    assert slide.mu == pytest.approx(1.0)  # no friction in the source: MuJoCo's default
    assert (slide.stick or 1.0) < 0.01 < 0.05 < (slide.slide or 0.0)


def test_quadruped_drops_and_stands_in_mujoco() -> None:
    """From the Isaac folder's default stance (the legged heuristic: knees bent, feet under the hips)
    and its derived gains, as ``--isaac-sim --no-fix-base`` spawns it."""
    dyn = robodesc.check(QUAD, "urdf", dynamics=MUJOCO).dynamics
    assert dyn is not None and dyn.ok, dyn.to_text()
    assert dyn.info["pose_note"] == "pose: legged heuristic; gains: derived (docs/isaac.md)"
    drop = next(r for r in dyn.runs if r.scenario == "drop")  # it stands on four feet: the drop runs
    assert drop.ok and drop.tilt is not None and drop.tilt < math.radians(5)
    robot = robodesc.load(QUAD)
    pose = dyn.info["setup"]["pose"]
    assert pose["FL_knee"] < -1.0 and pose["RR_hip_flex"] > 0.5
    # It settles near the height the scenario computed from the colliders (contact softness apart).
    assert drop.height == pytest.approx(stand_height(robot, pose), abs=0.02)
    assert drop.drift is not None and drop.drift < 0.1  # the knees hold the body's share


def test_an_output_unlike_its_source_fails(tmp_path: Path) -> None:
    """A heavier forearm in the output: the same engine, gains and pose, a different sag."""
    robot = robodesc.load(ARM)
    out = tmp_path / "arm.urdf"
    robodesc.compile_to(ARM, "urdf", str(out), mesh_paths="absolute")
    text = out.read_text()
    # The forearm's mass: 0.8 kg in the source.
    out.write_text(re.sub(r'(<link name="forearm">.*?<mass value=")([^"]+)', r"\g<1>2.4", text, count=1, flags=re.S))
    opts = DynamicsOptions(engines=("mujoco",), pose=ARM_POSE)
    report = run_dynamics(robot, {"urdf": str(out)}, opts, source_urdf=ARM)
    assert _rows(report, "source:hold-fixed") == [Status.FAIL]
    assert not report.ok


def _setup(friction: float | None = None) -> Setup:
    return Setup(pose={"a": 0.0}, gains={"a": (100.0, 1.0)}, floating=True, stand_height=0.3, friction=friction)


def _hold(engine: str, q: float) -> Run:
    return Run(engine, engine, "hold-fixed", drift=abs(q), worst_joint="a", final_q={"a": q})


def test_drives_that_do_not_hold_where_another_engine_holds_fail() -> None:
    report = DynamicsReport("r", runs=[_hold("mujoco", 0.001), _hold("newton", 0.4)])
    judge(report, _setup(), Thresholds())
    assert _rows(report, "agree:hold-fixed") == [Status.FAIL]
    # Both sag, apart: engines differ, not the file.
    report = DynamicsReport("r", runs=[_hold("mujoco", 0.2), _hold("newton", 0.4)])
    judge(report, _setup(), Thresholds())
    assert _rows(report, "agree:hold-fixed") == [Status.WARN] and report.ok


def test_a_sag_the_source_shows_in_the_same_engine_is_an_engine_difference() -> None:
    source = Run("mujoco", "source", "hold-fixed", drift=0.4, worst_joint="a", final_q={"a": 0.4})
    source.trajectory = [(0.5, {"a": 0.4})]
    output = _hold("mujoco", 0.4)
    output.trajectory = [(0.5, {"a": 0.4})]
    report = DynamicsReport("r", runs=[output, source, _hold("drake", 0.001)])
    judge(report, _setup(), Thresholds())
    assert _rows(report, "source:hold-fixed") == [Status.PASS]
    assert _rows(report, "agree:hold-fixed") == [Status.WARN] and report.ok


def test_a_friction_not_the_sources_fails() -> None:
    slide = Run("mujoco", "mjcf", "slide", mu=1.0, stick=0.002, slide=1.2)
    report = DynamicsReport("r", runs=[slide])
    judge(report, _setup(friction=0.5), Thresholds())
    assert _rows(report, "friction") == [Status.FAIL] and not report.ok
    # Without a friction in the source, the engine's default is no contradiction.
    report = DynamicsReport("r", runs=[Run("mujoco", "mjcf", "slide", mu=1.0, stick=0.002, slide=1.2)])
    judge(report, _setup(), Thresholds())
    assert report.ok and _rows(report, "slide") == [Status.PASS]


def _drop(engine: str, file: str, height: float, mass: float) -> Run:
    return Run(engine, file, "drop", height=height, tilt=0.0, mass=mass)


def test_a_mass_the_output_loses_is_a_mass_row_not_a_contact_model() -> None:
    """ANYmal C from main: Newton read 81.5 kg from the USD for a 52.1 kg URDF and settled 12 cm
    apart from MuJoCo; the verdict blamed contact models."""
    setup = Setup(pose={"a": 0.0}, gains={"a": (100.0, 1.0)}, floating=True, stand_height=0.6, friction=None)
    setup.mass = 52.13
    runs = [_drop("mujoco", "urdf", 0.55, 52.13), _drop("newton", "usd", 0.43, 81.51)]
    report = DynamicsReport("anymal", runs=runs)
    judge(report, setup, Thresholds())
    masses = {c.element: c for c in report.checks if c.name == "mass"}
    assert masses["mujoco/urdf"].status is Status.PASS
    assert masses["newton/usd"].status is Status.FAIL and not report.ok
    assert masses["newton/usd"].error == pytest.approx((81.51 - 52.13) / 52.13, rel=1e-9)
    drop = next(c for c in report.checks if c.name == "agree:drop")
    assert "different masses" in drop.message and "contact models" not in drop.message
    # The same drop with equal masses: what is left is the engines' contact.
    runs = [_drop("mujoco", "urdf", 0.55, 52.13), _drop("newton", "usd", 0.43, 52.13)]
    report = DynamicsReport("anymal", runs=runs)
    judge(report, setup, Thresholds())
    assert report.ok and _rows(report, "mass") == [Status.PASS, Status.PASS]
    assert "contact models differ" in next(c for c in report.checks if c.name == "agree:drop").message


def test_home_pose_takes_the_table_and_clamps_into_limits() -> None:
    robot = robodesc.load(ARM)
    pose = home_pose(robot, {"shoulder_pitch": 99.0, "elbow": -0.3})
    limit = robot.joint_map()["shoulder_pitch"].limit
    assert limit is not None and pose["shoulder_pitch"] == limit.upper
    assert pose["elbow"] == pytest.approx(-0.3)
    assert "finger_right_joint" not in pose  # a mimic follows its leader: no drive of its own


def test_cli_prints_the_table_and_json() -> None:
    cmd = [sys.executable, "-m", "robodesc", "validate", ARM, "--dynamics", "--engines", "mujoco"]
    done = subprocess.run([*cmd, "--pose", "shoulder_pitch=0.8"], capture_output=True, text=True, cwd=ROOT)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "dynamics of 'gripper_arm'" in done.stdout and "hold-fixed" in done.stdout
    done = subprocess.run([*cmd, "--json"], capture_output=True, text=True, cwd=ROOT)
    doc = json.loads(done.stdout)
    # An arm does not stand on three feet: no drop (a fall from any pose is chaotic).
    assert doc["dynamics"]["ok"] and {r["scenario"] for r in doc["dynamics"]["runs"]} == {"hold-fixed", "slide"}


def _mjcf_with_gains(urdf: Path, out: Path, kp: float) -> Path:
    """An MJCF of the arm with its own position actuators, as an MJCF target would write it."""
    import mujoco

    from robodesc.validation.dynamics.mujoco_run import load_spec

    robot = robodesc.load(ARM)
    spec, why = load_spec(robot, str(urdf), "urdf", {})
    assert spec is not None, why
    for name in home_pose(robot):
        act = spec.add_actuator(name=f"act_{name}", target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.set_to_position(kp=kp, kv=1.0)
    spec.compile()
    out.write_text(spec.to_xml())
    return out


@pytest.mark.parametrize(("kp", "status"), [(100.0, Status.PASS), (30.0, Status.FAIL)])
def test_an_mjcf_runs_with_its_own_actuators(tmp_path: Path, kp: float, status: Status) -> None:
    """The MJCF target plugs in: its actuators are used as written and compared with the source
    (gains 100/1): the compile's gains pass, other gains fail."""
    urdf = tmp_path / "arm.urdf"
    robodesc.compile_to(ARM, "urdf", str(urdf), mesh_paths="absolute")
    mjcf = _mjcf_with_gains(urdf, tmp_path / "arm.xml", kp)
    opts = DynamicsOptions(engines=("mujoco",), pose=ARM_POSE)
    report = run_dynamics(robodesc.load(ARM), {"mjcf": str(mjcf)}, opts, source_urdf=ARM)
    assert _rows(report, "source:hold-fixed") == [status], report.to_text()


def test_names_the_checked_target_renamed_still_match() -> None:
    """-t usd renames Spirit's joints (``0`` -> ``a0``): the scenarios use the source's names,
    which the URDF MuJoCo reads keeps, and the stand pose applies."""
    from ..conftest import SPIRIT_XACRO

    if not SPIRIT_XACRO.is_file():
        pytest.skip("Quad-SDK corpus not present")
    stand = {"0|2|4|6": 0.76, "1|3|5|7": 1.52}
    dyn = robodesc.check(str(SPIRIT_XACRO), "usd", dynamics={**MUJOCO, "pose": stand}).dynamics
    assert dyn is not None and dyn.ok, dyn.to_text()
    hold = next(r for r in dyn.runs if r.file == "urdf" and r.scenario == "hold-fixed")
    assert len(hold.final_q) == 12 and hold.final_q["1"] == pytest.approx(1.52, abs=0.05)


def test_a_quadruped_slides_and_stands_on_its_feet_friction(tmp_path: Path) -> None:
    """Feet with their own friction, a body with none: the slide's material and the drop's floor
    are the feet's (what touches the ground), read back from the MJCF and judged against the
    source; the dropped robot settles before the run ends."""
    text = Path(QUAD).read_text()
    calf = "        mass: 0.25\n        pose: [0, 0, -0.22]\n"
    assert calf in text
    src = tmp_path / "quadruped.yaml"
    src.write_text(text.replace(calf, calf + "        contact: {mu: 0.6}\n"))
    dyn = robodesc.check(str(src), "mjcf", dynamics=MUJOCO, fix_base=False).dynamics
    assert dyn is not None and dyn.ok, dyn.to_text()
    assert dyn.info["setup"]["friction"] == pytest.approx(0.6)
    assert sorted(dyn.info["setup"]["feet"]) == sorted(f"{leg}_calf" for leg in ("FL", "FR", "RL", "RR"))
    runs = {r.scenario: r for r in dyn.runs if r.file == "mjcf"}
    assert runs["slide"].mu == pytest.approx(0.6) and runs["drop"].mu == pytest.approx(0.6)
    assert _rows(dyn, "friction") == [] and _rows(dyn, "slide") == [Status.PASS]
    assert runs["drop"].settle is not None and runs["drop"].settle < 1.0


def test_an_engine_reading_the_source_differently_is_a_warning() -> None:
    """Drake reads SDF's mu/mu2 as static/dynamic friction and refuses a source's lone mu 0.8 (SDF's
    mu2 defaults to 1): the file says what the source says, so the failed run is a warning."""
    from robodesc.validation.dynamics.result import READS_DIFFERENTLY

    refused = Run("drake", "sdf", "slide", ok=False, error=f"{READS_DIFFERENTLY} Drake reads SDF's mu ...")
    report = DynamicsReport("r", runs=[refused])
    judge(report, _setup(), Thresholds())
    assert _rows(report, "run") == [Status.WARN] and report.ok
    crashed = Run("drake", "sdf", "slide", ok=False, error="NaN")
    report = DynamicsReport("r", runs=[crashed])
    judge(report, _setup(), Thresholds())
    assert _rows(report, "run") == [Status.FAIL]


def test_scenarios_start_from_the_isaac_modules_pose_and_gains(tmp_path: Path) -> None:
    """Issue 29: hold and drop start where ``--isaac-sim --no-fix-base`` spawns the robot, with the
    same per-joint gains (the module rounds them to four digits)."""
    import runpy

    from robodesc.check_dynamics import default_stance

    robodesc.compile_for_isaac_sim(QUAD, tmp_path / "q", fix_base=False)
    module = runpy.run_path(str(next((tmp_path / "q").glob("*_isaaclab.py"))))["ROBOT"]
    opts = default_stance(robodesc.load(QUAD), DynamicsOptions())
    assert opts.pose is not None and opts.stiffness is not None and opts.damping is not None
    pose = {k.replace("\\", ""): v for k, v in opts.pose.items()}
    assert pose == pytest.approx(module["init_state"]["joint_pos"])
    for group in module["actuators"].values():
        for expr in group["joint_names_expr"]:
            assert opts.stiffness[expr] == pytest.approx(group["stiffness"], rel=1e-3)  # type: ignore[index]
            assert opts.damping[expr] == pytest.approx(group["damping"], rel=1e-3)  # type: ignore[index]


def test_given_pose_and_gains_win_over_the_defaults() -> None:
    from robodesc.check_dynamics import default_stance

    robot = robodesc.load(QUAD)
    opts = default_stance(robot, DynamicsOptions(pose={".*": 0.0}, stiffness=50.0))
    assert set(opts.pose.values()) == {0.0}  # type: ignore[union-attr]
    assert opts.stiffness == 50.0
    # The damping is derived from the given stiffness: kd = 2·sqrt(kp·I_eff).
    assert isinstance(opts.damping, dict) and all(v > 0 for v in opts.damping.values())
    assert opts.defaults == "pose: given; gains: derived (docs/isaac.md)"


def test_the_usd_is_simulated_with_the_gains_it_writes(tmp_path: Path) -> None:
    """-t usd derives its gains per joint (issue 38: its 100 / 1 sagged ur10 by 1.1 rad) and Newton
    and PhysX read them from the file: every engine is given the same derived ones, the MJCF's."""
    from pxr import Usd, UsdPhysics

    usd = robodesc.check(ARM, "usd", dynamics=MUJOCO).dynamics
    mjcf = robodesc.check(ARM, "mjcf", dynamics=MUJOCO).dynamics
    assert usd is not None and mjcf is not None
    gains = {k: tuple(v) for k, v in usd.info["setup"]["gains"].items()}
    assert gains == {k: tuple(v) for k, v in mjcf.info["setup"]["gains"].items()}
    assert set(gains.values()) != {(100.0, 1.0)}
    out = tmp_path / "arm.usda"
    robodesc.compile_to(ARM, "usd", str(out), validate=False)
    stage = Usd.Stage.Open(str(out))
    for prim in stage.Traverse():
        name = prim.GetDisplayName() or prim.GetName()
        if name in gains and prim.HasAPI(UsdPhysics.DriveAPI, "angular"):
            drive = UsdPhysics.DriveAPI(prim, "angular")
            # Per degree in the file; the setup's kp is SI, rounded to 4 figures in the file.
            assert math.degrees(drive.GetStiffnessAttr().Get()) == pytest.approx(gains[name][0], rel=1e-3), name


def test_every_engine_is_given_the_source_servos_gains() -> None:
    # An MJCF's position servo (shoulder kp 50 kv 2, slide kp 200 kv 10) is what every target writes;
    # the dynamics check must simulate it in every engine, not the USD's constant 100 in MuJoCo and
    # Drake beside the source's gains in Newton and PhysX (menagerie's iiwa14 drifted 0.156 rad in
    # MuJoCo and 0.029 in PhysX, a "disagreement" made by the gains alone).
    from robodesc.check_dynamics import _with_source_gains
    from robodesc.ir.rules import lookup

    robot = robodesc.load(str(ROOT / "tests/mjcf_in/data/features.xml"))
    opts = _with_source_gains(robot, DynamicsOptions(stiffness=100.0, damping=1.0), {})
    assert lookup(opts.stiffness, "shoulder", "stiffness") == pytest.approx(50.0)
    assert lookup(opts.damping, "shoulder", "damping") == pytest.approx(2.0)
    assert lookup(opts.stiffness, "slide", "stiffness") == pytest.approx(200.0)
    assert lookup(opts.damping, "slide", "damping") == pytest.approx(10.0)
    # A velocity servo holds no position: stiffness 0, its kv as damping.
    assert lookup(opts.stiffness, "wrist_roll", "stiffness") == pytest.approx(0.0)
    assert lookup(opts.damping, "wrist_roll", "damping") == pytest.approx(3.0)
    # Joints without a source servo keep the constant.
    others = [j.name for j in robot.actuated_joints() if j.drive is None]
    assert others and all(lookup(opts.stiffness, n, "stiffness") == pytest.approx(100.0) for n in others)
    assert "the source's servos on 3 joints" in (opts.defaults or "")
    # Gains the user gives win.
    given = _with_source_gains(robot, DynamicsOptions(stiffness=7.0, damping=1.0), {"stiffness": 7.0})
    assert lookup(given.stiffness, "shoulder", "stiffness") == pytest.approx(7.0)
    assert lookup(given.damping, "shoulder", "damping") == pytest.approx(2.0)


@pytest.mark.parametrize("blown", [4.85e27, math.nan])
def test_a_run_that_blows_up_is_a_run_failure_not_a_disagreement(blown: float) -> None:
    """tiago_pro's hold in PhysX ended 4.85e27 rad off: a failure of that engine's run (a ``run``
    row, FAIL for an output), never a WARN that two engines "settle apart"."""
    physx = Run("physx", "usd", "hold-fixed", drift=abs(blown), worst_joint="a", final_q={"a": blown})
    physx.trajectory = [(0.01, {"a": 0.02}), (0.02, {"a": blown})]
    report = DynamicsReport("r", runs=[physx, _hold("mujoco", 0.01)])
    judge(report, _setup(), Thresholds())
    assert not physx.ok and "blew up" in physx.error and "0.02 s" in physx.error
    assert _rows(report, "run") == [Status.FAIL] and not report.ok
    assert _rows(report, "agree:hold-fixed") == []
    # The source blowing up in the same engine too: the engine's trouble with the robot, a warning.
    source = Run("physx", "source", "hold-fixed", final_q={"a": blown})
    report = DynamicsReport("r", runs=[Run("physx", "usd", "hold-fixed", final_q={"a": blown}), source])
    judge(report, _setup(), Thresholds())
    assert _rows(report, "run") == [Status.WARN, Status.WARN] and report.ok


def test_a_run_within_bounds_is_judged_as_before() -> None:
    # A continuous joint may turn many times in a run: 300 rad is motion, not a blow-up.
    report = DynamicsReport("r", runs=[_hold("physx", 300.0), _hold("mujoco", 300.0)])
    judge(report, _setup(), Thresholds())
    assert _rows(report, "run") == [] and _rows(report, "agree:hold-fixed") == [Status.PASS]


def test_mimic_followers_start_where_their_leader_puts_them() -> None:
    """Every engine starts a follower at multiplier x its leader + offset (Setup.start); a follower
    left at 0 starts its mimic constraint violated (PhysX ran tiago_pro away from 0.15 rad)."""
    robot = robodesc.load(str(ROOT / "tests/usd/data/gripper.urdf"))
    setup = make_setup(robot, DynamicsOptions(pose={"finger": 0.3}))
    assert setup.pose == {"finger": 0.3}
    assert setup.followers == pytest.approx({"finger_mimic": -0.3 + 0.05, "pad_slide": 0.02 * 0.3 + 0.001})
    assert setup.as_dict()["start"] == {**setup.followers, "finger": 0.3}
    # MuJoCo starts the follower there: its equality constraint then holds a still robot.
    dyn = robodesc.check(
        str(ROOT / "tests/usd/data/gripper.urdf"), "urdf", dynamics={**MUJOCO, "pose": {"finger": 0.3}}
    )
    assert dyn.dynamics is not None and dyn.dynamics.ok, dyn.dynamics.to_text()


NAMESAKE = """<robot name="namesake">
  <link name="base"><inertial><mass value="2"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="elbow"><inertial><origin xyz="0 0 0.25"/><mass value="1"/>
    <inertia ixx="0.02" iyy="0.02" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="elbow" type="revolute"><parent link="base"/><child link="elbow"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="100" velocity="5"/></joint>
</robot>
"""


def test_a_joint_the_sdf_renames_is_driven_to_the_pose_in_drake(tmp_path: Path) -> None:
    """SDF keeps one namespace per model, so a joint named like a link is written ``elbow_joint``
    (ANYmal C: all 12). Drake's drive targets were looked up by the file's name and fell to 0: the
    SDF ran 1.24 rad from the SRDF pose at RF_KFE in 40 ms while the source held (#38)."""
    urdf = tmp_path / "namesake.urdf"
    urdf.write_text(NAMESAKE)
    dyn = robodesc.check(str(urdf), "sdf", dynamics={"engines": ("drake",), "pose": {"elbow": 0.5}}).dynamics
    assert dyn is not None and dyn.ok, dyn.to_text()
    assert _rows(dyn, "source:hold-fixed") == [Status.PASS]
    hold = next(r for r in dyn.runs if r.file == "sdf" and r.scenario == "hold-fixed")
    source = next(r for r in dyn.runs if r.file == "source" and r.scenario == "hold-fixed")
    # Held near 0.5 (gravity sags it a little), as the source is: not driven back to 0.
    assert hold.final_q["elbow"] == pytest.approx(source.final_q["elbow"], abs=1e-6)
    assert hold.final_q["elbow"] == pytest.approx(0.5, abs=0.05)


HEAVY_BASE = """<robot name="heavy_base">
  <link name="world"/>
  <joint name="weld" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base"><inertial><mass value="4"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="plate"><inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="plate_fix" type="fixed"><parent link="base"/><child link="plate"/><origin xyz="0 0 0.05"/></joint>
  <link name="arm"><inertial><origin xyz="0 0 0.2"/><mass value="1"/>
    <inertia ixx="0.02" iyy="0.02" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="shoulder" type="revolute"><parent link="plate"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="100" velocity="5"/></joint>
</robot>
"""


def test_a_welded_base_fused_into_the_world_body_is_weighed(tmp_path: Path) -> None:
    """A root link named ``world`` (ur5's URDF) welds the base; the MJCF writes it and the links fixed to
    it into <worldbody>, where MuJoCo weighs nothing: the dynamics check counted ur5's MJCF 4 kg light and failed it (exit 1) though the file
    carries every gram (the structural check already leaves those links out)."""
    urdf = tmp_path / "heavy_base.urdf"
    urdf.write_text(HEAVY_BASE)
    dyn = robodesc.check(str(urdf), "mjcf", dynamics=MUJOCO).dynamics
    assert dyn is not None
    masses = {c.element: c for c in dyn.checks if c.name == "mass"}
    assert masses["mujoco/mjcf"].status is Status.PASS, masses["mujoco/mjcf"].message
    assert "5.5 kg" in masses["mujoco/mjcf"].message


def test_the_source_run_carries_the_mjcf_default_armature() -> None:
    """-t mjcf adds a default armature where the source gives none (docs/passes.md); the source's run
    beside the MJCF in MuJoCo is given the same, so the comparison measures the writing. z1's MJCF ran
    1.46 mrad from its source without it and failed (exit 1); 6.8e-6 with it."""
    dyn = robodesc.check(ARM, "mjcf", dynamics=MUJOCO).dynamics
    assert dyn is not None
    added = dyn.info.get("source_armature")
    assert added and all(value > 0 for value in added.values())
    mjcf = next(r for r in dyn.runs if r.file == "mjcf" and r.scenario == "hold-fixed")
    assert mjcf.armature == pytest.approx(added)
    assert _rows(dyn, "source:hold-fixed") == [Status.PASS]
    # A file without armature of its own leaves the source as it is.
    urdf = robodesc.check(ARM, "urdf", dynamics=MUJOCO).dynamics
    assert urdf is not None and "source_armature" not in urdf.info
