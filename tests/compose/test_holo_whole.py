"""The whole HoloScript language: every joint spelling, scenes, nesting, templates as defaults.

The fixtures are written for robodesc, modelled on the constructs of HoloScript's public examples
(brianonbased-dev/HoloScript); HoloScript's own files are not copied into this repository (see
docs/compositions.md). ``test_holoscript_checkout`` reads a real checkout when
``ROBODESC_HOLOSCRIPT_REPO`` points at one.
"""

from __future__ import annotations

import math
import os
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import robodesc
from robodesc.frontends.holo.lower import HoloResult, load_holo, load_holo_text
from robodesc.frontends.holo.parser import MAX_DEPTH, Expr, parse
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.ir.diagnostics import Findings, ParseError
from robodesc.ir.model import JointType, Robot
from robodesc.ir.transforms import forward_kinematics

FIXTURES = Path(__file__).parent / "holo"


def load(text: str) -> HoloResult:
    return load_holo_text(text, "t.holo", LoadOptions())


def codes(result: HoloResult) -> list[str]:
    return [f.code for f in result.findings]


Movable = tuple[JointType, tuple[float, ...] | None, float | None, float | None]


def movable(robot: Robot) -> dict[str, Movable]:
    out: dict[str, Movable] = {}
    for j in robot.joints:
        if j.type is JointType.FIXED:
            continue
        lim = j.limit
        out[j.name] = (
            j.type,
            None if j.axis is None else tuple(round(c, 9) for c in j.axis),
            None if lim is None else lim.lower,
            None if lim is None else lim.upper,
        )
    return out


def descendants(robot: Robot, joint_name: str) -> set[str]:
    child = robot.joint(joint_name).child
    out = {child}
    changed = True
    while changed:
        changed = False
        for j in robot.joints:
            if j.parent in out and j.child not in out:
                out.add(j.child)
                changed = True
    return out


def assert_each_joint_moves_its_children(robot: Robot) -> None:
    """Turning a joint moves (or turns) its child link and every link below it, and nothing else."""
    rest = forward_kinematics(robot)
    for j in robot.joints:
        if j.type is JointType.FIXED:
            continue
        q = 0.3 if j.limit is None or j.limit.upper is None else 0.5 * (j.limit.upper or 0.3) or 0.3
        moved = forward_kinematics(robot, {j.name: q})
        below = descendants(robot, j.name)
        for name, pose in moved.items():
            changed = not np.allclose(pose, rest[name], atol=1e-12)
            if name in below:
                assert changed, f"{j.name} does not move {name}"
            else:
                assert not changed, f"{j.name} moves {name}, which is not below it"


