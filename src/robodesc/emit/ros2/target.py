"""The ROS 2 target as the pipeline sees it."""

from __future__ import annotations

import os

from robodesc._files import write_folder
from robodesc.emit.common.target import EmitRequest, Emitted, Target
from robodesc.emit.ros2.options import Ros2Options
from robodesc.emit.urdf import check_urdf
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot


def emit_target(robot: Robot, request: EmitRequest, findings: Findings) -> Emitted:
    out = request.output("the ROS 2 package is several files: give an output folder with -o")
    from robodesc.emit.ros2.package import build_ros2_package  # the SDF writer behind it: only when writing

    ros2_options: Ros2Options = request.options
    ros2_options.out_dir = os.path.abspath(out)
    package = build_ros2_package(robot, ros2_options)
    findings.extend(package.findings)
    return Emitted(files=write_folder(out, package.files))


TARGET = Target(
    name="ros2",
    emit=emit_target,
    summary="a ROS 2 / Gazebo Harmonic folder: URDF with ros2_control, controllers, launch, bridge, world",
    options=Ros2Options,
    folder=True,
    check=check_urdf,
    options_title="ROS 2 (--ros2)",
)
