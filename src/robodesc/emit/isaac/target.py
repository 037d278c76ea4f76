"""The Isaac Sim target as the pipeline sees it."""

from __future__ import annotations

import os

from robodesc._files import write_atomic
from robodesc.emit.common.target import EmitRequest, Emitted, Target
from robodesc.emit.isaac.check import check_isaac
from robodesc.emit.isaac.defaults import apply_defaults
from robodesc.emit.isaac.settings import IsaacSettings
from robodesc.ir.diagnostics import Finding, Findings
from robodesc.ir.model import Robot
from robodesc.validation.report import ValidationReport


def emit_target(robot: Robot, request: EmitRequest, findings: Findings) -> Emitted:
    from robodesc.emit.isaac.folder import write_isaac_folder  # the writers load when they write

    out = request.output("the Isaac Sim target writes a folder: give it with -o OUT_DIR")
    # Where the composition put the robot.
    request.default("init_pos", robot.placement.xyz if robot.placement is not None else None)
    settings: IsaacSettings = request.options
    # The pose, spawn height and gains the user left out (emit/isaac/defaults.py).
    initial = apply_defaults(robot, settings, request.given, findings)
    world = None
    if request.world is not None:
        from robodesc.emit.isaac.world import place

        # The spawn on the world's ground replaces the spawn height over z = 0 (a given --init-pos wins).
        world = (place(robot, request.world, settings, initial, request.given, findings), request.world)
    files = write_isaac_folder(robot, out, settings, findings, request.mesh_paths, initial, world)
    return Emitted(files=files, extra={"settings": settings})


def finish(robot: Robot, out: str, findings: list[Finding], validation: ValidationReport | None) -> dict[str, str]:
    """The findings and validation reports, written once validation has run."""
    from robodesc.emit.isaac.folder import findings_markdown

    written = {"findings": os.path.join(out, "findings.md")}
    write_atomic(written["findings"], findings_markdown(robot, findings))
    if validation is not None:
        write_atomic(os.path.join(out, "validation.md"), validation.to_markdown())
        write_atomic(os.path.join(out, "validation.json"), validation.to_json())
        written["validation"] = os.path.join(out, "validation.md")
    return written


TARGET = Target(
    name="isaac",
    emit=emit_target,
    summary="an Isaac Sim / Isaac Lab folder: USD, Isaac URDF, importer settings, ArticulationCfg module",
    options=IsaacSettings,
    folder=True,
    passes={"sanitize_names": True, "unique_materials": True, "mass_from_colliders": True, "placeholder_masses": True},
    preset="isaac_sim",
    check=check_isaac,
    finish=finish,
    derives_gains=True,
    worlds=True,
    options_title="USD and Isaac Sim (-t usd, --isaac-sim; see docs/usd.md, docs/isaac.md)",
)
