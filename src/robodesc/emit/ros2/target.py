"""The ROS 2 target as the pipeline sees it."""

from __future__ import annotations

import os

from robodesc.emit.common.files import write_folder
from robodesc.emit.common.target import EmitRequest, Emitted, Target
from robodesc.emit.ros2.options import Ros2Options
from robodesc.emit.ros2.package import build_ros2_package
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot


def emit_target(robot: Robot, request: EmitRequest, findings: Findings) -> Emitted:
    out = request.output("the ROS 2 package is several files: give an output folder with -o")
    ros2_options: Ros2Options = request.options
    ros2_options.out_dir = os.path.abspath(out)
    package = build_ros2_package(robot, ros2_options)
    findings.extend(package.findings)
    return Emitted(files=write_folder(out, package.files))


TARGET = Target(name="ros2", emit=emit_target, options=Ros2Options, folder=True)
