"""Robots the SDF and ROS 2 tests share: small URDF fixtures, one with sensors added as IR, and Spirit."""

from __future__ import annotations

import copy
import math
from pathlib import Path

from robodesc.frontends.load import load_path
from robodesc.ir.geometry import Inertia, Pose
from robodesc.ir.model import (
    CameraSpec,
    FixedFrame,
    RayAxis,
    RaySpec,
    Robot,
    Sensor,
    SensorType,
)
from tests.conftest import SPIRIT_XACRO

DATA = Path(__file__).resolve().parent / "data"
GOLDEN = Path(__file__).resolve().parent / "golden"


def arm() -> Robot:
    return load_path(str(DATA / "arm.urdf")).robot


def gripper() -> Robot:
    return load_path(str(DATA / "gripper.urdf")).robot


def sensor_bot() -> Robot:
    robot = load_path(str(DATA / "sensor_bot.urdf")).robot
    robot.sensors = [
        Sensor(
            "front_camera",
            SensorType.CAMERA,
            "camera_mount",
            origin=Pose((0.03, 0.0, 0.0)),
            update_rate=30.0,
            camera=CameraSpec(width=640, height=480, hfov=1.047, format="R8G8B8", near=0.05, far=50.0),
            noise=0.007,
        ),
        Sensor(
            "depth",
            SensorType.DEPTH,
            "camera_mount",
            origin=Pose((0.03, 0.02, 0.0)),
            update_rate=15.0,
            camera=CameraSpec(width=320, height=240, hfov=1.2, near=0.1, far=10.0),
        ),
        Sensor(
            "lidar",
            SensorType.RAY,
            "head",
            origin=Pose((0.0, 0.0, 0.08)),
            update_rate=10.0,
            ray=RaySpec(
                horizontal=RayAxis(samples=360, resolution=1.0, min_angle=-math.pi, max_angle=math.pi),
                vertical=RayAxis(samples=16, min_angle=-0.26, max_angle=0.26),
                min_range=0.1,
                max_range=30.0,
            ),
            noise=0.01,
        ),
        Sensor("imu", SensorType.IMU, "base", origin=Pose((0.0, 0.0, 0.02)), update_rate=200.0),
        Sensor("tilt_ft", SensorType.FORCE_TORQUE, "camera_mount", parent_joint="tilt", update_rate=100.0),
        Sensor("bumper_contact", SensorType.CONTACT, "bumper", update_rate=50.0, topic="bumper/contacts"),
        Sensor("gps", SensorType.GPS, "base", origin=Pose((-0.1, 0.0, 0.05)), update_rate=5.0),
    ]
    robot.fixed_frames = [
        FixedFrame("camera_optical", "camera_mount", origin=Pose((0.03, 0, 0), (-1.5708, 0, -1.5708)))
    ]
    return robot


def spirit() -> Robot:
    """Spirit with a valid tensor for its two name-plate links (the source gives them zero inertia)."""
    robot = load_path(str(SPIRIT_XACRO)).robot
    for name in ("text_left", "text_right"):
        inertial = robot.link(name).inertial
        assert inertial is not None and inertial.mass is not None
        inertial.inertia = Inertia(1e-9, 1e-9, 1e-9)
    return robot


def copy_of(robot: Robot) -> Robot:
    return copy.deepcopy(robot)
