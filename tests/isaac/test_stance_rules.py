"""Rules for the default pose and gains added after the corpus runs (issue 29; docs/isaac.md,
"Defaults that stand"): a named pose that is not a stance is not the default, a gravity floor the
motor cannot hold is capped and reported."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import robodesc
from robodesc.emit.common.gains import GRAVITY, HOLD_ERROR, derived_gains
from robodesc.emit.common.stance import choose_stance, stance_defect

_LEG = """
  <joint name="{s}_hip" type="revolute"><parent link="body"/><child link="{s}_thigh"/>
    <origin xyz="0 {y} -0.1"/><axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="{effort}" velocity="10"/></joint>
  <link name="{s}_thigh"><inertial><origin xyz="0 0 -0.15"/><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="{s}_knee" type="revolute"><parent link="{s}_thigh"/><child link="{s}_shin"/>
    <origin xyz="0 0 -0.3"/><axis xyz="0 1 0"/><limit lower="-2" upper="0" effort="{effort}" velocity="10"/></joint>
  <link name="{s}_shin"><inertial><origin xyz="0 0 -0.15"/><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="{s}_ankle" type="revolute"><parent link="{s}_shin"/><child link="{s}_foot"/>
    <origin xyz="0 0 -0.3"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="{effort}" velocity="10"/></joint>
  <link name="{s}_foot"><inertial><mass value="0.5"/>
    <inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.03 0 -0.03"/><geometry><box size="0.2 0.1 0.02"/></geometry></collision></link>
"""


def biped(tmp_path: Path, pose: dict[str, float] | None, effort: float = 100.0) -> Path:
    """A box body on two legs (hip, knee, ankle pitching about y; flat box soles), in a package
    whose ``srdf/`` names ``pose`` as ``half_sitting``."""
    legs = "".join(_LEG.format(s=s, y=y, effort=effort) for s, y in (("l", 0.1), ("r", -0.1)))
    urdf = tmp_path / "biped" / "urdf" / "biped.urdf"
    urdf.parent.mkdir(parents=True)
    urdf.write_text(
        '<robot name="biped"><link name="body"><inertial><mass value="10"/>'
        '<inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>'
        '<collision><geometry><box size="0.3 0.3 0.2"/></geometry></collision></link>' + legs + "</robot>"
    )
    if pose is not None:
        (tmp_path / "biped" / "srdf").mkdir()
        joints = "".join(f'<joint name="{s}_{n}" value="{v}"/>' for s in "lr" for n, v in pose.items())
        (tmp_path / "biped" / "srdf" / "biped.srdf").write_text(
            f'<robot name="biped"><group_state name="half_sitting" group="all">{joints}</group_state></robot>'
        )
    return urdf


def test_named_pose_with_level_soles_is_the_default(tmp_path: Path) -> None:
    robot = robodesc.load(str(biped(tmp_path, {"hip": 0.3, "knee": -0.6, "ankle": 0.3})))
    stance = choose_stance(robot, None)
    assert stance.source == "SRDF group_state 'half_sitting' (biped.srdf)"
    assert stance.skipped is None
    assert stance.positions["l_knee"] == pytest.approx(-0.6)


def test_named_pose_with_tilted_soles_is_not_the_default(tmp_path: Path) -> None:
    """iCub's half_sitting pitches its soles 3.6°: it stood on their edges and tipped over."""
    source = biped(tmp_path, {"hip": 0.3, "knee": -0.6, "ankle": 0.2})
    robot = robodesc.load(str(source))
    stance = choose_stance(robot, None)
    assert stance.source == "zeros"  # a biped gets no heuristic
    assert stance.skipped is not None and "tilted 5.7°" in stance.skipped
    result = robodesc.compile_for_isaac_sim(str(source), tmp_path / "out", fix_base=False)
    warned = [f.message for f in result.findings if f.code == "default-pose-not-stance"]
    assert len(warned) == 1 and "half_sitting" in warned[0]


def test_named_pose_that_lifts_a_foot_is_not_a_stance(tmp_path: Path) -> None:
    robot = robodesc.load(str(biped(tmp_path, None)))
    q = {j.name: 0.0 for j in robot.joints if j.type.dof == 1}
    assert stance_defect(robot, q) is None
    q.update(l_hip=0.5, l_knee=-1.0, l_ankle=0.5)  # the left sole level but 13 cm up
    why = stance_defect(robot, q)
    assert why is not None and "'l_foot' is not among the lowest points" in why


