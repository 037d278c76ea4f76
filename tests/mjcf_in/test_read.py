"""The MJCF frontend: what it reads from each element, and what it says it cannot hold."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from robodesc.frontends.load import frontend_for, load_path
from robodesc.ir.model import JointType, Robot, SensorType
from robodesc.ir.rigid import link_frames, pose_frame
from robodesc.ir.verify import verify

DATA = Path(__file__).parent / "data"
FEATURES = DATA / "features.xml"


@pytest.fixture(scope="module")
def loaded() -> tuple[Robot, list[tuple[str, str, str]]]:
    result = load_path(str(FEATURES))
    findings = [(f.severity.value, f.code, f.render()) for f in result.findings]
    return result.robot, findings


def test_chosen_by_content_and_suffix(tmp_path: Path) -> None:
    assert frontend_for(str(FEATURES)).name == "mjcf"
    copy = tmp_path / "model.mjcf"
    copy.write_text(FEATURES.read_text().replace('file="parts/defaults.xml"', f'file="{DATA}/parts/defaults.xml"'))
    assert frontend_for(str(copy)).name == "mjcf"
    urdf = tmp_path / "robot.xml"
    urdf.write_text('<robot name="r"><link name="a"/></robot>')
    assert frontend_for(str(urdf)).name == "urdf"


def test_tree_and_root(loaded: tuple[Robot, list[tuple[str, str, str]]]) -> None:
    robot, _ = loaded
    assert robot.name == "features"
    assert robot.root.name == "base"
    assert robot.fixed_base is False  # a <freejoint/>
    assert robot.placement is not None
    assert robot.placement.xyz == pytest.approx((0.0, 0.0, 0.5))
    assert robot.placement.rpy == pytest.approx((0.0, 0.0, math.radians(30)))
    # The two-hinge wrist: a massless link between its joints.
    joints = robot.joint_map()
    assert joints["wrist_pitch"].child == "wrist_pitch_link"
    assert joints["wrist_roll"].parent == "wrist_pitch_link"
    assert joints["wrist_roll"].child == "wrist"
    assert robot.link("wrist_pitch_link").inertial is None
    assert [f for f in verify(robot) if f.severity.value == "error"] == []


def test_joints(loaded: tuple[Robot, list[tuple[str, str, str]]]) -> None:
    robot, _ = loaded
    j = robot.joint_map()
    shoulder = j["shoulder"]
    assert shoulder.type is JointType.REVOLUTE
    # Degrees in the file, radians in the IR, moved by ref (10 deg): the IR's zero is the ref.
    assert shoulder.limit is not None
    assert shoulder.limit.lower == pytest.approx(math.radians(-130))
    assert shoulder.limit.upper == pytest.approx(math.radians(110))
    assert shoulder.limit.effort == pytest.approx(20.0)  # the position servo's forcerange
    assert shoulder.dynamics is not None
    assert shoulder.dynamics.damping == pytest.approx(0.5)
    assert shoulder.dynamics.friction == pytest.approx(0.1)
    assert shoulder.dynamics.spring_stiffness == pytest.approx(3.0)
    assert shoulder.dynamics.spring_reference == pytest.approx(math.radians(10))  # springref 20 - ref 10
    assert shoulder.armature == pytest.approx(0.01)  # from the childclass
    # The joint turns about its anchor (pos 0.02 0 0): the IR joint sits there.
    assert shoulder.origin is not None
    base_to_arm = pose_frame(shoulder.origin)
    assert base_to_arm.translation == pytest.approx((0.2, 0.02, 0.0), abs=1e-12)
    # The childclass's range and the top default's damping.
    assert j["wrist_roll"].type is JointType.REVOLUTE
    assert j["wrist_roll"].limit is not None and j["wrist_roll"].limit.upper == pytest.approx(math.radians(120))
    assert j["wrist_roll"].dynamics is not None and j["wrist_roll"].dynamics.damping == pytest.approx(0.05)
    assert j["wrist_roll"].limit is not None and j["wrist_roll"].limit.effort == pytest.approx(5.0)
    # A motor: its control range times its gear.
    assert j["wrist_pitch"].limit is not None and j["wrist_pitch"].limit.effort == pytest.approx(15.0)
    slide = j["slide"]
    assert slide.type is JointType.PRISMATIC
    assert slide.limit is not None and (slide.limit.lower, slide.limit.upper) == pytest.approx((0.0, 0.1))
    assert slide.limit.effort == pytest.approx(40.0)
    assert slide.armature == pytest.approx(0.02)
    assert j["ball"].type is JointType.SPHERICAL
    assert j["plate_hinge"].type is JointType.CONTINUOUS


def test_geometry_and_inertia(loaded: tuple[Robot, list[tuple[str, str, str]]]) -> None:
    robot, _ = loaded
    arm = robot.link("arm")
    assert arm.inertial is not None and arm.inertial.mass == pytest.approx(1.5)
    # Inertia from geoms, as MuJoCo computes it: the box (500 kg/m³) and the ellipsoid (1000).
    base = robot.link("base")
    assert base.inertial is not None
    box = 500 * 0.4 * 0.2 * 0.1
    shell = 1000 * 4 / 3 * math.pi * 0.05 * 0.04 * 0.03
    assert base.inertial.mass == pytest.approx(box + shell, rel=1e-9)
    kinds = sorted(type(c.geometry).__name__ for c in arm.collisions)
    assert kinds == ["Capsule"]
    capsule = arm.collisions[0]
    assert capsule.geometry.length == pytest.approx(0.2)  # type: ignore[union-attr]
    assert capsule.contact is not None
    assert capsule.contact.mu == pytest.approx(0.7)
    # MuJoCo's friction is isotropic: both directions (SDF's mu2 would default to 1, which Drake reads
    # as a dynamic friction above the static 0.7 and refuses).
    assert capsule.contact.mu2 == pytest.approx(0.7)
    assert capsule.contact.torsional == pytest.approx(0.01)
    assert capsule.contact.kp is not None and capsule.contact.kd is not None
    mesh = next(v for v in arm.visuals if type(v.geometry).__name__ == "Mesh")
    assert mesh.geometry.scale == (2.0, 1.0, 0.5)  # type: ignore[union-attr]
    assert mesh.geometry.path == str(DATA / "parts" / "wedge.stl")  # type: ignore[union-attr]
    assert mesh.material is not None and mesh.material.name == "steel"
    assert all(len(link.collisions) == 0 for link in robot.links if link.name == "world")


def test_actuators_equalities_sensors(loaded: tuple[Robot, list[tuple[str, str, str]]]) -> None:
    robot, _ = loaded
    j = robot.joint_map()
    follower = j["follower"]
    assert follower.mimic is not None
    # q_f = 0.1 - 2 q_p in MuJoCo; no refs here, so the same in the IR.
    assert (follower.mimic.joint, follower.mimic.multiplier, follower.mimic.offset) == ("wrist_pitch", -2.0, 0.1)
    loops = {loop.name: loop for loop in robot.loop_joints}
    assert loops["close"].type == "spherical" and loops["bolt"].type == "fixed"
    # The closure's two frames coincide at qpos0.
    frames = link_frames(robot)
    for loop in loops.values():
        a = frames[loop.link1.link] @ pose_frame(loop.link1.origin)
        b = frames[loop.link2.link] @ pose_frame(loop.link2.origin)
        assert a.translation == pytest.approx(b.translation, abs=1e-9)
    gears = {t.actuators[0].name: t.actuators[0].mechanical_reduction for t in robot.transmissions}
    assert gears["pitch_motor"] == 10.0
    sensors = {s.name: s for s in robot.sensors}
    assert sensors["imu_acc"].type is SensorType.IMU and "imu_gyro" not in sensors
    assert sensors["ft_force"].type is SensorType.FORCE_TORQUE
    assert sensors["tip_touch"].type is SensorType.CONTACT
    eye = sensors["eye"]
    assert eye.type is SensorType.CAMERA and eye.camera is not None
    assert (eye.camera.width, eye.camera.height) == (640, 480)
    # fovy 60 deg at 4:3 is a horizontal field of 2 atan(tan(30 deg) 4/3).
    assert eye.camera.hfov == pytest.approx(2 * math.atan(math.tan(math.radians(30)) * 4 / 3))
    # The camera looks along its -Z (xyaxes 0 -1 0 0 0 1: -Z is +X of the base); the IR's along +X.
    look = pose_frame(eye.origin).rotation
    assert [look[i][0] for i in range(3)] == pytest.approx([1.0, 0.0, 0.0], abs=1e-9)
    assert {f.name for f in robot.fixed_frames} >= {"imu_site", "ft_site", "tip"}
    # The keyframe named home, not the first; IR positions are qpos - ref.
    assert robot.initial_positions["shoulder"] == pytest.approx(0.3 - math.radians(10))
    assert robot.initial_positions["slide"] == pytest.approx(0.05)


def test_everything_not_held_is_named(loaded: tuple[Robot, list[tuple[str, str, str]]]) -> None:
    _, findings = loaded
    warned = {code for severity, code, _ in findings if severity == "warning"}
    assert {
        "mjcf-ellipsoid",
        "mjcf-not-held",
        "mjcf-actuator-not-held",
        "mjcf-contact-exclude",
        "mjcf-contact-pair",
    } <= warned
    tendon = next(text for _, code, text in findings if code == "mjcf-not-held")
    assert "features.xml:58" in tendon and "'coupler'" in tendon
    # Each message names its file and line; an included file's element names the included file.
    assert all(".xml:" in text for severity, _, text in findings if severity == "warning")


def test_drives(loaded: tuple[Robot, list[tuple[str, str, str]]]) -> None:
    robot, _ = loaded
    drives = {j.name: j.drive for j in robot.joints if j.drive is not None}
    assert set(drives) == {"shoulder", "wrist_pitch", "wrist_roll", "slide"}
    assert (drives["shoulder"].kind, drives["shoulder"].stiffness, drives["shoulder"].damping) == ("position", 50, 2)
    # A <general> with biasprm 0 -kp -kv is the position servo it is.
    assert (drives["slide"].kind, drives["slide"].stiffness, drives["slide"].damping) == ("position", 200, 10)
    assert (drives["wrist_roll"].kind, drives["wrist_roll"].damping) == ("velocity", 3)
    assert drives["wrist_pitch"].kind == "effort"


def test_attached_models_and_several_top_bodies(tmp_path: Path) -> None:
    """<attach> (MuJoCo 3.2+) places a model file's body; two top bodies hang from a world link."""
    (tmp_path / "arm.xml").write_text(
        '<mujoco model="arm"><worldbody><body name="base"><joint name="j" axis="0 0 1"/>'
        '<geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/></body></worldbody></mujoco>'
    )
    scene = tmp_path / "scene.xml"
    scene.write_text(
        '<mujoco model="two arms"><asset><model name="arm" file="arm.xml"/></asset><worldbody>'
        '<body name="left" pos="0 0.3 0"><attach model="arm" body="base" prefix="l_"/></body>'
        '<body name="right" pos="0 -0.3 0"><attach model="arm" body="base" prefix="r_"/></body>'
        "</worldbody></mujoco>"
    )
    robot = load_path(str(scene)).robot
    assert robot.root.name == "world"
    joints = robot.joint_map()
    assert joints["l_j"].parent == "left" and joints["r_j"].type is JointType.CONTINUOUS
    assert pose_frame(joints["left_fixed"].origin).translation == pytest.approx((0.0, 0.3, 0.0))