# ---- one file per joint spelling ------------------------------------------------------------
EXPECTED = {
    # nesting + @joint(...) with [min, max] (degrees), header traits, scene wrapper
    "nested_call_traits.holo": {
        "Turret_joint": (JointType.REVOLUTE, (0.0, 0.0, 1.0), -math.pi, math.pi),
        "Boom_joint": (JointType.REVOLUTE, (0.0, 1.0, 0.0), -math.pi / 2, math.pi / 2),
        "Stick_joint": (JointType.PRISMATIC, (1.0, 0.0, 0.0), 0.0, 0.3),
    },
    # @joint_revolute / @joint_prismatic with joint_* properties
    "joint_traits_props.holo": {
        "Yaw_joint": (JointType.REVOLUTE, (0.0, 0.0, 1.0), -2.094395, 2.094395),  # radians as written
        "Lift_joint": (JointType.PRISMATIC, (0.0, 0.0, 1.0), 0.0, 0.25),
    },
    # top-level joint blocks with parent / child, and one with neither
    "joint_blocks.holo": {
        "Hip": (JointType.REVOLUTE, (0.0, 1.0, 0.0), -math.radians(45), math.radians(90)),
        "Knee": (JointType.REVOLUTE, (0.0, 1.0, 0.0), 0.0, math.radians(150)),
        "Ankle": (JointType.REVOLUTE, (1.0, 0.0, 0.0), -math.radians(30), math.radians(30)),
    },
    # behavior "RevoluteJoint" in a template, connectedBody, templates as defaults (radians)
    "behaviors_templates.holo": {
        "J1_joint": (JointType.REVOLUTE, (0.0, 0.0, 1.0), -2.96706, 2.96706),
        "J2_joint": (JointType.REVOLUTE, (0.0, 1.0, 0.0), -1.745329, 1.745329),
        "Finger_joint": (JointType.PRISMATIC, (1.0, 0.0, 0.0), 0.0, 0.04),
    },
}


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_joints_arrive_as_declared(name: str) -> None:
    result = load_holo(str(FIXTURES / name), LoadOptions())
    got = movable(result.robot)
    want = EXPECTED[name]
    assert set(got) == set(want)
    for joint, (jtype, axis, lower, upper) in want.items():
        g = got[joint]
        assert g[0] is jtype, joint
        assert g[1] == pytest.approx(axis), joint
        assert g[2] == pytest.approx(lower), joint
        assert g[3] == pytest.approx(upper), joint
    assert_each_joint_moves_its_children(result.robot)


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_every_target_compiles_with_the_declared_joints(name: str, tmp_path: Path) -> None:
    path = str(FIXTURES / name)
    urdf = robodesc.compile_to_urdf(path, tmp_path / "r.urdf")
    root = ET.fromstring(urdf.text or "")
    declared = EXPECTED[name]
    written = {j.get("name"): j for j in root.iter("joint") if j.get("type") != "fixed"}
    assert set(written) == set(declared)
    for joint, (_, axis, lower, upper) in declared.items():
        el = written[joint]
        xyz = [float(v) for v in el.find("axis").get("xyz").split()]  # type: ignore[union-attr]
        assert xyz == pytest.approx(axis)
        lim = el.find("limit")
        assert lim is not None
        assert float(lim.get("lower")) == pytest.approx(lower)  # type: ignore[arg-type]
        assert float(lim.get("upper")) == pytest.approx(upper)  # type: ignore[arg-type]
    sdf = robodesc.compile_to_sdf(path, tmp_path / "r.sdf")
    sdf_movable = [j for j in ET.fromstring(sdf.text or "").iter("joint") if j.get("type") != "fixed"]
    assert len(sdf_movable) == len(declared)
    robodesc.compile_to_usd(path, tmp_path / "r.usda")
    usd_text = (tmp_path / "r.usda").read_text()
    assert usd_text.count("PhysicsRevoluteJoint") + usd_text.count("PhysicsPrismaticJoint") >= len(declared)
    isaac = robodesc.compile_for_isaac_sim(path, tmp_path / "isaac")
    assert isaac.files


def test_template_values_are_defaults_not_contradictions() -> None:
    result = load_holo(str(FIXTURES / "behaviors_templates.holo"), LoadOptions())
    # The template says @physics { mass: 1.0 }; J2 says physics: { mass: 2.0 }: the object wins.
    j2 = result.robot.link("J2")
    assert j2.inertial is not None and j2.inertial.mass == pytest.approx(2.0)
    j1 = result.robot.link("J1")
    assert j1.inertial is not None and j1.inertial.mass == pytest.approx(1.0)
    overrides = [f for f in result.findings if f.code == "template-override"]
    assert overrides and all(f.severity.name == "INFO" for f in overrides)


def test_duplicate_names_get_unique_links_and_a_map() -> None:
    result = load("""composition "Two" {
      object "Base" { @physics(type: "static", mass: 5) geometry: "box" scale: 0.2 }
      group "Left" { object "Finger" { @joint(type: "prismatic", connectedBody: "Base", axis: [1, 0, 0], limits: [0, 0.02]) geometry: "box" scale: 0.02 mass: 0.1 } }
      group "Right" { object "Finger" { @joint(type: "prismatic", connectedBody: "Base", axis: [-1, 0, 0], limits: [0, 0.02]) geometry: "box" scale: 0.02 mass: 0.1 } }
    }""")
    names = {link.name for link in result.robot.links}
    assert names == {"Base", "Finger", "Right_Finger"}
    renamed = [f.message for f in result.findings if f.code == "renamed-duplicate"]
    assert len(renamed) == 1 and "'Right_Finger'" in renamed[0]
    assert len(movable(result.robot)) == 2


def test_scene_without_joints_says_it_holds_no_robot() -> None:
    with pytest.raises(ParseError, match=r"^t\.holo:1:1: composition 'Park': the composition holds no robot"):
        load('composition "Park" { scene "Main" { object "Tree" { geometry: "cone" scale: [1, 3, 1] } } }')


