"""SDF naming rules, frames, loop joints, joint types and findings."""

from __future__ import annotations

from lxml import etree

from robodesc.emit.sdf import SdfOptions, build_sdf, emit_sdf
from robodesc.frontends.load import load_string
from robodesc.ir.geometry import Pose
from robodesc.ir.model import Joint, JointType, Link, LoopFrame, LoopJoint, Robot
from tests.sdf import fixtures as fx

CLASH = """<robot name="world">
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="base" type="revolute"><parent link="base"/><child link="__model__"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="__model__"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="a::b" type="fixed"><parent link="__model__"/><child link="world"/></joint>
  <link name="world"/>
</robot>"""


def _tree(text: str) -> etree._Element:
    return etree.fromstring(text.encode())


def test_reserved_and_duplicate_names_are_renamed_with_findings() -> None:
    robot = load_string(CLASH).robot
    result = build_sdf(robot, SdfOptions())
    model = _tree(result.text).find("model")
    assert model is not None
    assert model.get("name") == "world_model"
    links = [el.get("name") for el in model.findall("link")]
    joints = [el.get("name") for el in model.findall("joint")]
    assert links == ["base", "model", "world_link"]
    assert joints == ["base_joint", "a_b"]
    assert model.find("joint[@name='base_joint']/child").text == "model"  # type: ignore[union-attr]
    renamed = sorted(f.element for f in result.findings if f.code == "sdf-rename")
    assert renamed == ["joint 'a::b'", "joint 'base'", "link '__model__'", "link 'world'", "robot 'world'"]
    assert result.names.get("link", "__model__") == "model"
    # Deterministic.
    assert build_sdf(load_string(CLASH).robot, SdfOptions()).text == result.text


def test_fixed_frames_are_frames() -> None:
    model = _tree(emit_sdf(fx.sensor_bot(), SdfOptions())[0]).find("model")
    assert model is not None
    frame = model.find("frame[@name='camera_optical']")
    assert frame is not None and frame.get("attached_to") == "camera_mount"
    assert frame.find("pose").get("relative_to") == "camera_mount"  # type: ignore[union-attr]


def _two_link(kind: JointType) -> Robot:
    robot = fx.gripper()
    robot.joints[0].type = kind
    return robot


def test_spherical_is_ball_and_floating_is_reported() -> None:
    ball = _tree(emit_sdf(_two_link(JointType.SPHERICAL), SdfOptions())[0])
    assert ball.find("model/joint[@name='finger_joint']").get("type") == "ball"  # type: ignore[union-attr]
    text, findings = emit_sdf(_two_link(JointType.FLOATING), SdfOptions())
    assert _tree(text).find("model/joint[@name='finger_joint']") is None
    assert [f.code for f in findings if f.code == "sdf-joint-dropped"] == ["sdf-joint-dropped"]
    # The freed link keeps its zero pose, given relative to its old parent.
    pose = _tree(text).find("model/link[@name='left_finger']/pose")
    assert pose is not None and pose.get("relative_to") == "palm" and pose.text == "0.03 0 0.01 0 0 0"


def test_loop_joint_is_written_with_a_finding() -> None:
    robot = fx.gripper()
    robot.loop_joints = [
        LoopJoint("closure", "spherical", LoopFrame("left_tip"), LoopFrame("right_finger", Pose((0, 0, 0.04))))
    ]
    text, findings = emit_sdf(robot, SdfOptions())
    joint = _tree(text).find("model/joint[@name='closure']")
    assert joint is not None and joint.get("type") == "ball"
    assert joint.findtext("parent") == "left_tip" and joint.findtext("child") == "right_finger"
    assert any(f.code == "sdf-loop-joint" and "Drake" in f.message for f in findings)


def test_massless_link_gets_explicit_zero_inertial() -> None:
    robot = Robot("r", links=[Link("a"), Link("b")], joints=[Joint("j", JointType.FIXED, "a", "b")])
    model = _tree(emit_sdf(robot, SdfOptions())[0])
    assert model.findtext("model/link[@name='b']/inertial/mass") == "0"
    assert model.findtext("model/link[@name='b']/inertial/inertia/ixx") == "0"


def test_versions_and_mesh_paths() -> None:
    for version in ("1.9", "1.10", "1.11"):
        assert f'<sdf version="{version}">' in emit_sdf(fx.arm(), SdfOptions(version=version))[0]
    text, findings = emit_sdf(fx.arm(), SdfOptions(version="1.7"))
    assert "<capsule>" not in text and any(f.code == "sdf-capsule" for f in findings)
    absolute = emit_sdf(fx.arm(), SdfOptions())[0]
    assert f"<uri>{fx.DATA / 'meshes' / 'tool.obj'}</uri>" in absolute
    relative = emit_sdf(fx.arm(), SdfOptions(out_dir=str(fx.DATA)))[0]
    assert "<uri>meshes/tool.obj</uri>" in relative


def test_unknown_version_is_a_config_error() -> None:
    import pytest

    from robodesc.ir.diagnostics import ConfigError

    with pytest.raises(ConfigError):
        emit_sdf(fx.arm(), SdfOptions(version="2.0"))