def test_gravity_floor_is_capped_at_what_the_effort_holds(tmp_path: Path) -> None:
    """A weak hip (1 N·m) under a 1.5 kg leg: the floor g·Σm·d / HOLD_ERROR would ask for more torque
    than the motor has at HOLD_ERROR; it is capped at effort / HOLD_ERROR and the joint is flagged."""
    robot = robodesc.load(str(biped(tmp_path, None, effort=1.0)))
    stance = choose_stance(robot, None)
    gains = derived_gains(robot, stance, floating=False)
    hip = gains["l_hip"]
    assert hip.stiffness == pytest.approx(1.0 / HOLD_ERROR)
    assert hip.weak
    # The lever: thigh at 0.15 m, shin 0.45 m, foot 0.6 m (centres of mass from the hip).
    assert hip.gravity_torque == pytest.approx(GRAVITY * (0.15 + 0.45 + 0.5 * 0.6))
    result = robodesc.compile_for_isaac_sim(str(tmp_path / "biped" / "urdf" / "biped.urdf"), tmp_path / "o")
    weak = [f.message for f in result.findings if f.code == "default-gains-weak"]
    assert len(weak) == 1 and "l_hip" in weak[0] and math.isfinite(hip.gravity_torque)


def test_gravity_floor_under_the_effort_is_kept() -> None:
    """With effort to spare the floor is g·Σm·d / HOLD_ERROR, above the effort / 0.2 cap of I_eff ω²."""
    from tests.conftest import EXAMPLES

    robot = robodesc.load(str(EXAMPLES / "urdf" / "gripper_arm.urdf"))
    gains = derived_gains(robot, choose_stance(robot, None), floating=False)
    for g in gains.values():
        assert not g.weak
        if g.gravity_torque:
            assert g.stiffness >= g.gravity_torque / HOLD_ERROR * (1 - 1e-9) or g.capped


def test_a_shins_own_collider_link_is_not_a_leg(tmp_path: Path) -> None:
    """Romeo (laas_small) hangs a collider link off each knee: its chain is the foot's chain cut
    short, so the robot has two legs, not four (and a biped gets no heuristic)."""
    source = biped(tmp_path, None)
    text = source.read_text()
    shins = "".join(
        f'<joint name="{s}_shin_shape" type="fixed"><parent link="{s}_shin"/><child link="{s}_shin_collision"/></joint>'
        f'<link name="{s}_shin_collision"><collision><origin xyz="0 0 -0.15"/>'
        '<geometry><cylinder radius="0.03" length="0.28"/></geometry></collision></link>'
        for s in "lr"
    )
    source.write_text(text.replace("</robot>", shins + "</robot>"))
    robot = robodesc.load(str(source))
    from robodesc.emit.common.stance import complete, find_legs

    legs = find_legs(robot, complete(robot, {}))
    assert [leg.foot for leg in legs] == ["l_foot", "r_foot"]
    assert choose_stance(robot, None).source == "zeros"


def test_a_robot_without_moving_joints_names_no_joint_pattern(tmp_path: Path) -> None:
    """iris_simple (rotors on fixed joints): Isaac Lab refused the module's ``joint_vel`` pattern
    ``.*``, which matched no joint."""
    import runpy

    urdf = tmp_path / "rigid.urdf"
    urdf.write_text(
        '<robot name="rigid"><link name="body"><inertial><mass value="1"/>'
        '<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
        '<collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>'
        '<joint name="rotor_joint" type="fixed"><parent link="body"/><child link="rotor"/></joint>'
        '<link name="rotor"><inertial><mass value="0.1"/>'
        '<inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>'
    )
    robodesc.compile_for_isaac_sim(str(urdf), tmp_path / "out", fix_base=False)
    module = runpy.run_path(str(next((tmp_path / "out").glob("*_isaaclab.py"))))["ROBOT"]
    assert module["init_state"]["joint_pos"] == {} and module["init_state"]["joint_vel"] == {}


