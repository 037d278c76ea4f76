"""PhysX as an engine of ``validate --dynamics`` (#38): ovphysx reads the USD robodesc wrote, on CPU,
in its own interpreter. Skipped, with the reason, where no interpreter has ovphysx (build the
consumer tier's with tests/consumers/run.sh, or set ROBODESC_PHYSX_PYTHON). Numbers are compared
with MuJoCo's within the agreement thresholds; nothing here is timed."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from pxr import Sdf

import robodesc
from robodesc.validation.dynamics import DynamicsOptions, physx_run, run_dynamics
from robodesc.validation.dynamics.result import DynamicsReport
from robodesc.validation.dynamics.run import folder_files, joining
from robodesc.validation.dynamics.scenarios import Thresholds, make_setup
from robodesc.validation.dynamics.verdict import judge
from robodesc.validation.physx_python import physx_python
from robodesc.validation.report import Status

from ..conftest import EXAMPLES
from .test_dynamics_saturation import HOLD, KD, KP, _pendulum

needs_physx = pytest.mark.skipif(
    physx_python() is None, reason="no interpreter with ovphysx (tests/consumers/run.sh builds one)"
)
TH = Thresholds()


def _runs(dyn: robodesc.validation.dynamics.DynamicsReport) -> dict[tuple[str, str], robodesc.validation.dynamics.Run]:
    return {(r.engine, r.scenario): r for r in dyn.runs if r.file != "source"}


@needs_physx
def test_the_quadruped_holds_and_lands_in_physx_as_in_mujoco() -> None:
    # Soft constant drives (-t usd's default before issue 38), so the gravity load dominates the peak
    # effort; with the stiffer derived gains the first steps' transient does (7 % apart at a hip).
    gains = {"stiffness": 100.0, "damping": 1.0}
    opts = {"engines": ("mujoco", "physx"), **gains}
    dyn = robodesc.check(str(EXAMPLES / "quadruped.yaml"), "usd", dynamics=opts, **gains).dynamics
    assert dyn is not None and dyn.ok, dyn.to_text()
    runs = _runs(dyn)
    hold_m, hold_p = runs[("mujoco", "hold-fixed")], runs[("physx", "hold-fixed")]
    assert hold_p.drift == pytest.approx(hold_m.drift, abs=TH.hold_agree)
    for joint, q in hold_m.final_q.items():
        assert hold_p.final_q[joint] == pytest.approx(q, abs=TH.hold_agree), joint
        # The same gravity load on the same drives: the same effort, within 3 %.
        assert hold_p.peak_effort[joint] == pytest.approx(hold_m.peak_effort[joint], rel=0.03, abs=0.02), joint
    drop_m, drop_p = runs[("mujoco", "drop")], runs[("physx", "drop")]
    assert drop_p.height == pytest.approx(drop_m.height, abs=TH.drop_height_agree)
    assert abs((drop_p.tilt or 0.0) - (drop_m.tilt or 0.0)) < TH.drop_tilt_agree
    assert math.degrees(drop_p.tilt or 0.0) < 5.0  # lands on its feet
    # Slide with PhysX's default friction (the source gives none): sticks and slides as tan says.
    slide = runs[("physx", "slide")]
    assert (
        slide.mu == pytest.approx(0.5) and (slide.stick or 1.0) < TH.stick_max and (slide.slide or 0.0) > TH.slide_min
    )
    assert [c.status for c in dyn.checks if c.name == "agree:drop"] == [Status.PASS]


@needs_physx
def test_the_arm_in_the_isaac_folder_holds_in_physx_as_in_mujoco() -> None:
    """The Isaac folder's USD, its derived gains as written: PhysX joins the default engines."""
    pose = {"shoulder_pitch": 0.8, "elbow": 0.5}
    dyn = robodesc.check(str(EXAMPLES / "urdf/gripper_arm.urdf"), "isaac", dynamics={"pose": pose}).dynamics
    assert dyn is not None and dyn.ok, dyn.to_text()
    runs = _runs(dyn)
    assert {e for e, _ in runs} == {"mujoco", "drake", "physx"}
    hold_m, hold_p = runs[("mujoco", "hold-fixed")], runs[("physx", "hold-fixed")]
    for joint, q in hold_m.final_q.items():
        assert hold_p.final_q[joint] == pytest.approx(q, abs=TH.hold_agree), joint


