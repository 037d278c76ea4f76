"""unique_materials, strip_tags, armature, isaac_limits, zero_pose."""

from __future__ import annotations

import hashlib
import math
from pathlib import Path

import pytest

from robodesc.ir import (
    Collision,
    ConfigError,
    Extension,
    Inertia,
    Inertial,
    Joint,
    JointType,
    Limit,
    Link,
    Material,
    Mimic,
    Robot,
    Ros2Control,
    Sphere,
    Transmission,
    Visual,
)
from robodesc.ir.verify import check
from robodesc.passes.armature import armature
from robodesc.passes.isaac_limits import isaac_limits
from robodesc.passes.options import ArmatureRule, PassOptions, options_from_mapping, parse_armature
from robodesc.passes.strip_tags import strip_tags
from robodesc.passes.unique_materials import unique_materials
from robodesc.passes.zero_pose import zero_pose
from tests.passes.pass_helpers import chain, codes, ctx, resolved_color

WHITE = (1.0, 1.0, 1.0, 1.0)
RED = (1.0, 0.0, 0.0, 1.0)


def _sha6(rgba: tuple[float, ...]) -> str:
    return hashlib.sha1(f"rgba={' '.join(repr(c) for c in rgba)};texture=".encode()).hexdigest()[:6]


# ---- unique_materials --------------------------------------------------------------------


def test_unnamed_materials_get_unique_shared_names() -> None:
    robot = chain("body", "hip", "leg", "foot")
    colors = [WHITE, WHITE, RED, WHITE]
    for link, color in zip(robot.links, colors, strict=True):
        link.visuals[0].material = Material("", color=color)
    c = ctx(unique_materials=True)
    unique_materials(robot, c)
    check(robot)
    white = f"material_body_{_sha6(WHITE)}"
    red = f"material_leg_{_sha6(RED)}"
    assert [link.visuals[0].material.name for link in robot.links] == [white, white, red, white]  # type: ignore[union-attr]
    assert [(m.name, m.color) for m in robot.materials] == [(white, WHITE), (red, RED)]
    assert all(link.visuals[0].material.is_reference() for link in robot.links)  # type: ignore[union-attr]
    assert codes(c) == ["material-named", "material-named", "unnamed-materials"]
    assert "4 unnamed inline material(s) -> 2" in c.findings.items[-1].message


def test_named_materials_keep_names_and_conflicts_split() -> None:
    robot = chain("a", "b", "c")
    robot.materials = [Material("grey", color=(0.5, 0.5, 0.5, 1.0))]
    robot.links[0].visuals[0].material = Material("grey")  # reference
    robot.links[1].visuals[0].material = Material("grey", color=RED)  # same name, other colour
    robot.links[2].visuals[0].material = Material("paint", color=RED)  # named: not merged with the red one
    c = ctx(unique_materials=True)
    unique_materials(robot, c)
    check(robot)
    split = f"grey_{_sha6(RED)}"
    assert [link.visuals[0].material.name for link in robot.links] == ["grey", split, "paint"]  # type: ignore[union-attr]
    assert [resolved_color(robot, link.visuals[0].material) for link in robot.links] == [
        (0.5, 0.5, 0.5, 1.0),
        RED,
        RED,
    ]
    assert "material-renamed" in codes(c)
    names = [m.name for m in robot.materials]
    assert len(names) == len(set(names)) == 3


# ---- strip_tags --------------------------------------------------------------------------


def _cluttered() -> Robot:
    robot = chain("a", "b")
    robot.extensions = [Extension("gazebo", "<gazebo/>"), Extension("gazebo", '<gazebo reference="a"/>', reference="a")]
    robot.links[0].extensions = [Extension("contact", "<contact/>"), Extension("gazebo", "<gazebo/>")]
    robot.links[0].collisions = [Collision(Sphere(0.1), extensions=[Extension("surface", "<surface/>")])]
    robot.transmissions = [Transmission("t")]
    robot.ros2_controls = [Ros2Control("rc")]
    robot.joints[0].dont_collapse = True
    return robot