def test_no_dead_actuator_on_gram_links() -> None:
    """Links of 1 g (Allegro's URDF has none: robodesc gives each 1 g) once derived kp near 0. The
    floor is the effort at 1 rad, bounded by a 20 Hz loop on the inertia it moves; a stiffness that
    cannot lift the links is named."""
    from robodesc.ir import Inertia, Inertial, Limit, Pose
    from robodesc.ir.diagnostics import Findings
    from tests.passes.pass_helpers import chain

    robot = chain("palm", "f1", "f2", "f3")
    for link in robot.links:
        link.inertial = Inertial(mass=1e-3, inertia=Inertia(1e-6, 0, 0, 1e-6, 0, 1e-6))
    for joint in robot.joints:
        joint.axis = (1.0, 0.0, 0.0)
        joint.armature = 5e-4
    gains = derived_gains(robot, choose_stance(robot, None), floating=False)
    for g in gains.values():
        assert g.stiffness == pytest.approx(min(10.0 / 1.0, g.inertia * (2 * math.pi * 20) ** 2))
        assert g.stiffness > 1.0 and not g.dead
    heavy = chain("base", "arm")
    heavy.joints[0].axis = (1.0, 0.0, 0.0)
    heavy.joints[0].limit = Limit(lower=-1.0, upper=1.0, effort=100.0, velocity=1.0)
    heavy.links[1].inertial = Inertial(
        mass=5.0, origin=Pose(xyz=(0.0, 0.5, 0.0)), inertia=Inertia(0.1, 0, 0, 0.1, 0, 0.1)
    )
    weak = derived_gains(heavy, choose_stance(heavy, None), floating=False, stiffness={"j0": 1.0})
    assert weak["j0"].dead  # 1 N·m/rad over 2 rad cannot lift 5 kg at 0.5 m (24.5 N·m)
    findings = Findings()
    from robodesc.emit.common.gains import fill_default_gains
    from robodesc.emit.mjcf.options import MjcfOptions

    fill_default_gains(
        heavy, MjcfOptions(stiffness=1.0), {"stiffness"}, choose_stance(heavy, None), False, findings, "t"
    )
    dead = [f for f in findings.items if f.code == "default-gains-dead"]
    assert len(dead) == 1 and "j0" in dead[0].message


def test_a_welded_robot_below_the_ground_is_raised(tmp_path: Path) -> None:
    """Isaac Lab scenes have a ground at z = 0: a welded robot with a collider below it at its start
    pose (Allegro's thumb, 4.6 cm) is raised until none is, 5 mm above; one above it stays put."""
    from robodesc.emit.isaac.defaults import apply_defaults
    from robodesc.emit.isaac.settings import IsaacSettings
    from robodesc.ir.diagnostics import Findings

    urdf = tmp_path / "hand.urdf"
    urdf.write_text(
        '<robot name="hand"><link name="palm"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
        '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
        "</link></robot>"
    )
    robot = robodesc.load(str(urdf))
    settings = IsaacSettings(fix_base=True)
    findings = Findings()
    apply_defaults(robot, settings, set(), findings)
    assert settings.init_pos[2] == pytest.approx(0.055)
    assert [f.code for f in findings.items if f.code == "isaac-welded-raised"] == ["isaac-welded-raised"]
    settings = IsaacSettings(fix_base=True, init_pos=(0.0, 0.0, 1.0))
    apply_defaults(robot, settings, {"init_pos"}, Findings())
    assert settings.init_pos[2] == 1.0


def test_anymal_c_hind_knees_mirror_the_front_ones() -> None:
    """The legged heuristic bends each knee as its leg is built: ANYmal C's hind legs are its front
    ones turned half a turn, and its SRDF and Isaac Lab's own config bend their knees forward."""
    from robodesc.emit.common.stance import legged_pose
    from robodesc.ir.rigid import link_frames
    from robodesc.validation.corpora import example_robot_data_root

    root = example_robot_data_root()
    if root is None:
        pytest.skip("example-robot-data is not installed (the test extra)")
    robot = robodesc.load(
        f"{root}/robots/anymal_c_simple_description/urdf/anymal.urdf", package_paths={"example-robot-data": root}
    )
    found = legged_pose(robot)
    assert found is not None
    q, legs = found
    frames = link_frames(robot, q)
    ahead = {}
    for leg in legs:
        knee = robot.joint(next(j for j in leg.joints if j.endswith("KFE")))
        ahead[leg.foot] = frames[knee.child].translation[0] > frames[leg.foot].translation[0]
    assert ahead == {"LF_FOOT": False, "RF_FOOT": False, "LH_FOOT": True, "RH_FOOT": True}
