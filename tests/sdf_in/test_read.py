"""SDF models read into the IR: frame semantics, joints, links, surfaces, sensors, plugins, includes,
and a warning naming element and line for what the IR cannot hold."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings, ParseError
from robodesc.ir.model import JointType, Robot
from robodesc.ir.transforms import forward_kinematics, pose_matrix
from tests.sdf_in.compare import differences

DATA = Path(__file__).parent / "data"
FEATURES = DATA / "feature_bot.sdf"
MODELS = DATA / "models"
OPTIONS = LoadOptions(model_path=(str(MODELS),))


def _features() -> tuple[Robot, Findings]:
    loaded = load_path(str(FEATURES), OPTIONS)
    return loaded.robot, loaded.findings


def _sdf(tmp_path: Path, body: str, version: str = "1.9", name: str = "m.sdf") -> Path:
    path = tmp_path / name
    path.write_text(f'<?xml version="1.0"?>\n<sdf version="{version}">\n<model name="m">\n{body}\n</model>\n</sdf>\n')
    return path


LINK = '<link name="{name}"><pose>{pose}</pose><inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial></link>'


def test_link_posed_apart_from_its_joint_keeps_its_place() -> None:
    robot, _ = _features()
    shoulder = robot.joint("shoulder")
    # mount is 0.1 0 0.2 yaw 1.5708 on base; the joint is 0.1 above mount, rolled 0.2.
    assert shoulder.origin is not None
    assert np.allclose(shoulder.origin.xyz, (0.1, 0.0, 0.3)) and np.allclose(shoulder.origin.rpy, (0.2, 0.0, 1.5708))
    # upper sits 0.05 above its joint: its COM (0.1 above upper) is 0.15 above the IR frame.
    upper = robot.link("upper")
    assert upper.inertial is not None and upper.inertial.origin is not None
    assert np.allclose(upper.inertial.origin.xyz, (0.0, 0.0, 0.15))
    # The axis was expressed in the model frame: in the joint frame, model z is (0, sin 0.2, cos 0.2).
    assert np.allclose(shoulder.axis, (0.0, math.sin(0.2), math.cos(0.2)))


def test_joints_limits_dynamics_and_gains() -> None:
    robot, _ = _features()
    shoulder = robot.joint("shoulder")
    assert shoulder.type is JointType.REVOLUTE
    assert shoulder.limit is not None
    assert (shoulder.limit.lower, shoulder.limit.upper, shoulder.limit.effort, shoulder.limit.velocity) == (
        -1.0,
        1.5,
        20.0,
        3.0,
    )
    assert shoulder.dynamics is not None
    assert (shoulder.dynamics.damping, shoulder.dynamics.friction, shoulder.dynamics.spring_stiffness) == (
        0.5,
        0.1,
        2.0,
    )
    # The JointPositionController's gains are the joint's drive.
    assert shoulder.drive is not None and (shoulder.drive.kind, shoulder.drive.stiffness, shoulder.drive.damping) == (
        "position",
        50.0,
        2.0,
    )
    # A revolute joint without limits is continuous; a ball joint spherical.
    assert robot.joint("wheel_joint").type is JointType.CONTINUOUS
    assert robot.joint("tail_ball").type is JointType.SPHERICAL
    slide = robot.joint("hand::slide")
    assert slide.type is JointType.PRISMATIC and slide.limit is not None and slide.limit.upper == 0.04


def test_universal_joint_is_two_revolutes_with_a_warning() -> None:
    robot, findings = _features()
    first, second = robot.joint("wrist_1"), robot.joint("wrist_2")
    assert (first.parent, first.child, second.parent, second.child) == (
        "upper",
        "wrist_cross",
        "wrist_cross",
        "hand::palm",
    )
    assert np.allclose(first.effective_axis, (1, 0, 0)) and np.allclose(second.effective_axis, (0, 1, 0))
    warning = next(f for f in findings.items if f.code == "sdf-universal-joint")
    assert warning.loc is not None and warning.loc.line == 92 and "wrist" in warning.element


def test_nested_model_and_include_are_scoped() -> None:
    robot, _ = _features()
    names = {link.name for link in robot.links}
    assert {"hand::palm", "hand::slider", "hand::finger::knuckle", "hand::finger::tip"} <= names
    tip = robot.link("hand::finger::tip")
    mesh = tip.visuals[0].geometry
    # The included model's relative mesh resolved in its own folder, its scale kept.
    assert getattr(mesh, "path", "").endswith("finger_part/meshes/tip.stl")
    assert getattr(mesh, "scale", None) == (0.001, 0.001, 0.001)
    bend = robot.joint("hand::finger::bend")
    assert bend.limit is not None and bend.limit.upper == 1.2


def test_frames_surfaces_materials_sensors_and_placement() -> None:
    robot, _ = _features()
    (mount,) = robot.fixed_frames
    assert mount.parent == "base" and mount.origin is not None and np.allclose(mount.origin.xyz, (0.1, 0.0, 0.2))
    collision = robot.link("base").collisions[0]
    assert collision.contact is not None
    assert (collision.contact.mu, collision.contact.mu2, collision.contact.kp, collision.contact.kd) == (
        0.8,
        0.7,
        1e5,
        10.0,
    )
    material = robot.link("base").visuals[0].material
    assert material is not None and material.color == (0.8, 0.2, 0.1, 1.0)
    (imu,) = robot.sensors
    assert imu.parent == "base" and imu.update_rate == 200 and imu.origin is not None
    assert np.allclose(imu.origin.rpy, (0.0, 0.0, 1.5708))
    # The model's pose composed with its root link's (0.1 up): where the root stands in the world.
    assert robot.placement is not None and np.allclose(robot.placement.xyz, (1.0, 2.0, 0.6))
    assert robot.fixed_base is None  # no weld: the model does not say


def test_sdf_1_6_and_1_9_of_one_model_are_the_same_robot() -> None:
    new = load_path(str(MODELS / "finger_part" / "model.sdf")).robot
    old = load_path(str(MODELS / "finger_part" / "model_old.sdf")).robot
    problems, fk = differences(new, old)
    assert problems == [] and fk < 1e-12


def test_model_folder_reads_its_model_config(tmp_path: Path) -> None:
    # The highest version model.config lists (model.sdf, 1.9) is read.
    robot = load_path(str(MODELS / "finger_part")).robot
    assert robot.name == "finger_part" and len(robot.links) == 2


def test_sdf_1_4_axis_is_in_the_model_frame(tmp_path: Path) -> None:
    body = (
        LINK.format(name="a", pose="0 0 0 0 0 0")
        + LINK.format(name="b", pose="0 0 1 0 0 1.5707963267948966")
        + '<joint name="j" type="revolute"><parent>a</parent><child>b</child>'
        "<axis><xyz>1 0 0</xyz><limit><lower>-1</lower><upper>1</upper></limit></axis></joint>"
    )
    old = load_path(str(_sdf(tmp_path, body, "1.4", "old.sdf"))).robot
    new = load_path(str(_sdf(tmp_path, body, "1.7", "new.sdf"))).robot
    # The child is yawed 90 degrees: model x is the joint's -y; in 1.7 the axis is the joint's own x.
    assert np.allclose(old.joint("j").effective_axis, (0.0, -1.0, 0.0))
    assert np.allclose(new.joint("j").effective_axis, (1.0, 0.0, 0.0))


def test_mimic_with_reference_and_degrees_and_quaternion_poses(tmp_path: Path) -> None:
    body = (
        LINK.format(name="a", pose="0 0 0 0 0 0")
        + '<link name="b"><pose degrees="true">0 0 1 0 0 90</pose></link>'
        + '<link name="c"><pose rotation_format="quat_xyzw">0 0 2 0 0 0.7071067811865476 0.7071067811865476</pose></link>'
        + '<joint name="j1" type="revolute"><parent>a</parent><child>b</child><axis><xyz>0 0 1</xyz>'
        "<limit><lower>-1</lower><upper>1</upper></limit></axis></joint>"
        + '<joint name="j2" type="revolute"><parent>b</parent><child>c</child><axis><xyz>0 0 1</xyz>'
        '<limit><lower>-1</lower><upper>1</upper></limit><mimic joint="j1" axis="axis"><multiplier>2</multiplier>'
        "<offset>0.5</offset><reference>0.1</reference></mimic></axis></joint>"
    )
    robot = load_path(str(_sdf(tmp_path, body, "1.11"))).robot
    mimic = robot.joint("j2").mimic
    # q2 = 2 (q1 - 0.1) + 0.5 = 2 q1 + 0.3
    assert mimic is not None and mimic.joint == "j1" and mimic.multiplier == 2 and mimic.offset == pytest.approx(0.3)
    # b is yawed 90 degrees (in degrees), c the same (as a quaternion): c sits on b unrotated, 1 m up.
    j1, j2 = robot.joint("j1").origin, robot.joint("j2").origin
    assert j1 is not None and np.allclose(j1.rpy, (0.0, 0.0, math.pi / 2))
    assert j2 is not None and np.allclose(pose_matrix(j2), pose_matrix(type(j2)((0.0, 0.0, 1.0))))
    # At q1 = 0.1 the mimic is 2 * 0.1 + 0.3 = 0.5: c's x axis is yawed pi/2 + 0.1 + 0.5.
    fk = forward_kinematics(robot, {"j1": 0.1})
    angle = math.pi / 2 + 0.6
    assert np.allclose(fk["c"][:2, 0], (math.cos(angle), math.sin(angle)))


def test_what_the_ir_cannot_hold_is_a_warning_at_its_line(tmp_path: Path) -> None:
    body = (
        '<link name="a"><inertial><mass>1</mass></inertial>'
        '<visual name="e"><geometry><ellipsoid><radii>0.1 0.2 0.3</radii></ellipsoid></geometry></visual>\n'
        '<collision name="p"><geometry><plane><normal>0 0 1</normal><size>1 1</size></plane></geometry></collision>\n'
        "<velocity_decay/>\n"
        '<sensor name="alt" type="altimeter"/></link>\n'
        "<include><uri>model://not_there</uri></include>\n"
        '<joint name="s" type="screw"><parent>a</parent><child>b</child></joint>\n<link name="b"/>'
    )
    loaded = load_path(str(_sdf(tmp_path, body)))
    codes = {f.code: f for f in loaded.findings.items}
    lines = {"sdf-ellipsoid": 4, "sdf-geometry-unsupported": 5, "sdf-unread": 6, "sdf-sensor-unsupported": 7}
    for code, line in lines.items():
        assert code in codes and codes[code].loc is not None and codes[code].loc.line == line, code
    assert codes["sdf-include-missing"].loc.line == 8  # type: ignore[union-attr]
    assert codes["sdf-joint-unsupported"].loc.line == 9  # type: ignore[union-attr]
    # The ellipsoid is the sphere of its largest radius; the screw joint fixed; b's default inertial 1 kg.
    robot = loaded.robot
    assert getattr(robot.link("a").visuals[0].geometry, "radius", None) == 0.3
    assert robot.link("a").collisions == []
    assert robot.joint("s").type is JointType.FIXED
    b = robot.link("b").inertial
    assert b is not None and b.mass == 1.0 and b.inertia is not None and b.inertia.ixx == 1.0


@pytest.mark.parametrize(
    ("body", "message", "line"),
    [
        (
            '<link name="a"><pose relative_to="b"/></link>\n<link name="b"><pose relative_to="a"/></link>',
            "form a cycle",
            4,
        ),
        ('<link name="a"><pose relative_to="nowhere"/></link>', "names no frame", 4),
        ('<link name="a"/>\n<link name="a"/>', "used twice", 5),
        ('<link name="a"><pose>1 2 3</pose></link>', "needs 6 numbers", 4),
    ],
)
def test_errors_name_the_line(tmp_path: Path, body: str, message: str, line: int) -> None:
    with pytest.raises(ParseError, match=message) as err:
        load_path(str(_sdf(tmp_path, body)))
    assert f"m.sdf:{line}" in str(err.value)


def test_a_world_file_is_sent_to_world(tmp_path: Path) -> None:
    path = tmp_path / "empty.world"
    path.write_text('<sdf version="1.9"><world name="w"><model name="m"><link name="a"/></model></world></sdf>')
    with pytest.raises(ParseError, match="give it with --world"):
        load_path(str(path))


def test_fixed_to_world_is_a_fixed_base(tmp_path: Path) -> None:
    body = (
        LINK.format(name="a", pose="0 0 0 0 0 0")
        + '<joint name="w" type="fixed"><parent>world</parent><child>a</child></joint>'
    )
    robot = load_path(str(_sdf(tmp_path, body))).robot
    assert robot.fixed_base is True and robot.joints == []


def test_a_second_joint_into_a_link_is_a_loop_joint(tmp_path: Path) -> None:
    body = (
        LINK.format(name="a", pose="0 0 0 0 0 0")
        + LINK.format(name="b", pose="0 0 1 0 0 0")
        + LINK.format(name="c", pose="1 0 0 0 0 0")
        + '<joint name="ab" type="revolute"><parent>a</parent><child>b</child><axis><xyz>0 1 0</xyz></axis></joint>'
        + '<joint name="ac" type="revolute"><parent>a</parent><child>c</child><axis><xyz>0 1 0</xyz></axis></joint>'
        + '<joint name="bc" type="revolute"><pose>0 0 0.5 0 0 0</pose><parent>b</parent><child>c</child>'
        "<axis><xyz>0 1 0</xyz></axis></joint>"
    )
    loaded = load_path(str(_sdf(tmp_path, body)))
    (loop,) = loaded.robot.loop_joints
    assert (loop.name, loop.link1.link, loop.link2.link) == ("bc", "b", "c")
    # At zero both sides of the loop are the same place: 0.5 above c, in the model frame.
    fk = forward_kinematics(loaded.robot)
    one = fk["b"] @ pose_matrix(loop.link1.origin)
    two = fk["c"] @ pose_matrix(loop.link2.origin)
    assert np.allclose(one, two) and np.allclose(two[:3, 3], (1.0, 0.0, 0.5))
    assert any(f.code == "sdf-loop-joint" for f in loaded.findings.items)


def test_old_pose_frame_and_unknown_version_are_warnings(tmp_path: Path) -> None:
    body = '<link name="a"><pose frame="elsewhere">0 0 1 0 0 0</pose></link>'
    loaded = load_path(str(_sdf(tmp_path, body, "1.6")))
    frame = next(f for f in loaded.findings.items if f.code == "sdf-pose-frame")
    assert frame.loc is not None and frame.loc.line == 4
    loaded = load_path(str(_sdf(tmp_path, '<link name="a"/>', "2.0", "new.sdf")))
    assert any(f.code == "sdf-version" for f in loaded.findings.items)