@needs_physx
def test_the_hold_effort_of_a_horizontal_arm_is_m_g_l_in_physx_and_the_file_is_untouched(tmp_path: Path) -> None:
    """PhysX reads the USD as written: the scenario's weld, gravity and targets go in a layer over
    it and through ovphysx's write API, so the file's bytes are the same after the run."""
    urdf = _pendulum(tmp_path, effort=2 * HOLD)
    usd = tmp_path / "pendulum.usda"
    robodesc.compile_to(str(urdf), "usd", str(usd), stiffness=KP, damping=KD)
    before = usd.read_bytes()
    robot = robodesc.load(str(urdf))
    options = DynamicsOptions(engines=("physx",), pose={"hinge": 0.0}, stiffness=KP, damping=KD)
    dyn = run_dynamics(robot, {"usd": str(usd)}, options)
    assert usd.read_bytes() == before
    (hold,) = [r for r in dyn.runs if r.scenario == "hold-fixed"]
    assert hold.engine == "physx" and hold.peak_effort["hinge"] == pytest.approx(HOLD, rel=0.02)
    assert hold.saturation["hinge"] == pytest.approx(0.5, rel=0.02)
    assert hold.drift == pytest.approx(HOLD / KP * (1.0 - math.exp(-KP / KD)), rel=0.05)


def test_the_isaac_folders_usd_is_what_physx_reads(tmp_path: Path) -> None:
    folder = tmp_path / "robot"
    folder.mkdir()
    (folder / "robot.usda").write_text("#usda 1.0\n")
    (folder / "robot.urdf").write_text("<robot/>")
    assert folder_files(str(folder)) == {"usd": str(folder / "robot.usda")}
    assert joining(folder_files(str(folder))) == ("physx",) and joining({"urdf": "x.urdf"}) == ()
    (folder / "other.usd").write_text("")
    assert folder_files(str(folder)) == {}  # two USD files: which robot is meant is not known


def test_without_an_interpreter_physx_is_a_skip_row_saying_how_to_get_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("ROBODESC_CONSUMERS_DIR", str(tmp_path))
    monkeypatch.delenv("ROBODESC_PHYSX_PYTHON", raising=False)
    monkeypatch.setattr("robodesc.validation.physx_python.importlib.util.find_spec", lambda name: None)
    dyn = robodesc.check(
        str(EXAMPLES / "urdf/gripper_arm.urdf"), "usd", dynamics={"engines": ("mujoco", "physx")}
    ).dynamics
    assert dyn is not None and dyn.ok
    (row,) = [c for c in dyn.checks if c.element == "physx/usd"]
    assert row.status is Status.SKIP and "robodesc[physx]" in row.message and "tests/consumers/run.sh" in row.message
    assert {r.engine for r in dyn.runs} == {"mujoco"}


