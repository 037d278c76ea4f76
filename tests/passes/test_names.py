"""sanitize_names and rename: the scheme, uniqueness, and every reference following."""

from __future__ import annotations

import pytest

from robodesc.ir import (
    ConfigError,
    ControlJoint,
    Extension,
    FixedFrame,
    LoopFrame,
    LoopJoint,
    Material,
    Mimic,
    Robot,
    Ros2Control,
    Sensor,
    SensorType,
    Transmission,
    TransmissionActuator,
    TransmissionJoint,
)
from robodesc.ir.verify import check
from robodesc.passes import run_passes
from robodesc.passes.options import PassOptions, RenameRule, parse_rename
from robodesc.passes.rename import rename
from robodesc.passes.sanitize_names import sanitize, sanitize_names, unique_names
from tests.passes.pass_helpers import chain, codes, ctx


@pytest.mark.parametrize(
    ("name", "expected"),
    [
        ("100_shoulder_mesh", "a100_shoulder_mesh"),
        ("_base", "a_base"),
        ("joint-1", "joint_1"),
        ("Schulter-Gelenk", "Schulter_Gelenk"),
        ("Gelenk_ä", "Gelenk_a"),
        ("关节", "a__"),
        ("ﬁnger.1", "finger_1"),  # NFKD expands the ligature
        ("", "a"),
        ("valid_Name9", "valid_Name9"),
    ],
)
def test_sanitize_scheme(name: str, expected: str) -> None:
    assert sanitize(name) == expected


def test_unique_names_keep_valid_names_and_suffix_in_input_order() -> None:
    # joint_1 is valid and keeps its name even though joint-1 comes first.
    assert unique_names(["joint-1", "joint_1", "joint.1", "joint 1"]) == {
        "joint-1": "joint_1_1",
        "joint.1": "joint_1_2",
        "joint 1": "joint_1_3",
    }
    assert unique_names(["关节", "关节2", "节关"]) == {"关节": "a__", "关节2": "a__2", "节关": "a___1"}


def _robot_with_references() -> Robot:
    robot = chain(
        "100_shoulder_mesh", "_base", "Schulter-Gelenk", "关节", joint_names=["joint-1", "joint_1", "Gelenk_ä"]
    )
    robot.name = "my robot"
    robot.joints[2].mimic = Mimic(joint="joint-1", multiplier=2.0)
    robot.loop_joints = [
        LoopJoint("loop-1", "spherical", LoopFrame("_base"), LoopFrame("关节")),
    ]
    robot.fixed_frames = [FixedFrame("tcp.frame", parent="关节"), FixedFrame("a_base", parent="_base")]
    robot.sensors = [Sensor("cam-1", SensorType.CAMERA, parent="Schulter-Gelenk", parent_joint="joint_1")]
    robot.transmissions = [
        Transmission("t1", joints=[TransmissionJoint("joint-1")], actuators=[TransmissionActuator("m1")])
    ]
    robot.ros2_controls = [Ros2Control("rc", joints=[ControlJoint("Gelenk_ä")])]
    robot.materials = [Material("dark-grey", color=(0.1, 0.1, 0.1, 1.0))]
    robot.links[0].visuals[0].material = Material("dark-grey")
    robot.extensions = [
        Extension(
            "gazebo", '<gazebo reference="_base"><mu1>1</mu1></gazebo>', anchor=("link", "_base"), reference="_base"
        ),
        Extension("gazebo", '<gazebo reference="joint-1"/>', anchor=("joint", "joint-1"), reference="joint-1"),
    ]
    return robot


def test_sanitize_names_updates_every_reference() -> None:
    robot = _robot_with_references()
    c = ctx(sanitize_names=True)
    sanitize_names(robot, c)
    check(robot)
    assert robot.name == "my_robot" and robot.display_name == "my robot"
    assert [link.name for link in robot.links] == ["a100_shoulder_mesh", "a_base_1", "Schulter_Gelenk", "a__"]
    assert [link.display_name for link in robot.links] == ["100_shoulder_mesh", "_base", "Schulter-Gelenk", "关节"]
    assert [j.name for j in robot.joints] == ["joint_1_1", "joint_1", "Gelenk_a"]
    assert [(j.parent, j.child) for j in robot.joints] == [
        ("a100_shoulder_mesh", "a_base_1"),
        ("a_base_1", "Schulter_Gelenk"),
        ("Schulter_Gelenk", "a__"),
    ]
    assert robot.joints[2].mimic is not None and robot.joints[2].mimic.joint == "joint_1_1"
    assert (robot.loop_joints[0].name, robot.loop_joints[0].link1.link, robot.loop_joints[0].link2.link) == (
        "loop_1",
        "a_base_1",
        "a__",
    )
    # Links and frames share a namespace: the valid frame 'a_base' keeps its name, the link moves.
    assert [(f.name, f.parent) for f in robot.fixed_frames] == [("tcp_frame", "a__"), ("a_base", "a_base_1")]
    assert (robot.sensors[0].name, robot.sensors[0].parent, robot.sensors[0].parent_joint) == (
        "cam_1",
        "Schulter_Gelenk",
        "joint_1",
    )
    assert robot.transmissions[0].joints[0].name == "joint_1_1"
    assert robot.ros2_controls[0].joints[0].name == "Gelenk_a"
    assert robot.materials[0].name == "dark_grey" and robot.materials[0].display_name == "dark-grey"
    assert robot.links[0].visuals[0].material is not None and robot.links[0].visuals[0].material.name == "dark_grey"
    gz_link, gz_joint = robot.extensions
    assert (gz_link.reference, gz_link.anchor) == ("a_base_1", ("link", "a_base_1"))
    assert 'reference="a_base_1"' in gz_link.xml and "<mu1>1</mu1>" in gz_link.xml
    assert (gz_joint.reference, gz_joint.anchor) == ("joint_1_1", ("joint", "joint_1_1"))
    assert all(f.stage == "pass:sanitize_names" for f in c.findings)
    assert codes(c).count("renamed") == 1 + 4 + 2 + 1 + 1 + 1 + 1  # robot, links, joints, material, frame, sensor, loop


