"""ROS 2 target: ros2_control URDF, controllers, launch file, ros_gz_bridge YAML and world.
Entry point: :func:`build_ros2_package`."""

from robodesc.emit.ros2.options import CommandInterface, ControllerKind, Ros2Options
from robodesc.emit.ros2.package import Ros2Package, build_ros2_package, emit_ros2_package
from robodesc.emit.ros2.target import TARGET

__all__ = [
    "TARGET",
    "CommandInterface",
    "ControllerKind",
    "Ros2Options",
    "Ros2Package",
    "build_ros2_package",
    "emit_ros2_package",
]