def test_non_robot_blocks_are_skipped_with_info() -> None:
    result = load_holo(str(FIXTURES / "nested_call_traits.holo"), LoadOptions())
    skipped = [f for f in result.findings if f.code == "ignored-block"]
    kinds = " ".join(f.message for f in skipped)
    for kind in ("'logic'", "'audio'", "'post_processing'", "'ui'", "'state'"):
        assert kind in kinds
    assert all(f.severity.name == "INFO" for f in skipped)


def test_robot_block_with_joints_block() -> None:
    result = load("""robot arm {
      base { mass: 2 geometry: "box" scale: 0.2 }
      joints {
        swing { type: revolute, axis: "z", limits: [-1.5707963, 1.5707963] }  // radians, as the robotics plugin reads them
        lift { type: prismatic, axis: "x", limits: [0, 0.1] }
      }
    }""")
    got = movable(result.robot)
    jtype, axis, lower, upper = got["swing"]
    assert (jtype, axis) == (JointType.REVOLUTE, (0.0, 0.0, 1.0))
    assert (lower, upper) == pytest.approx((-math.pi / 2, math.pi / 2))
    assert got["lift"][0] is JointType.PRISMATIC
    assert result.robot.joint("lift").parent == "swing_link"
    assert "empty-link" in codes(result) and "default-mass" in codes(result)
    assert_each_joint_moves_its_children(result.robot)


def test_substituted_geometry_is_reported() -> None:
    result = load("""composition "Ring" {
      object "Base" { @physics { type: "static" mass: 1 } geometry: "box" scale: 0.1 }
      object "Wheel" { @joint { type: "continuous" connectedBody: "Base" axis: [0, 1, 0] } geometry: "torus" scale: [0.3, 0.05, 0.3] mass: 1 }
    }""")
    assert "substituted-geometry" in codes(result)
    assert result.robot.joint("Wheel_joint").type is JointType.CONTINUOUS


def test_radian_looking_limits_are_read_in_degrees_and_reported() -> None:
    # @joint's unit is degrees (HoloScript's URDF compiler multiplies its limits by pi/180).
    result = load("""composition "R" {
      object "Base" { @physics { type: "static" mass: 1 } geometry: "box" scale: 0.1 }
      object "Arm" { geometry: "box" scale: 0.1 mass: 1
        @joint { jointType: "hinge", connectedBody: "Base", axis: [0, 0, 1], limits: { min: -3.14159, max: 3.14159 } } }
    }""")
    lim = result.robot.joint("Arm_joint").limit
    assert lim is not None and lim.upper == pytest.approx(math.radians(3.14159))
    assert "radian-looking-limits" in codes(result)


# Angles in the robotics plugin's notations (behavior blocks, @joint_revolute with joint_limits, the
# joints of a robot block) are radians, as HoloScript's examples write them: a shoulder written
# [-3.14159, 3.14159] turns half a turn each way, not 3 degrees.
RADIAN_NOTATIONS = {
    "behavior": """object "Arm" { geometry: "box" scale: 0.1 mass: 1 parent: "Base"
        behavior "RevoluteJoint" { axis: [0, 0, 1], lowerLimit: LO, upperLimit: HI } }""",
    "joint_revolute": """object "Arm" { @joint_revolute joint_parent: "Base" joint_axis: [0, 0, 1]
        joint_limits: [LO, HI] geometry: "box" scale: 0.1 mass: 1 }""",
    "robot block": """robot arm { joints { Arm_joint { type: revolute, parent: "Base", axis: "z",
        limits: [LO, HI] } } }""",
}


@pytest.mark.parametrize("notation", sorted(RADIAN_NOTATIONS))
def test_robotics_plugin_notations_read_angles_in_radians(notation: str) -> None:
    def read(lo: float, hi: float) -> HoloResult:
        body = RADIAN_NOTATIONS[notation].replace("LO", repr(lo)).replace("HI", repr(hi))
        return load(
            'composition "R" { object "Base" { @physics { type: "static" mass: 1 } geometry: "box" scale: 0.1 }\n'
            + body
            + "\n}"
        )

    result = read(-2.3562, 3.14159)
    lim = result.robot.joint("Arm_joint").limit
    assert lim is not None and (lim.lower, lim.upper) == pytest.approx((-2.3562, 3.14159))
    assert not {"radian-looking-limits", "degree-looking-limits"} & set(codes(result))
    # Degrees written where radians are read: kept as written (a notation has one unit), reported
    # with the radian values to write.
    result = read(-170.0, 170.0)
    lim = result.robot.joint("Arm_joint").limit
    assert lim is not None and lim.upper == pytest.approx(170.0)
    warned = [f for f in result.findings if f.code == "degree-looking-limits"]
    assert warned and "2.967" in warned[0].message