def test_strip_each_kind_with_counts() -> None:
    robot = _cluttered()
    c = ctx(strip="gazebo,transmission,ros2_control,dont_collapse,contact,surface")
    strip_tags(robot, c)
    assert robot.extensions == [] and robot.links[0].extensions == []
    assert robot.links[0].collisions[0].extensions == []
    assert robot.transmissions == [] and robot.ros2_controls == [] and robot.joints[0].dont_collapse is None
    assert [(f.code, f.message) for f in c.findings] == [
        ("stripped-gazebo", "removed 3 <gazebo> block(s)"),
        ("stripped-transmission", "removed 1 <transmission>(s)"),
        ("stripped-ros2_control", "removed 1 <ros2_control>(s)"),
        ("stripped-dont_collapse", "removed 1 dont_collapse attribute(s)"),
        ("stripped-contact", "removed 1 link-level <contact>(s)"),
        ("stripped-surface", "removed 1 collision-level <surface>(s)"),
    ]


def test_strip_only_selected_kinds() -> None:
    robot = _cluttered()
    c = ctx(strip=["contact"])
    strip_tags(robot, c)
    assert [e.tag for e in robot.links[0].extensions] == ["gazebo"]
    assert len(robot.extensions) == 2 and robot.transmissions and robot.joints[0].dont_collapse is True
    assert codes(c) == ["stripped-contact"]


def test_unknown_strip_kind_names_the_closest() -> None:
    with pytest.raises(ConfigError, match="did you mean 'gazebo'"):
        ctx(strip="gazbo")


# ---- armature ----------------------------------------------------------------------------


def test_armature_first_matching_rule_wins_and_unmatched_reported() -> None:
    robot = chain("a", "b", "c", "d", joint_names=["j_knee_0", "j_hip_0", "wrist"])
    rules = (
        ArmatureRule(r"^j_knee_[0-3]$", j_rotor=1.231e-4, gear_ratio=12.0),
        ArmatureRule(r"^j_", 4.4316e-3),
        ArmatureRule(r"knee", 99.0),  # never reached for j_knee_0
    )
    c = ctx(armature=rules)
    armature(robot, c)
    assert robot.joints[0].armature == pytest.approx(1.231e-4 * 144, rel=1e-15)
    assert robot.joints[0].armature == pytest.approx(1.77264e-2, rel=1e-12)
    assert robot.joints[1].armature == 4.4316e-3
    assert robot.joints[2].armature is None
    assert codes(c) == ["armature-set", "armature-set", "armature-unmatched"]
    assert "wrist" in c.findings.items[-1].message


def test_armature_by_robot_and_parse() -> None:
    assert parse_armature("^j_knee_=1.231e-4*12^2").armature() == pytest.approx(1.77264e-2)
    assert parse_armature("^j_=4.4316e-3") == ArmatureRule("^j_", 4.4316e-3)
    robot = chain("a", "b", joint_names=["j_hip_0"])
    c = ctx(armature_by_robot={"spirit": (ArmatureRule("j_", 1.0),)})
    armature(robot, c)
    assert robot.joints[0].armature is None and codes(c) == ["no-armature-table"]
    robot.name = "spirit"
    armature(robot, c)
    assert robot.joints[0].armature == 1.0


def test_mimic_joints_are_not_actuated() -> None:
    robot = chain("a", "b", "c", joint_names=["x", "y"])
    robot.joints[1].mimic = Mimic("x")
    c = ctx(armature=(ArmatureRule("^x$", 1.0),))
    armature(robot, c)
    assert "armature-unmatched" not in codes(c)