def test_feet_friction_is_read_inside_instances(tmp_path: Path) -> None:
    # Isaac Sim 6's importer instances a mesh collider; the worker (pxr only, here usd-core) must
    # look inside the instance for its shapes, or the slide has no friction to test (solo12).
    from pxr import Usd, UsdPhysics

    from robodesc.validation.dynamics import physx_worker

    (tmp_path / "mesh.usda").write_text(
        '#usda 1.0\n(defaultPrim = "shape")\ndef Xform "shape" {\n def Cube "box" (prepend apiSchemas = '
        '["PhysicsCollisionAPI", "MaterialBindingAPI"]) {\n  rel material:binding:physics = </shape/grip>\n }\n'
        ' def Material "grip" (prepend apiSchemas = ["PhysicsMaterialAPI"]) {\n'
        "  float physics:dynamicFriction = 0.9\n }\n}\n"
    )
    (tmp_path / "robot.usda").write_text(
        '#usda 1.0\ndef Xform "robot" {\n def Xform "foot" (prepend apiSchemas = ["PhysicsRigidBodyAPI"]) {\n'
        '  def Xform "collider" (instanceable = true\n   prepend references = @./mesh.usda@) {}\n }\n}\n'
    )
    stage = Usd.Stage.Open(str(tmp_path / "robot.usda"))
    foot = stage.GetPrimAtPath("/robot/foot")
    assert foot.HasAPI(UsdPhysics.RigidBodyAPI)
    assert physx_worker._feet_mu([foot]) == pytest.approx(0.9)


def test_joints_are_found_by_the_names_a_file_uses(tmp_path: Path) -> None:
    # Isaac Sim 6's import names Spirit's joint "0" as the Isaac URDF does, "a0", with no displayName.
    from robodesc.validation.dynamics import physx_worker

    (tmp_path / "robot.usda").write_text(
        '#usda 1.0\ndef Xform "robot" {\n def Xform "body" (prepend apiSchemas = ["PhysicsRigidBodyAPI"]) {}\n'
        ' def Xform "leg" (prepend apiSchemas = ["PhysicsRigidBodyAPI"]) {}\n'
        ' def PhysicsRevoluteJoint "a0" {\n  rel physics:body0 = </robot/body>\n  rel physics:body1 = </robot/leg>\n }\n'
        ' def PhysicsRevoluteJoint "knee" (displayName = "knee joint") {\n'
        "  rel physics:body0 = </robot/body>\n  rel physics:body1 = </robot/leg>\n }\n}\n"
    )
    info = physx_worker._inspect(str(tmp_path / "robot.usda"), "body", (), {"a0": "0", "knee": "other"})
    # displayName first (robodesc's USD), then the file's name mapped, then the name itself.
    assert info["joints"] == {"/robot/a0": ("0", "angular"), "/robot/knee": ("knee joint", "angular")}
    assert info["root"] == "/robot/body"


def test_feet_friction_skips_nested_bodies_without_stopping(tmp_path: Path) -> None:
    # Isaac Sim 6's importer nests a child link before its parent's collider: the parent's collider
    # still counts, the child's belongs to the child.
    from pxr import Usd

    from robodesc.validation.dynamics import physx_worker

    grip = ' def Material "grip" (prepend apiSchemas = ["PhysicsMaterialAPI"]) {\n  float physics:dynamicFriction = 0.9\n }\n'
    (tmp_path / "robot.usda").write_text(
        '#usda 1.0\ndef Xform "robot" {\n'
        + grip
        + ' def Xform "thigh" (prepend apiSchemas = ["PhysicsRigidBodyAPI"]) {\n'
        '  def Xform "shin" (prepend apiSchemas = ["PhysicsRigidBodyAPI"]) {\n   def Cube "c" (prepend apiSchemas = '
        '["PhysicsCollisionAPI"]) {}\n  }\n  def Cube "collider" (prepend apiSchemas = ["PhysicsCollisionAPI", '
        '"MaterialBindingAPI"]) {\n   rel material:binding:physics = </robot/grip>\n  }\n }\n}\n'
    )
    stage = Usd.Stage.Open(str(tmp_path / "robot.usda"))
    assert physx_worker._feet_mu([stage.GetPrimAtPath("/robot/thigh")]) == pytest.approx(0.9)
    assert physx_worker._feet_mu([stage.GetPrimAtPath("/robot/thigh/shin")]) == pytest.approx(0.5)