def test_robotics_plugin_inertia_list_and_viscous_friction_are_read() -> None:
    # The robotics plugin's object: `inertia: [ixx, iyy, izz(, ixy, ixz, iyz)]` beside `mass`, and
    # joint_viscous_friction (PhysX's viscous coefficient, URDF's damping).
    result = load("""composition "R" {
      object "Base" { @static geometry: "box" scale: 0.1 mass: 1 }
      object "Arm" { @joint_revolute joint_parent: "Base" joint_axis: [0, 1, 0] joint_limits: [-1, 1]
        joint_viscous_friction: 0.01 joint_friction: 0.05 max_effort: 7
        geometry: "cylinder" radius: 0.05 length: 0.3 mass: 1.0 inertia: [0.01, 0.01, 0.001, 0.0001, 0, 0] }
      object "Tip" { @joint_revolute joint_parent: "Arm" joint_axis: [0, 0, 1] joint_limits: [-1, 1]
        geometry: "sphere" radius: 0.03 mass: 0.2 inertia: [0.003, 0.004, 0.005] }
    }""")
    arm = result.robot.link("Arm").inertial
    assert arm is not None and arm.inertia is not None
    i = arm.inertia
    assert (i.ixx, i.iyy, i.izz, i.ixy, i.ixz, i.iyz) == pytest.approx((0.01, 0.01, 0.001, 0.0001, 0, 0))
    tip = result.robot.link("Tip").inertial
    assert tip is not None and tip.inertia is not None
    assert (tip.inertia.ixx, tip.inertia.iyy, tip.inertia.izz) == pytest.approx((0.003, 0.004, 0.005))
    joint = result.robot.joint("Arm_joint")
    assert joint.dynamics is not None and joint.dynamics.damping == pytest.approx(0.01)
    assert joint.dynamics.friction == pytest.approx(0.05)
    assert joint.limit is not None and joint.limit.effort == pytest.approx(7)
    ignored = {f.message for f in result.findings if f.code == "ignored-property"}
    assert not any(k in m for m in ignored for k in ("inertia", "viscous", "max_effort")), ignored
    with pytest.raises(ParseError, match="inertia"):
        load("""composition "R" { object "Base" { @static geometry: "box" scale: 0.1 mass: 1 }
          object "Arm" { @joint_revolute joint_parent: "Base" joint_limits: [-1, 1] joint_axis: [0, 0, 1]
            geometry: "box" scale: 0.1 mass: 1 inertia: [0.01, 0.02] } }""")


def test_mass_without_shape_is_kept_on_a_moving_body() -> None:
    # HoloScript's isaac-lab bridge: `robot spot { base_link { mass: 12 } joints { ... } }`. A moving
    # body keeps its stated mass (not the 1 kg default) with a 1 m cube's inertia; a fixed body
    # without shape drops it, with one warning (not also "has no mass").
    result = load("""composition "R" {
      object "Base" { @static mass: 5 }
      object "Arm" { @joint_revolute joint_parent: "Base" joint_axis: [0, 0, 1] joint_limits: [-1, 1] mass: 12 }
    }""")
    arm = result.robot.link("Arm").inertial
    assert arm is not None and arm.mass == 12 and arm.inertia is not None
    assert arm.inertia.ixx == pytest.approx(2.0)
    assert result.robot.link("Base").inertial is None
    by_code = {f.code: f.element for f in result.findings}
    assert "default-mass" not in by_code
    assert [f.element for f in result.findings if f.code == "mass-without-shape"] == ["object 'Base'", "object 'Arm'"]
    assert not [f for f in result.findings if f.code == "no-mass" and f.element == "object 'Base'"]
    # The base of a floating robot moves too: it keeps its mass.
    result = load("""robot spot { base_link { mass: 12 }
      joints { hip { type: revolute, axis: "y", limits: [-1.57, 1.57] } } }""")
    base = result.robot.link("base_link").inertial
    assert base is not None and base.mass == 12 and base.inertia is not None