def test_default_armature_from_effort_and_source_values_win() -> None:
    """effort^1.5·1e-4: 23.7 N·m (Go1's hip, menagerie 0.01) gives 0.0115; a source value and a
    prismatic joint are left alone, a joint without effort is listed."""
    from robodesc.passes.default_armature import default_armature

    robot = chain("a", "b", "c", "d", "e", joint_names=["hip", "given", "slide", "free"])
    robot.joints[0].limit = Limit(lower=-1.0, upper=1.0, effort=23.7, velocity=30.0)
    robot.joints[1].limit = Limit(lower=-1.0, upper=1.0, effort=87.0, velocity=2.0)
    robot.joints[1].armature = 0.5
    robot.joints[2].type = JointType.PRISMATIC
    robot.joints[2].limit = Limit(lower=0.0, upper=0.04, effort=100.0, velocity=0.2)
    robot.joints[3].limit = Limit(lower=-1.0, upper=1.0, effort=None, velocity=1.0)
    c = ctx(default_armature=True)
    default_armature(robot, c)
    assert robot.joints[0].armature == pytest.approx(1e-4 * 23.7**1.5, rel=5e-3)  # three digits
    assert robot.joints[0].armature == pytest.approx(0.0115, rel=1e-2)
    assert robot.joints[1].armature == 0.5
    assert robot.joints[2].armature is None and robot.joints[3].armature is None
    assert codes(c) == ["armature-default", "armature-default-skipped"]
    assert "slide" in c.findings.items[-1].message and "free" in c.findings.items[-1].message


def test_default_armature_preset_on_and_option_turns_it_off() -> None:
    from robodesc.passes.pipeline import enabled_passes, resolve_options

    assert "default_armature" in enabled_passes(resolve_options("mjcf", None))
    assert "default_armature" in enabled_passes(resolve_options("isaac_sim", None))
    assert "default_armature" not in enabled_passes(resolve_options("ros2", None))
    off = options_from_mapping({"default_armature": False}, PassOptions())
    assert "default_armature" not in enabled_passes(resolve_options("mjcf", off))


# ---- isaac_limits and zero_pose ----------------------------------------------------------


def test_isaac_limits() -> None:
    robot = chain("root", "a", "b", "c", joint_names=["rev", "pri", "cont"])
    robot.joints[0].limit = None
    robot.joints[1].type = JointType.PRISMATIC
    robot.joints[1].limit = Limit(lower=0.0, upper=0.5)  # effort and velocity missing
    robot.joints[2].type = JointType.CONTINUOUS
    robot.joints[2].limit = None
    robot.links.insert(0, Link("world"))
    robot.joints.insert(0, Joint("fix", JointType.FIXED, "world", "root"))
    c = ctx(isaac_limits=True)
    isaac_limits(robot, c)
    check(robot)
    lim = robot.joint("rev").limit
    assert lim is not None and (lim.lower, lim.upper) == (-math.pi, math.pi)
    pri = robot.joint("pri").limit
    assert pri is not None and (pri.lower, pri.upper, pri.effort, pri.velocity) == (0.0, 0.5, 1000.0, 100.0)
    assert robot.joint("cont").type is JointType.CONTINUOUS and robot.joint("cont").limit is None
    world = robot.link("world").inertial
    assert world is not None and world.mass == 0.001 and world.inertia == Inertia(1e-6, 1e-6, 1e-6)
    assert codes(c) == ["limit-added", "limit-completed", "empty-root-link"]


def test_isaac_limits_widens_a_range_with_no_width() -> None:
    """SolidWorks' all-zero <limit> (double_pendulum, Stretch's gripper fingers) is 'not set': a
    placeholder range and the default effort and velocity; a zero-width range with a real effort
    keeps its effort."""
    robot = chain("root", "a", "b", "c", joint_names=["rev", "pri", "cont"])
    robot.joints[0].limit = Limit(lower=0.0, upper=0.0, effort=0.0, velocity=0.0)
    robot.joints[1].type = JointType.PRISMATIC
    robot.joints[1].limit = Limit(lower=0.2, upper=0.1, effort=5.0, velocity=1.0)
    robot.joints[2].type = JointType.CONTINUOUS  # double_pendulum_continuous: a [0, 0] force range
    robot.joints[2].limit = Limit(effort=0.0, velocity=0.0)
    c = ctx(isaac_limits=True)
    isaac_limits(robot, c)
    rev, pri, cont = robot.joint("rev").limit, robot.joint("pri").limit, robot.joint("cont").limit
    assert rev is not None and (rev.lower, rev.upper, rev.effort, rev.velocity) == (-math.pi, math.pi, 1000.0, 100.0)
    assert pri is not None and (pri.lower, pri.upper, pri.effort, pri.velocity) == (-1.0, 1.0, 5.0, 1.0)
    assert cont is not None and (cont.lower, cont.upper, cont.effort, cont.velocity) == (None, None, 1000.0, 100.0)
    assert codes(c) == ["limit-completed", "limit-widened", "limit-widened", "limit-completed"]


