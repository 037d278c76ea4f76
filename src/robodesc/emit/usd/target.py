"""The USD target as the pipeline sees it."""

from __future__ import annotations

from robodesc.emit.common.target import EmitRequest, Emitted, Target
from robodesc.emit.usd.check import check_usd
from robodesc.emit.usd.layers import PAYLOAD_DIR
from robodesc.emit.usd.options import UsdOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot


def emit_target(robot: Robot, request: EmitRequest, findings: Findings) -> Emitted:
    out = request.output("USD is written to a file: give one with -o robot.usda|.usdc|.usd")
    request.default("fix_base", robot.fixed_base)
    from robodesc.emit.usd.emitter import emit_usd  # the writer loads when it writes

    findings.extend(emit_usd(robot, out, request.options))
    return Emitted(files={"usd": out})


# USD prim names must be identifiers, and Isaac merges materials that share a name.
TARGET = Target(
    name="usd",
    emit=emit_target,
    options=UsdOptions,
    summary="a UsdPhysics articulation for Isaac Sim and Newton; checked by usd-core (and mujoco-usd)",
    suffixes=(".usda", ".usdc", ".usd"),
    suffix_required=True,
    passes={"sanitize_names": True, "unique_materials": True, "mass_from_colliders": True, "placeholder_masses": True},
    check=check_usd,
    # A layered asset owns its payload folder beside the file.
    owned=lambda options, out: (PAYLOAD_DIR,) if options.layered else (),
    options_title="USD and Isaac Sim (-t usd, --isaac-sim; see docs/usd.md, docs/isaac.md)",
)
