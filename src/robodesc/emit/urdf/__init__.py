"""URDF target (ROS 2, Gazebo and Isaac flavours). Entry point: :func:`emit_urdf`."""

from robodesc.emit.urdf.target import TARGET
from robodesc.emit.urdf.writer import UrdfOptions, emit_urdf

__all__ = ["TARGET", "UrdfOptions", "emit_urdf"]