def test_valid_names_never_change() -> None:
    robot = chain("base", "upper", "lower")
    c = ctx(sanitize_names=True)
    sanitize_names(robot, c)
    assert [link.name for link in robot.links] == ["base", "upper", "lower"]
    assert all(link.display_name is None for link in robot.links)
    assert len(c.findings) == 0


def test_frame_never_takes_a_link_name() -> None:
    robot = chain("a_b", "c")
    robot.fixed_frames = [FixedFrame("a-b", parent="c")]
    sanitize_names(robot, ctx(sanitize_names=True))
    assert robot.fixed_frames[0].name == "a_b_1"
    check(robot)


# ---- rename ------------------------------------------------------------------------------


def _quad_like() -> Robot:
    robot = chain("body", "hip", "upper", joint_names=["8", "0"])
    robot.transmissions = [
        Transmission("transmission_8", joints=[TransmissionJoint("8")], actuators=[TransmissionActuator("motor_8")]),
        Transmission("transmission_0", joints=[TransmissionJoint("0")], actuators=[TransmissionActuator("motor_0")]),
    ]
    robot.ros2_controls = [Ros2Control("rc", joints=[ControlJoint("8"), ControlJoint("0")])]
    robot.sensors = [Sensor("s", SensorType.IMU, parent="upper", parent_joint="0")]
    robot.extensions = [Extension("gazebo", '<gazebo reference="0"/>', anchor=("joint", "0"), reference="0")]
    return robot


def test_rename_table_with_transmissions_motors_and_references() -> None:
    robot = _quad_like()
    c = ctx(rename=[RenameRule("8", "j_abad_0"), RenameRule("0", "j_hip_0")])
    rename(robot, c)
    check(robot)
    assert [j.name for j in robot.joints] == ["j_abad_0", "j_hip_0"]
    # An explicit rename is the name to show: no displayName pointing back to "8" (sanitization keeps one).
    assert [j.display_name for j in robot.joints] == [None, None]
    assert [(t.name, t.joints[0].name, t.actuators[0].name) for t in robot.transmissions] == [
        ("transmission_j_abad_0", "j_abad_0", "motor_j_abad_0"),
        ("transmission_j_hip_0", "j_hip_0", "motor_j_hip_0"),
    ]
    assert [j.name for j in robot.ros2_controls[0].joints] == ["j_abad_0", "j_hip_0"]
    assert robot.sensors[0].parent_joint == "j_hip_0"
    assert robot.extensions[0].reference == "j_hip_0" and 'reference="j_hip_0"' in robot.extensions[0].xml
    assert codes(c) == ["renamed"] * 6


def test_rename_regex_links_and_mimic() -> None:
    robot = chain("l0", "l1", "l2", joint_names=["1", "2"])
    robot.joints[1].mimic = Mimic("1")
    rename(robot, ctx(rename=[parse_rename(r"re:([0-9]+)=j_\1"), parse_rename(r"link:re:l([0-9])=link_\1")]))
    assert [j.name for j in robot.joints] == ["j_1", "j_2"]
    assert robot.joints[1].mimic is not None and robot.joints[1].mimic.joint == "j_1"
    assert [link.name for link in robot.links] == ["link_0", "link_1", "link_2"]
    assert [(j.parent, j.child) for j in robot.joints] == [("link_0", "link_1"), ("link_1", "link_2")]


def test_rename_refuses_duplicates_naming_both() -> None:
    robot = chain("a", "b", "c", joint_names=["x", "y"])
    with pytest.raises(ConfigError, match=r"'x'.*'y'.*'z'"):
        rename(robot, ctx(rename=["x=z", "y=z"]))
    robot = chain("a", "b", "c", joint_names=["x", "y"])
    with pytest.raises(ConfigError, match=r"'y'.*'x'"):
        rename(robot, ctx(rename=["x=y"]))  # y exists and is not renamed


def test_unused_rule_is_reported() -> None:
    c = ctx(rename=["nope=x"])
    rename(chain("a", "b"), c)
    assert codes(c) == ["rename-unused"]


def test_sanitize_runs_after_rename_in_pipeline() -> None:
    robot = chain("a", "b", "c", joint_names=["0", "1"])
    findings = run_passes(robot, options=PassOptions(rename=(RenameRule("0", "hip"),), sanitize_names=True))
    assert [j.name for j in robot.joints] == ["hip", "a1"]
    assert {f.stage for f in findings} == {"pass:rename", "pass:sanitize_names"}