def test_flat_collision_mesh_becomes_a_thin_box(tmp_path: Path) -> None:
    """Stretch's ArUco plates: a planar mesh has no hull for PhysX or Newton's MuJoCo backend."""
    from robodesc.ir.geometry import Box, Mesh, Pose
    from robodesc.ir.model import Collision
    from robodesc.passes.flat_colliders import THICKNESS, flat_colliders

    flat = tmp_path / "plate.obj"  # a 4 x 2 cm plate in the plane z = 0.01, centred at (0.02, 0, 0.01)
    flat.write_text("v 0 -0.01 0.01\nv 0.04 -0.01 0.01\nv 0.04 0.01 0.01\nv 0 0.01 0.01\nf 1 2 3\nf 1 3 4\n")
    solid = tmp_path / "tet.obj"
    solid.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    robot = chain("a", "b")
    origin = Pose(xyz=(1.0, 0.0, 0.0), rpy=(0.0, 0.0, math.pi / 2))
    robot.links[1].collisions = [
        Collision(Mesh("plate.obj", path=str(flat)), origin=origin),
        Collision(Mesh("tet.obj", path=str(solid))),
    ]
    c = ctx()
    flat_colliders(robot, c)
    box, kept = robot.links[1].collisions
    assert isinstance(box.geometry, Box) and isinstance(kept.geometry, Mesh)
    assert box.geometry.size == pytest.approx((0.04, 0.02, THICKNESS))
    assert box.origin is not None
    # The plate's centre (0.02, 0, 0.01) turned a quarter about z, then moved by the origin.
    assert box.origin.xyz == pytest.approx((1.0, 0.02, 0.01))
    assert box.origin.rpy == pytest.approx((0.0, 0.0, math.pi / 2))
    assert codes(c) == ["flat-collider"]


def test_zero_pose_outside_limits() -> None:
    robot = chain("a", "b", "c", joint_names=["knee", "hip"])
    robot.joints[0].limit = Limit(lower=-2.7227, upper=-0.83776, effort=1.0, velocity=1.0)
    c = ctx()
    zero_pose(robot, c)
    assert [(f.code, f.element) for f in c.findings] == [("zero-outside-limits", "joint 'knee'")]
    assert "[-2.7227, -0.83776]" in c.findings.items[0].message


def test_pass_leaves_inertial_alone_when_given() -> None:
    link = Link("x", inertial=Inertial(mass=1.0), visuals=[Visual(Sphere(0.1))])
    robot = Robot("r", links=[link])
    isaac_limits(robot, ctx(isaac_limits=True))
    assert link.inertial is not None and link.inertial.inertia is None


def test_keep_bodies_marks_fixed_joints_carrying_sensors_and_frames() -> None:
    from robodesc.frontends.load import load_path
    from robodesc.passes import PassOptions, run_passes
    from tests.conftest import EXAMPLES

    robot = load_path(str(EXAMPLES / "urdf" / "gripper_arm.urdf")).robot
    # The camera and tcp hang on 'hand' (behind a continuous joint): nothing to mark there.
    run_passes(robot, options=PassOptions(keep_bodies=True))
    assert robot.joint("tool_mount").dont_collapse is None
    robot.sensors[0].parent = "tool"
    findings = run_passes(robot, options=PassOptions(keep_bodies=True))
    assert robot.joint("tool_mount").dont_collapse is True
    assert [f.code for f in findings if f.element == "joint 'tool_mount'"] == ["dont-collapse"]