def test_values_that_are_expressions_are_kept_as_text() -> None:
    doc = parse('object "A" { speed: rate * 2, on_click: () => { go() }, color: #ff8800 }', "t.holo")
    props = doc.body.children[0].props
    assert props["speed"].data == Expr("rate * 2")
    assert props["color"].data == "#ff8800"
    assert doc.body.children[0].name_loc.line == 1


def test_deep_nesting_is_one_clear_error() -> None:
    lists = "[" * 100_000 + "]" * 100_000
    with pytest.raises(ParseError) as info:
        parse('object "A" { x: ' + lists + " }", "deep.holo")
    assert f"nesting deeper than {MAX_DEPTH} levels" in str(info.value)
    assert str(info.value).startswith("deep.holo:1:")
    blocks = 'object "A" { ' * 100_000 + "}" * 100_000
    with pytest.raises(ParseError, match="nesting deeper than"):
        parse(blocks, "deep.holo")
    # Prefix operators, arrow functions and conditionals nest too: read in a loop or counted.
    for value in ("- " * 100_000 + "1", "!" * 100_000 + "x", "new " * 100_000 + "x"):
        assert isinstance(parse('object "A" { x: ' + value + " }", "deep.holo").body.children[0].props["x"].data, Expr)
    for value in ("x => " * 100_000 + "1", "a ? " * 100_000 + "1"):
        with pytest.raises(ParseError, match="nesting deeper than"):
            parse('object "A" { x: ' + value + " }", "deep.holo")
    # Braces that are not entries are code: skipped by iterative bracket matching, no recursion.
    braces = "{" * 100_000 + "}" * 100_000
    doc = parse('object "A" { x: ' + braces + " }", "deep.holo")
    assert isinstance(doc.body.children[0].props["x"].data, Expr)


# ---- HoloScript's own repository (optional) ----------------------------------------------
REPO = os.environ.get("ROBODESC_HOLOSCRIPT_REPO")

# Movable joints the authors declared, counted by hand in HoloScript's robotics examples.
DECLARED = {
    "benchmarks/cross-compilation/compositions/15-robotics.holo": 2,
    "benchmarks/scenarios/03-robotics-sim/robotics-sim.holo": 6,
    "examples/domain-starters/robotics/robotics-starter.holo": 3,
    "examples/robotics/isaac-sim-robot-arm.holo": 2,
    "examples/robotics/two-dof-robot-arm.holo": 2,
    "examples/showcase/multi-domain.holo": 3,
    "examples/specialized/robotics/robot-arm-simulation.holo": 7,
    "packages/plugins/robotics-plugin/examples/isaac-lab-sim-to-real.holo": 3,
    # robot { joints { FL_hip { } FL_knee { } } }
    "packages/plugins/robotics-plugin/examples/isaac-lab-sim-to-real-bridge.holo": 2,
    # two hinges; the third joint is a "spring" (no URDF equivalent: fixed, reported)
    "examples/showcase/realistic-forest.refreshed.holo": 2,
}


R, P = JointType.REVOLUTE, JointType.PRISMATIC
X, Y, Z = (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)
PI = 3.14159  # as the examples write it

