"""The URDF target as the pipeline sees it.

From a composition (YAML, ``.holo``, Python), an MJCF or an SDF model the URDF is written for ROS: capsules and spherical
joints are lowered as ``ros.py`` says. From a URDF or xacro input it is a faithful round trip that
keeps pybullet's extensions, with a warning when ROS will not load the result.
"""

from __future__ import annotations

import dataclasses
import os

from robodesc._files import write_atomic
from robodesc.emit.common.target import EmitRequest, Emitted, Target
from robodesc.emit.urdf.check import check_urdf
from robodesc.emit.urdf.ros import from_composition, ros_equivalent, warn_round_trip
from robodesc.emit.urdf.writer import UrdfOptions, emit_urdf
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot


def emit_target(robot: Robot, request: EmitRequest, findings: Findings) -> Emitted:
    with_armature = [j.name for j in robot.joints if j.armature is not None]
    if with_armature:
        findings.info(
            "urdf-armature",
            f"armature of {len(with_armature)} joints written as <dynamics armature=...> (URDF has no armature element; "
            "standard parsers ignore it, the USD output carries physxJointAxis:<axis>:armature and newton:armature)",
            element=f"robot {robot.name!r}",
            stage="emit:urdf",
        )
    out = request.out
    out_dir = os.path.dirname(os.path.abspath(out)) if out else None
    given: UrdfOptions = request.options if isinstance(request.options, UrdfOptions) else UrdfOptions()
    options = dataclasses.replace(given, path_mode=request.mesh_paths, out_dir=out_dir)
    if from_composition(robot):
        written = ros_equivalent(robot, options.capsules, findings)
    else:
        warn_round_trip(robot, findings)
        written = robot
    text = emit_urdf(written, options, findings)
    emitted = Emitted(text=text)
    if out:
        write_atomic(out, text)
        emitted.files["urdf"] = out
    return emitted


TARGET = Target(
    name="urdf",
    emit=emit_target,
    summary="URDF for ROS 2, Gazebo and every URDF reader; checked by MuJoCo",
    suffixes=(".urdf", ".xml"),
    stdout=True,
    options=UrdfOptions,
    check=check_urdf,
    options_title="URDF (-t urdf, and the URDF of --ros2 and --isaac-sim)",
)
