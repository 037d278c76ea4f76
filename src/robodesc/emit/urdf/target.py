"""The URDF target as the pipeline sees it."""

from __future__ import annotations

import os

from robodesc._files import write_atomic
from robodesc.emit.common.target import EmitRequest, Emitted, Target
from robodesc.emit.urdf.check import check_urdf
from robodesc.emit.urdf.writer import UrdfOptions, emit_urdf
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot


def emit_target(robot: Robot, request: EmitRequest, findings: Findings) -> Emitted:
    with_armature = [j.name for j in robot.joints if j.armature is not None]
    if with_armature:
        findings.info(
            "urdf-armature",
            f"armature of {len(with_armature)} joints written as <dynamics armature=...> (URDF has no armature element; "
            "standard parsers ignore it, the USD output carries physxJoint:armature and newton:armature)",
            element=f"robot {robot.name!r}",
            stage="emit:urdf",
        )
    out = request.out
    out_dir = os.path.dirname(os.path.abspath(out)) if out else None
    text = emit_urdf(robot, UrdfOptions(path_mode=request.mesh_paths, out_dir=out_dir))
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
    check=check_urdf,
)
