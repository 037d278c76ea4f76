"""HoloScript's flagship Isaac arm (../shared/corpus/holoscript/isaac-sim-robot-arm.holo)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robodesc.frontends.holo.lower import load_holo
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.ir.diagnostics import BrokenReferenceError
from robodesc.ir.geometry import Box, Cylinder, Mesh
from robodesc.ir.model import JointType, Robot, SensorType
from robodesc.ir.transforms import forward_kinematics, pose_matrix
from tests.conftest import EXAMPLES, HOLO_ARM

ARM = str(HOLO_ARM)
PRIMITIVE = LoadOptions(missing_mesh=MissingMesh.PRIMITIVE)
MASSES = {
    "BaseLink": 10.0,
    "ShoulderJoint": 0.5,
    "UpperArm": 2.0,
    "ElbowJoint": 0.3,
    "Forearm": 1.0,
    "EndEffector": 0.5,
}
# World (composition) positions the .holo declares.
WORLD_Z = {
    "BaseLink": 0.05,
    "ShoulderJoint": 0.1,
    "UpperArm": 0.35,
    "ElbowJoint": 0.55,
    "Forearm": 0.75,
    "EndEffector": 0.92,
}


@pytest.fixture(scope="module")
def arm() -> Robot:
    return load_path(ARM, PRIMITIVE).robot


def world(robot: Robot, q: dict[str, float] | None = None) -> dict[str, np.ndarray]:
    """Link poses in the composition's world: the robot's placement times forward kinematics."""
    place = pose_matrix(robot.placement)
    return {name: place @ m for name, m in forward_kinematics(robot, q).items()}


def test_missing_gripper_mesh_is_a_clear_error() -> None:
    with pytest.raises(BrokenReferenceError) as info:
        load_path(ARM, LoadOptions(missing_mesh=MissingMesh.ERROR))  # a warning by default
    text = str(info.value)
    assert text.startswith(f"{ARM}:155:15: object 'EndEffector': mesh file 'gripper_v2.stl' does not exist")


def test_missing_mesh_policies() -> None:
    warn = load_path(ARM, LoadOptions(missing_mesh=MissingMesh.WARN))
    geom = warn.robot.link("EndEffector").visuals[0].geometry
    assert isinstance(geom, Mesh) and geom.uri == "gripper_v2.stl" and geom.path is None
    assert geom.scale == (0.05, 0.05, 0.05)
    assert any(f.code == "missing-mesh" and "reference kept" in f.message for f in warn.findings)

    prim = load_path(ARM, PRIMITIVE)
    box = prim.robot.link("EndEffector").visuals[0].geometry
    assert isinstance(box, Box) and box.size == (0.05, 0.05, 0.05)
    assert any(f.code == "missing-mesh" and "box of its declared scale" in f.message for f in prim.findings)

    drop = load_path(ARM, LoadOptions(missing_mesh=MissingMesh.DROP))
    ee = drop.robot.link("EndEffector")
    assert ee.visuals == [] and ee.collisions == []
    assert ee.inertial is not None and ee.inertial.mass == 0.5
    assert any(f.code == "missing-mesh" and "dropped" in f.message for f in drop.findings)


def test_chain_the_author_meant(arm: Robot) -> None:
    parents = {j.child: j.parent for j in arm.joints}
    assert parents == {
        "ShoulderJoint": "BaseLink",
        "UpperArm": "ShoulderJoint",
        "ElbowJoint": "UpperArm",
        "Forearm": "ElbowJoint",
        "EndEffector": "Forearm",
    }
    assert arm.root.name == "BaseLink"
    assert arm.fixed_base is True


def test_inferred_parents_are_reported() -> None:
    loaded = load_path(ARM, PRIMITIVE)
    inferred = {f.element for f in loaded.findings if f.code == "inferred-parent"}
    assert inferred == {"object 'UpperArm'", "object 'Forearm'", "object 'EndEffector'"}
    ignored = [f for f in loaded.findings if f.code == "ignored-block"]
    assert len(ignored) == 1 and "'logic'" in ignored[0].message and ignored[0].loc is not None
    assert ignored[0].loc.line == 171


def test_revolute_joints_axes_and_limits(arm: Robot) -> None:
    shoulder, elbow = arm.joint("ShoulderJoint_joint"), arm.joint("ElbowJoint_joint")
    assert shoulder.type is JointType.REVOLUTE and elbow.type is JointType.REVOLUTE
    assert shoulder.axis == (0.0, 0.0, 1.0)
    assert elbow.axis == (0.0, 1.0, 0.0)
    assert shoulder.limit is not None and elbow.limit is not None
    assert shoulder.limit.lower == pytest.approx(-math.pi) and shoulder.limit.upper == pytest.approx(math.pi)
    assert elbow.limit.lower == pytest.approx(-3 * math.pi / 4) and elbow.limit.upper == pytest.approx(3 * math.pi / 4)
    assert (shoulder.limit.effort, shoulder.limit.velocity) == (10.0, 2.0)
    assert (elbow.limit.effort, elbow.limit.velocity) == (5.0, 1.5)
    assert shoulder.dynamics is not None and (shoulder.dynamics.damping, shoulder.dynamics.friction) == (0.5, 0.1)
    assert [j.type for j in arm.joints].count(JointType.FIXED) == 3
    assert arm.dof == 2


def test_every_mass_is_the_declared_one(arm: Robot) -> None:
    masses = {link.name: link.inertial.mass for link in arm.links if link.inertial is not None}
    assert masses == MASSES
    upper = arm.link("UpperArm").inertial
    assert upper is not None and upper.inertia is not None
    assert upper.inertia.as_tuple() == (0.027083, 0.027083, 0.000833, 0.0, 0.0, 0.0)
    # No tensor given: left for the geometric-inertia pass.
    base = arm.link("BaseLink").inertial
    assert base is not None and base.inertia is None


def test_world_positions_at_zero_pose(arm: Robot) -> None:
    assert arm.placement is not None and arm.placement.xyz == (0.0, 0.0, 0.05)
    poses = world(arm)
    for name, z in WORLD_Z.items():
        assert poses[name][:3, 3] == pytest.approx([0.0, 0.0, z], abs=1e-12), name
    # Visuals sit at the link origin: the world position is not applied twice (HoloScript's 1.84).
    for link in arm.links:
        for visual in link.visuals:
            assert visual.origin is None or visual.origin.is_identity()


def test_shoulder_turns_everything_above_it(arm: Robot) -> None:
    q = {"ShoulderJoint_joint": math.pi / 2}
    turned = world(arm, q)
    rest = world(arm)
    # The end effector sits on the shoulder axis: it keeps its place and turns 90° about z.
    assert turned["EndEffector"][:3, 3] == pytest.approx(rest["EndEffector"][:3, 3], abs=1e-12)
    rz90 = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    for name in ("UpperArm", "ElbowJoint", "Forearm", "EndEffector"):
        assert turned[name][:3, :3] == pytest.approx(rz90, abs=1e-12), name
    assert turned["BaseLink"][:3, :3] == pytest.approx(np.eye(3))


def test_elbow_then_shoulder_moves_the_end_effector(arm: Robot) -> None:
    # Elbow at z = 0.55; the end effector is 0.37 above it. Bending the elbow +90° about y swings
    # the end effector to +x; turning the shoulder +90° about z then carries it to +y.
    bent = world(arm, {"ElbowJoint_joint": math.pi / 2})
    assert bent["EndEffector"][:3, 3] == pytest.approx([0.37, 0.0, 0.55], abs=1e-12)
    both = world(arm, {"ElbowJoint_joint": math.pi / 2, "ShoulderJoint_joint": math.pi / 2})
    assert both["EndEffector"][:3, 3] == pytest.approx([0.0, 0.37, 0.55], abs=1e-12)
    # Random joint values: the end effector is where the planar formula puts it.
    rng = np.random.default_rng(7)
    for _ in range(20):
        t1, t2 = rng.uniform(-math.pi, math.pi), rng.uniform(-3 * math.pi / 4, 3 * math.pi / 4)
        p = world(arm, {"ShoulderJoint_joint": t1, "ElbowJoint_joint": t2})["EndEffector"][:3, 3]
        r = 0.37 * math.sin(t2)
        assert p == pytest.approx([r * math.cos(t1), r * math.sin(t1), 0.55 + 0.37 * math.cos(t2)], abs=1e-12)


def test_primitive_shapes_follow_the_scale(arm: Robot) -> None:
    base = arm.link("BaseLink").visuals[0].geometry
    assert isinstance(base, Cylinder) and (base.radius, base.length) == (0.075, 0.1)
    upper = arm.link("UpperArm").visuals[0].geometry
    assert isinstance(upper, Box) and upper.size == (0.05, 0.05, 0.4)
    # Only @collidable objects collide.
    colliding = {link.name for link in arm.links if link.collisions}
    assert colliding == {"BaseLink", "UpperArm", "Forearm", "EndEffector"}
    colors = {link.name: link.visuals[0].material for link in arm.links}
    red = colors["ShoulderJoint"]
    assert red is not None and red.color == pytest.approx((0xE5 / 255, 0x3E / 255, 0x3E / 255, 1.0))
    upper_mat = colors["UpperArm"]
    assert upper_mat is not None and upper_mat.name == "aluminum_3080c0"


def test_sensors_frames_and_actuators(arm: Robot) -> None:
    sensors = {s.name: s for s in arm.sensors}
    assert set(sensors) == {"EndEffector_camera", "EndEffector_force_torque"}
    cam = sensors["EndEffector_camera"]
    assert cam.parent == "EndEffector" and cam.type is SensorType.CAMERA
    assert cam.camera is not None and (cam.camera.width, cam.camera.height, cam.camera.hfov) == (640, 480, 1.2)
    assert cam.topic == "/wrist_camera/image_raw"
    assert sensors["EndEffector_force_torque"].type is SensorType.FORCE_TORQUE
    assert [(f.name, f.parent) for f in arm.fixed_frames] == [("wrist_camera_frame", "EndEffector")]
    trans = {t.joints[0].name: t for t in arm.transmissions}
    assert set(trans) == {"ShoulderJoint_joint", "ElbowJoint_joint"}
    assert trans["ShoulderJoint_joint"].type == "transmission_interface/SimpleTransmission"
    assert trans["ShoulderJoint_joint"].joints[0].hardware_interfaces == ["hardware_interface/PositionJointInterface"]


def test_load_holo_returns_the_same_robot() -> None:
    result = load_holo(ARM, PRIMITIVE)
    assert result.props == []
    assert result.gravity == (0.0, 0.0, -9.81)
    assert [link.name for link in result.robot.links] == list(MASSES)


def test_yaml_twin_gives_the_same_ir_numbers(arm: Robot) -> None:
    twin = load_path(str(EXAMPLES / "isaac_arm.yaml"), PRIMITIVE).robot
    assert (twin.name, twin.placement, twin.fixed_base) == (arm.name, arm.placement, arm.fixed_base)
    assert [j.name for j in twin.joints] == [j.name for j in arm.joints]
    for a, b in zip(arm.joints, twin.joints, strict=True):
        assert (a.type, a.parent, a.child, a.axis) == (b.type, b.parent, b.child, b.axis), a.name
        assert a.origin is not None and b.origin is not None
        assert (a.origin.xyz, a.origin.rpy) == (b.origin.xyz, b.origin.rpy)
        for field in ("lower", "upper", "effort", "velocity"):
            assert getattr(a.limit, field, None) == pytest.approx(getattr(b.limit, field, None), abs=1e-14)
        assert (a.dynamics is None) == (b.dynamics is None)
        if a.dynamics is not None and b.dynamics is not None:
            assert (a.dynamics.damping, a.dynamics.friction) == (b.dynamics.damping, b.dynamics.friction)
    for la, lb in zip(arm.links, twin.links, strict=True):
        assert la.name == lb.name
        assert la.inertial is not None and lb.inertial is not None
        assert la.inertial.mass == lb.inertial.mass
        ia, ib = la.inertial.inertia, lb.inertial.inertia
        assert (ia.as_tuple() if ia else None) == (ib.as_tuple() if ib else None)
        assert [type(v.geometry) for v in la.visuals] == [type(v.geometry) for v in lb.visuals]
        assert [_shape(v.geometry) for v in la.visuals] == [_shape(v.geometry) for v in lb.visuals]
        assert [v.material.name if v.material else None for v in la.visuals] == [
            v.material.name if v.material else None for v in lb.visuals
        ]
        assert len(la.collisions) == len(lb.collisions)
    assert [(s.name, s.type, s.parent, s.topic) for s in arm.sensors] == [
        (s.name, s.type, s.parent, s.topic) for s in twin.sensors
    ]
    assert twin.sensors[0].camera is not None and twin.sensors[0].camera.hfov == pytest.approx(1.2, abs=1e-14)
    assert [(f.name, f.parent) for f in arm.fixed_frames] == [(f.name, f.parent) for f in twin.fixed_frames]
    assert [(t.name, t.type) for t in arm.transmissions] == [(t.name, t.type) for t in twin.transmissions]
    q = {"ShoulderJoint_joint": 0.3, "ElbowJoint_joint": -1.1}
    fa, fb = world(arm, q), world(twin, q)
    for name in fa:
        assert fa[name] == pytest.approx(fb[name], abs=1e-12)


def _shape(geom: object) -> object:
    if isinstance(geom, Box):
        return geom.size
    if isinstance(geom, Cylinder):
        return (geom.radius, geom.length)
    return None