def test_scene_objects_are_left_out_with_a_warning(tmp_path: Path) -> None:
    scene = tmp_path / "scene.xml"
    scene.write_text(
        '<mujoco model="arm on a table"><worldbody><geom name="floor" type="plane" size="5 5 0.1"/>'
        '<body name="table" pos="0 0 0.4"><geom type="box" size="0.5 0.5 0.02"/></body>'
        '<body name="cube" pos="0.2 0 0.5"><freejoint/><geom type="box" size="0.02 0.02 0.02"/><site name="s"/></body>'
        '<body name="arm" pos="0 0 0.42"><geom type="cylinder" size="0.05 0.02"/>'
        '<body name="link" pos="0 0 0.05"><joint name="j" axis="0 0 1"/><geom type="capsule" fromto="0 0 0 0.3 0 0" '
        'size="0.02"/></body></body></worldbody></mujoco>'
    )
    result = load_path(str(scene))
    robot = result.robot
    assert robot.root.name == "arm" and robot.fixed_base is True
    assert {link.name for link in robot.links} == {"arm", "link"}
    found = [f for f in result.findings if f.code == "mjcf-scene-object"]
    assert len(found) == 1 and "'table', 'cube'" in found[0].message
    assert not [f for f in result.findings if f.code in ("mjcf-world-geom", "mjcf-world-frame")]


