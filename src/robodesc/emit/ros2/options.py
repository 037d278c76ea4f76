"""Options of the ROS 2 / Gazebo Harmonic package files (``--ros2``)."""

from __future__ import annotations

import enum
from dataclasses import dataclass, field

from robodesc.emit.common.flags import flag
from robodesc.emit.common.paths import PathMode
from robodesc.emit.urdf import DEFAULT_EFFORT, DEFAULT_VELOCITY


class CommandInterface(enum.Enum):
    POSITION = "position"
    VELOCITY = "velocity"
    EFFORT = "effort"


class ControllerKind(enum.Enum):
    JOINT_TRAJECTORY = "joint_trajectory"  # joint_trajectory_controller/JointTrajectoryController
    FORWARD_COMMAND = "forward_command"  # forward_command_controller/ForwardCommandController


@dataclass(slots=True)
class Ros2Options:
    command_interface: CommandInterface = field(
        default=CommandInterface.POSITION, metadata=flag("what the controllers command (default position)")
    )
    controller: ControllerKind = field(
        default=ControllerKind.JOINT_TRAJECTORY, metadata=flag("the command controller (default joint_trajectory)")
    )
    update_rate: int = 100  # controller_manager's loop rate (Hz)
    # The URDF travels over the robot_description topic, where a relative mesh path means nothing,
    # so meshes are absolute by default (PACKAGE suits an installed ROS package).
    path_mode: PathMode = PathMode.ABSOLUTE
    out_dir: str | None = None
    # Height at which ros_gz_sim spawns the robot (m).
    spawn_z: float = 0.0
    # What the URDF writes so that urdfdom loads it (emit/urdf/writer.py, emit/urdf/ros.py): effort
    # and velocity for a revolute/prismatic joint that gives none, and capsules "split" or "keep".
    default_effort: float | None = DEFAULT_EFFORT
    default_velocity: float | None = DEFAULT_VELOCITY
    capsules: str = "split"
