"""The MJCF target as the pipeline sees it: a file target (``-o OUT/robot.xml``) that also writes
its scene and converted meshes beside the file (docs/mjcf.md, Outputs)."""

from __future__ import annotations

import os

from robodesc.emit.common.target import EmitRequest, Emitted, Target
from robodesc.emit.mjcf.emitter import emit_mjcf
from robodesc.emit.mjcf.options import MjcfOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot

# pipeline.Staging stages a file output as ".robodesc-<random>-<name>" in the same folder.
_STAGED_PREFIX = ".robodesc-"


def final_name(path: str) -> str:
    """The output's own name, from the staged file's name (the scene includes robot.xml by it)."""
    base = os.path.basename(path)
    if base.startswith(_STAGED_PREFIX) and base.count("-") >= 2:
        return base.split("-", 2)[2]
    return base


def emit_target(robot: Robot, request: EmitRequest, findings: Findings) -> Emitted:
    out = request.output("MJCF is written to a file: give one with -o OUT/robot.xml")
    request.default("fix_base", robot.fixed_base)
    request.default("init_pos", robot.placement.xyz if robot.placement is not None else None)
    files = emit_mjcf(
        robot,
        out,
        request.options,
        findings,
        mesh_paths=request.mesh_paths,
        given=request.given,
        final_name=final_name(out),
    )
    return Emitted(files=files, extra={"mjcf_options": request.options})


# The "mjcf" preset (passes/presets.py): MuJoCo refuses an invalid inertia on a moving body, so
# invalid ones are repaired from geometry, as the Isaac folder does, and each repair reported.
TARGET = Target(name="mjcf", emit=emit_target, options=MjcfOptions, preset="mjcf", validator="mjcf")