def test_chained_joint_equalities_become_one_leader(tmp_path: Path) -> None:
    # Stretch's telescoping arm: l0 follows l1, l1 follows l2. URDF readers refuse a mimic of a
    # mimic (Newton's add_urdf raised on Stretch and TALOS); the maps compose exactly.
    source = tmp_path / "chain.xml"
    source.write_text(
        """<mujoco model="chain">
  <worldbody>
    <body name="base">
      <geom type="box" size="0.1 0.1 0.1" mass="1"/>
      <body name="a"><joint name="a" type="slide" axis="1 0 0" range="-1 1"/><geom size="0.02" mass="0.1"/>
        <body name="b"><joint name="b" type="slide" axis="1 0 0" range="-1 1"/><geom size="0.02" mass="0.1"/>
          <body name="c"><joint name="c" type="slide" axis="1 0 0" range="-1 1"/><geom size="0.02" mass="0.1"/>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
  <equality>
    <joint joint1="a" joint2="b" polycoef="0.1 2 0 0 0"/>
    <joint joint1="b" joint2="c" polycoef="0.05 3 0 0 0"/>
  </equality>
</mujoco>
""",
        encoding="utf-8",
    )
    loaded = load_path(str(source))
    joints = loaded.robot.joint_map()
    a, b = joints["a"].mimic, joints["b"].mimic
    assert a is not None and b is not None and a.joint == "c" and b.joint == "c"
    # a = 0.1 + 2 b = 0.1 + 2 (0.05 + 3 c) = 0.2 + 6 c
    assert a.multiplier == pytest.approx(6.0) and a.offset == pytest.approx(0.2)
    assert b.multiplier == pytest.approx(3.0) and b.offset == pytest.approx(0.05)
    assert "mjcf-mimic-chain" in {f.code for f in loaded.findings}