# The joints as written in each example (type, axis in the object's frame, limits as written: degrees
# or radians for revolute joints, by notation (RADIANS lists the files written in radians), metres for
# prismatic), read off the files by hand.
WRITTEN: dict[str, dict[str, tuple[JointType, tuple[float, float, float], float, float]]] = {
    "benchmarks/cross-compilation/compositions/15-robotics.holo": {
        "J1_joint": (R, Y, -PI, PI),  # behavior: { axis } over the template's behavior block
        "J2_joint": (R, X, -PI, PI),
    },
    "benchmarks/scenarios/03-robotics-sim/robotics-sim.holo": {
        "Shoulder_joint": (R, Y, -180, 180),
        "UpperArm_joint": (R, Z, -90, 90),
        "Forearm_joint": (R, Z, -135, 135),
        "Wrist_joint": (R, Y, -180, 180),
        "WristPitch_joint": (R, Z, -90, 90),
        "Gripper_joint": (R, Y, -180, 180),
    },
    "examples/domain-starters/robotics/robotics-starter.holo": {
        "J1_joint": (R, Y, -PI, PI),
        "J2_joint": (R, X, -1.5708, 1.5708),
        "J3_joint": (R, X, -2.3562, 0),
    },
    "examples/robotics/isaac-sim-robot-arm.holo": {
        "ShoulderJoint_joint": (R, Z, -180, 180),
        "ElbowJoint_joint": (R, Y, -135, 135),
    },
    "examples/robotics/two-dof-robot-arm.holo": {
        "ShoulderJoint_joint": (R, Z, -180, 180),
        "ElbowJoint_joint": (R, Y, -135, 135),
    },
    "examples/showcase/multi-domain.holo": {
        "ShoulderYaw": (R, Y, -170, 170),
        "ShoulderPitch": (R, Z, -90, 90),
        "ElbowFlex": (R, Z, 0, 150),
    },
    "examples/specialized/robotics/robot-arm-simulation.holo": {
        "Shoulder_joint": (R, Y, -PI, PI),
        "Elbow_joint": (R, X, -PI, 0),
        "Wrist_joint": (R, X, -PI, PI),
        "Wrist2_joint": (R, Y, -PI, PI),
        "Wrist3_joint": (R, Z, -6.28318, 6.28318),
        "GripperFinger1_joint": (P, X, -0.05, 0.05),
        "GripperFinger2_joint": (P, (-1.0, 0.0, 0.0), -0.05, 0.05),
    },
    "packages/plugins/robotics-plugin/examples/isaac-lab-sim-to-real.holo": {
        "joint1_joint": (R, Z, -3.14, 3.14),
        "joint2_joint": (R, Y, -1.57, 1.57),
        # link1's @joint_revolute writes neither axis nor limits: continuous about +x, reported.
    },
    "packages/plugins/robotics-plugin/examples/isaac-lab-sim-to-real-bridge.holo": {
        "FL_hip": (R, Y, -1.57, 1.57),
        "FL_knee": (R, X, -2.5, 2.5),
    },
    "examples/showcase/realistic-forest.refreshed.holo": {
        "BridgePlank1_joint": (R, X, -15, 15),
        "BridgePlank2_joint": (R, X, -15, 15),
    },
}


# Files whose joints are behavior blocks, @joint_revolute with joint_limits, or a robot block.
RADIANS = {
    "benchmarks/cross-compilation/compositions/15-robotics.holo",
    "examples/domain-starters/robotics/robotics-starter.holo",
    "examples/specialized/robotics/robot-arm-simulation.holo",
    "packages/plugins/robotics-plugin/examples/isaac-lab-sim-to-real.holo",
    "packages/plugins/robotics-plugin/examples/isaac-lab-sim-to-real-bridge.holo",
}


@pytest.mark.skipif(REPO is None, reason="set ROBODESC_HOLOSCRIPT_REPO to a HoloScript checkout")
@pytest.mark.parametrize("rel", sorted(DECLARED))
def test_holoscript_checkout(rel: str, tmp_path: Path) -> None:
    assert REPO is not None
    path = os.path.join(REPO, rel)
    result = load_holo(path, LoadOptions(missing_mesh=MissingMesh.PRIMITIVE), Findings())
    got = movable(result.robot)
    assert len(got) == DECLARED[rel]
    for joint, (jtype, axis, lower, upper) in WRITTEN[rel].items():
        k = math.pi / 180 if jtype is R and rel not in RADIANS else 1.0
        assert got[joint][0] is jtype, joint
        assert got[joint][1] == pytest.approx(axis), joint
        assert (got[joint][2], got[joint][3]) == pytest.approx((lower * k, upper * k)), joint
    for j in result.robot.joints:
        if j.type in (JointType.REVOLUTE, JointType.PRISMATIC):
            assert j.axis is not None and j.limit is not None and j.limit.lower is not None
    assert_each_joint_moves_its_children(result.robot)
    from robodesc.cli import main

    for target, out in (("urdf", "r.urdf"), ("sdf", "r.sdf"), ("usd", "r.usda"), ("isaac", "isaac")):
        args = ["compile", path, "-o", str(tmp_path / out), "--missing-mesh", "primitive", "-q"]
        args += ["--isaac-sim"] if target == "isaac" else ["-t", target]
        assert main(args) == 0, (rel, target)


