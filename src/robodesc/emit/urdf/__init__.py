"""URDF target (ROS 2, Gazebo and Isaac flavours). Entry point: :func:`emit_urdf`; what other
targets use: the check of a URDF (:func:`check_urdf`) and the URDF ROS loads (:func:`ros_equivalent`)."""

from robodesc.emit.urdf.check import check_urdf
from robodesc.emit.urdf.ros import ros_equivalent
from robodesc.emit.urdf.target import TARGET
from robodesc.emit.urdf.writer import DEFAULT_EFFORT, DEFAULT_VELOCITY, UrdfOptions, emit_urdf

__all__ = ["DEFAULT_EFFORT", "DEFAULT_VELOCITY", "TARGET", "UrdfOptions", "check_urdf", "emit_urdf", "ros_equivalent"]
