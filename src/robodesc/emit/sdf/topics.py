"""Gazebo topics of the sensors robodesc writes, and their ROS 2 message types.

The SDF emitter writes these topics into ``<sensor><topic>``; the ROS 2 bridge file lists the same
ones, so the two always agree.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from robodesc.ir.model import Robot, Sensor, SensorType


@dataclass(slots=True, frozen=True)
class Topic:
    gz_topic: str
    gz_type: str
    ros_type: str


def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9_/]", "_", text).strip("/") or "sensor"


def sensor_base_topic(robot: Robot, sensor: Sensor) -> str:
    """The sensor's own topic when the input gave one, else ``<robot>/<sensor>``."""
    if sensor.topic:
        return _slug(sensor.topic)
    return f"{_slug(robot.name)}/{_slug(sensor.name)}"


IMAGE = ("gz.msgs.Image", "sensor_msgs/msg/Image")
CAMERA_INFO = ("gz.msgs.CameraInfo", "sensor_msgs/msg/CameraInfo")
POINTS = ("gz.msgs.PointCloudPacked", "sensor_msgs/msg/PointCloud2")


def sensor_topics(robot: Robot, sensor: Sensor) -> dict[str, Topic]:
    """Every topic Gazebo Harmonic publishes for ``sensor``, keyed by role.

    Role ``main`` is the one written to ``<sensor><topic>``; ``camera_info`` goes to
    ``<camera><camera_info_topic>``; the others Gazebo derives from ``main``.
    """
    base = sensor_base_topic(robot, sensor)
    t = sensor.type
    if t is SensorType.CAMERA:
        return {"main": Topic(f"{base}/image", *IMAGE), "camera_info": Topic(f"{base}/camera_info", *CAMERA_INFO)}
    if t is SensorType.DEPTH:
        return {
            "main": Topic(f"{base}/depth_image", *IMAGE),
            "camera_info": Topic(f"{base}/camera_info", *CAMERA_INFO),
            "points": Topic(f"{base}/depth_image/points", *POINTS),
        }
    if t is SensorType.RAY:
        return {
            "main": Topic(f"{base}/scan", "gz.msgs.LaserScan", "sensor_msgs/msg/LaserScan"),
            "points": Topic(f"{base}/scan/points", *POINTS),
        }
    if t is SensorType.IMU:
        return {"main": Topic(base, "gz.msgs.IMU", "sensor_msgs/msg/Imu")}
    if t is SensorType.FORCE_TORQUE:
        return {"main": Topic(base, "gz.msgs.Wrench", "geometry_msgs/msg/Wrench")}
    if t is SensorType.CONTACT:
        return {"main": Topic(base, "gz.msgs.Contacts", "ros_gz_interfaces/msg/Contacts")}
    if t is SensorType.GPS:
        return {"main": Topic(base, "gz.msgs.NavSat", "sensor_msgs/msg/NavSatFix")}
    raise AssertionError(t)


CLOCK = Topic("clock", "gz.msgs.Clock", "rosgraph_msgs/msg/Clock")