# ---- shapes URDF lacks: the closest primitive, the true shape's inertia ----------------------
def _trimesh_props(mesh: object, mass: float) -> tuple[np.ndarray, np.ndarray]:
    props = mesh.mass_properties  # type: ignore[attr-defined]
    return np.asarray(props.center_mass), np.asarray(props.inertia) * (mass / props.mass)


def test_cone_inertia_is_the_cones() -> None:
    trimesh = pytest.importorskip("trimesh")
    result = load("""composition "Cone" {
      object "Base" { @physics { type: "static" mass: 1 } geometry: "box" scale: 0.1 }
      object "Tip" { @joint(type: "revolute", connectedBody: "Base", axis: [0, 0, 1], limits: [-90, 90])
                     geometry: "cone" scale: [0.2, 0.4, 0.2] mass: 3 position: [0, 0, 0.5] }
    }""")
    inertial = result.robot.link("Tip").inertial
    assert inertial is not None and inertial.inertia is not None and inertial.origin is not None
    # trimesh's cone: base at z = 0, apex at z = h; robodesc's frame is the bounding-box middle.
    center, tensor = _trimesh_props(trimesh.creation.cone(radius=0.1, height=0.4, sections=512), 3.0)
    assert inertial.origin.xyz[2] == pytest.approx(center[2] - 0.2, abs=1e-4)
    got = np.diag(inertial.inertia.as_tuple()[:3])
    assert got == pytest.approx(tensor, rel=1e-3, abs=1e-7)
    assert "cone-as-cylinder" in codes(result)


def test_torus_and_polyhedron_inertia() -> None:
    trimesh = pytest.importorskip("trimesh")
    result = load("""composition "Wheels" {
      object "Base" { @physics { type: "static" mass: 1 } geometry: "box" scale: 0.1 }
      object "Tyre" { @joint { type: "continuous" connectedBody: "Base" axis: [0, 0, 1] }
                      geometry: "torus" scale: [0.5, 0.1, 0.5] mass: 2 }
      object "Gem" { @joint { type: "continuous" connectedBody: "Base" axis: [1, 0, 0] }
                     geometry: "octahedron" scale: 0.2 mass: 1 }
    }""")
    tyre = result.robot.link("Tyre").inertial
    assert tyre is not None and tyre.inertia is not None
    # outer diameter 0.5, tube diameter 0.1: centre-line radius 0.2, tube radius 0.05
    mesh = trimesh.creation.torus(major_radius=0.2, minor_radius=0.05, major_sections=256, minor_sections=128)
    _, tensor = _trimesh_props(mesh, 2.0)
    assert np.diag(tyre.inertia.as_tuple()[:3]) == pytest.approx(tensor, rel=2e-3, abs=1e-7)
    gem = result.robot.link("Gem").inertial
    assert gem is not None and gem.inertia is not None
    # a solid regular octahedron of circumradius a: I = m a² / 5
    assert gem.inertia.ixx == pytest.approx(1.0 * 0.1**2 / 5)
    assert [f.code for f in result.findings].count("substituted-geometry") == 2


def test_lexer_constructs_from_holoscript_examples() -> None:
    text = """# a comment line, as some examples write them
composition "Lex" {
  @2d_canvas(title: "x")
  note: 'spans
two lines'
  shader: '''code with 'quotes' and { braces'''
  tint: #1a2b3c
  angle: 15°
  big: 1e-3
  mask: 0xff
  when: a /* a comment
  over lines */ size: 2
}"""
    comp = parse(text, "t.holo").body.children[0]
    props = {k: v.data for k, v in comp.props.items()}
    assert [t.name for t in comp.traits] == ["2d_canvas"]
    assert props["note"] == "spans\ntwo lines"
    assert props["shader"] == "code with 'quotes' and { braces"
    assert props["tint"] == "#1a2b3c"
    assert props["angle"] == Expr("15 °")
    assert props["big"] == pytest.approx(1e-3) and props["mask"] == 255.0
    assert props["when"] == "a" and props["size"] == 2.0
    assert comp.prop_locs["size"].line == 12 and comp.prop_locs["size"].column == 17
