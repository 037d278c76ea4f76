"""The composition examples: each loads, verifies, compiles to URDF, and has the numbers it declares."""

from __future__ import annotations

import importlib.util
import math

import numpy as np
import pytest

from robodesc.emit.urdf import emit_urdf
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.ir.inertia import inertia_problem
from robodesc.ir.model import JointType, Robot, SensorType
from robodesc.ir.transforms import forward_kinematics, pose_matrix
from robodesc.ir.verify import check
from tests.conftest import EXAMPLES, HOLO_ARM

YAML_EXAMPLES = ["arm6_gripper.yaml", "quadruped.yaml", "four_bar.yaml", "mobile_base.yaml", "isaac_arm.yaml"]
OPTS = LoadOptions(missing_mesh=MissingMesh.PRIMITIVE)


def four_bar_py() -> Robot:
    spec = importlib.util.spec_from_file_location("four_bar_example", EXAMPLES / "four_bar.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    robot = module.build()
    assert isinstance(robot, Robot)
    return robot


def load(name: str) -> Robot:
    return load_path(str(EXAMPLES / name), OPTS).robot


@pytest.mark.parametrize("name", YAML_EXAMPLES)
def test_example_loads_verifies_and_emits(name: str) -> None:
    robot = load(name)
    check(robot)
    text = emit_urdf(robot)
    assert f'<robot name="{robot.name}"' in text


def test_every_link_of_every_example_has_its_mass() -> None:
    for name in YAML_EXAMPLES:
        for link in load(name).links:
            assert link.inertial is not None and link.inertial.mass is not None and link.inertial.mass > 0, (
                name,
                link.name,
            )


def test_geometric_inertia_pass_completes_the_examples() -> None:
    geometric_inertia = pytest.importorskip("robodesc.passes.geometric_inertia")
    from robodesc.passes.context import PassContext

    robots = [load(name) for name in YAML_EXAMPLES] + [four_bar_py(), load_path(str(HOLO_ARM), OPTS).robot]
    for robot in robots:
        masses = {link.name: link.inertial.mass for link in robot.links if link.inertial}
        geometric_inertia.geometric_inertia(robot, PassContext())
        for link in robot.links:
            assert link.inertial is not None and link.inertial.inertia is not None, (robot.name, link.name)
            assert inertia_problem(link.inertial.inertia) is None, (robot.name, link.name)
            assert link.inertial.mass == masses[link.name]


def test_arm6_gripper_mimic_opens_both_fingers() -> None:
    robot = load("arm6_gripper.yaml")
    assert robot.dof == 7  # six arm joints and one gripper joint; the other finger mimics
    right = robot.joint("finger_right")
    assert right.mimic is not None and right.mimic.joint == "finger_left"
    fk = forward_kinematics(robot, {"finger_left": 0.02})
    base = np.linalg.inv(fk["gripper_base"])
    left_x = (base @ fk["left_finger"])[0, 3]
    right_x = (base @ fk["right_finger"])[0, 3]
    assert left_x == pytest.approx(0.04) and right_x == pytest.approx(-0.04)
    assert robot.joint("shoulder_lift").limit is not None
    assert robot.joint("shoulder_lift").limit.upper == pytest.approx(math.radians(120))  # type: ignore[union-attr]
    assert robot.joint("wrist_3").type is JointType.CONTINUOUS
    assert {t.joints[0].name for t in robot.transmissions} == {
        "shoulder_pan",
        "shoulder_lift",
        "elbow",
        "wrist_1",
        "wrist_2",
        "wrist_3",
        "finger_left",
    }
    assert [(f.name, f.parent) for f in robot.fixed_frames] == [("tcp", "gripper_base")]


def test_quadruped_legs_are_mirror_images() -> None:
    robot = load("quadruped.yaml")
    assert robot.fixed_base is False
    assert robot.dof == 12 and len(robot.links) == 13
    for joint in robot.actuated_joints():
        assert joint.armature == 0.005
        assert joint.dynamics is not None and joint.dynamics.damping == 0.1  # from the YAML anchor
    frames = {f.name: f for f in robot.fixed_frames}
    assert set(frames) == {"FL_foot", "FR_foot", "RL_foot", "RR_foot"}
    rng = np.random.default_rng(3)
    for _ in range(10):
        q: dict[str, float] = {}
        for joint in ("hip_abd", "hip_flex", "knee"):
            lim = robot.joint(f"FL_{joint}").limit
            assert lim is not None and lim.lower is not None and lim.upper is not None
            v = float(rng.uniform(lim.lower, lim.upper))
            for leg in ("FL", "FR", "RL", "RR"):
                q[f"{leg}_{joint}"] = v
        fk = forward_kinematics(robot, q)

        def foot(leg: str, fk: dict[str, np.ndarray] = fk) -> np.ndarray:
            f = frames[f"{leg}_foot"]
            return (fk[f.parent] @ pose_matrix(f.origin))[:3, 3]

        for left, right in (("FL", "FR"), ("RL", "RR")):
            assert foot(right) == pytest.approx(foot(left) * np.array([1.0, -1.0, 1.0]), abs=1e-12)
        assert foot("FL")[0] - foot("RL")[0] == pytest.approx(0.4)
    assert robot.joint("FR_hip_abd").axis == (-1.0, 0.0, 0.0)  # a rotation axis mirrors as a pseudovector
    assert robot.joint("FR_knee").axis == (0.0, 1.0, 0.0)


def test_four_bar_script_and_yaml_twin_agree_and_close_the_loop() -> None:
    py, yml = four_bar_py(), load("four_bar.yaml")
    assert [j.name for j in py.joints] == [j.name for j in yml.joints]
    for a, b in zip(py.links, yml.links, strict=True):
        assert a.name == b.name
        assert a.inertial is not None and b.inertial is not None
        assert a.inertial.mass == pytest.approx(b.inertial.mass, rel=1e-12)
    for robot in (py, yml):
        assert robot.placement is not None and robot.fixed_base is True
        (loop,) = robot.loop_joints
        assert loop.type == "spherical"
        # The zero pose is the assembled linkage: both sides of the loop joint coincide there.
        fk = forward_kinematics(robot)
        p1 = (fk[loop.link1.link] @ pose_matrix(loop.link1.origin))[:3, 3]
        p2 = (fk[loop.link2.link] @ pose_matrix(loop.link2.origin))[:3, 3]
        assert p1 == pytest.approx(p2, abs=1e-12)
    q = {"crank_joint": 0.4, "coupler_joint": -0.2, "rocker_joint": 0.1}
    fa, fb = forward_kinematics(py, q), forward_kinematics(yml, q)
    for name in fa:
        assert fa[name] == pytest.approx(fb[name], abs=1e-12)


def test_mobile_base_sensors_and_density() -> None:
    robot = load("mobile_base.yaml")
    wheel = robot.link("left_wheel").inertial
    assert wheel is not None and wheel.mass == pytest.approx(1200 * math.pi * 0.08**2 * 0.04)
    sensors = {s.name: s for s in robot.sensors}
    assert {s.type for s in sensors.values()} == {SensorType.RAY, SensorType.CAMERA, SensorType.IMU}
    lidar = sensors["lidar"]
    assert lidar.ray is not None and lidar.ray.horizontal is not None
    assert lidar.ray.horizontal.min_angle == pytest.approx(-math.pi)
    assert lidar.ray.horizontal.samples == 720 and lidar.update_rate == 10
    cam = sensors["front_camera"]
    assert cam.camera is not None and cam.camera.hfov == pytest.approx(math.pi / 2)
    assert [j.type for j in robot.actuated_joints()] == [JointType.CONTINUOUS, JointType.CONTINUOUS]