def _tiago_left_arm(folder: Path) -> Path:
    """example-robot-data's tiago_pro cut to its left arm and gripper (a linkage of five mimic
    followers, gearings ±1, on 16-34 g links), without meshes."""
    from robodesc.validation.corpora import example_robot_data_root

    root = example_robot_data_root()
    source = Path(root or "") / "robots/tiago_pro_description/robots/tiago_pro.urdf"
    if root is None or not source.is_file():
        pytest.skip("example-robot-data's tiago_pro is not installed")
    robot = ET.parse(source).getroot()
    arm = ET.Element("robot", name="tiago_pro_left_arm")
    keep = ("arm_left", "gripper_left")
    for link in robot.findall("link"):
        if link.get("name", "").startswith(keep):
            for shape in [*link.findall("visual"), *link.findall("collision")]:
                link.remove(shape)
            arm.append(link)
    for joint in robot.findall("joint"):
        ends = [joint.find(end) for end in ("parent", "child")]
        if all(e is not None and e.get("link", "").startswith(keep) for e in ends):
            arm.append(joint)
    path = folder / "tiago_pro_left_arm.urdf"
    ET.ElementTree(arm).write(path)
    return path


def _put_follower_velocity_limits_back(usd: Path, robot: robodesc.Robot) -> None:
    """The file as robodesc wrote it before: 2 rad/s on every follower, in both vocabularies."""
    from pxr import Usd

    stage = Usd.Stage.Open(str(usd))
    for joint in robot.joints:
        if joint.mimic is None:
            continue
        prim = next(p for p in stage.Traverse() if p.GetName() == joint.name)
        prim.AddAppliedSchema("PhysxJointAxisAPI:angular")
        prim.AddAppliedSchema("NewtonJointAPI")
        for name in ("physxJointAxis:angular:maxJointVelocity", "newton:velocityLimit"):
            prim.CreateAttribute(name, Sdf.ValueTypeNames.Float).Set(math.degrees(2.0))
    stage.GetRootLayer().Save()


@needs_physx
def test_tiago_pros_gripper_holds_in_physx_and_its_old_file_blows_up_as_a_run_failure(tmp_path: Path) -> None:
    """tiago_pro ran away in PhysX (#38: final joints 4.85e27 rad apart). Two causes together: its
    mimic followers carried velocity limits, and the scenario posed the leader (0.15 rad) but left
    the followers at 0, so the mimic constraints started violated. Now the followers carry no limit
    and start where their leader puts them: PhysX holds the arm as MuJoCo does. The old file from
    the old start blows up, and that is a ``run`` failure of PhysX, not a disagreement."""
    arm = _tiago_left_arm(tmp_path)
    pose = {"gripper_left_finger_joint": 0.15}
    opts = {"engines": ("mujoco", "physx"), "pose": pose, "duration": 0.3}
    dyn = robodesc.check(str(arm), "usd", dynamics=opts).dynamics
    assert dyn is not None and dyn.ok, dyn.to_text()
    runs = _runs(dyn)
    hold_m, hold_p = runs[("mujoco", "hold-fixed")], runs[("physx", "hold-fixed")]
    for joint, q in hold_m.final_q.items():
        assert hold_p.final_q[joint] == pytest.approx(q, abs=TH.hold_agree), joint
    robot = robodesc.load(str(arm))
    usd = tmp_path / "old.usda"
    robodesc.compile_to(str(arm), "usd", str(usd), validate=False)
    _put_follower_velocity_limits_back(usd, robot)
    setup = make_setup(robot, DynamicsOptions(pose=pose, duration=0.3, fix_base=True))
    setup.followers = {}  # the old start: followers at the file's 0
    old = physx_run.run_file(robot, str(usd), "usd", setup, DynamicsOptions(), ("hold-fixed",))
    assert isinstance(old, list)
    report = DynamicsReport("tiago_pro_left_arm", runs=old)
    judge(report, setup, TH)
    assert not old[0].ok and "blew up" in old[0].error, old[0].error
    assert [c.status for c in report.checks if c.name == "run"] == [Status.FAIL]
