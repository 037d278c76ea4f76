"""The USD target as the pipeline sees it."""

from __future__ import annotations

from typing import Any

from robodesc.emit.common.source_drives import apply_source_gains
from robodesc.emit.common.target import EmitRequest, Emitted, Target
from robodesc.emit.usd.check import check_usd
from robodesc.emit.usd.layers import PAYLOAD_DIR
from robodesc.emit.usd.options import UsdOptions
from robodesc.emit.usd.world import world_file_name, write_world_alone
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot

STAGE = "emit:usd"


def emit_target(robot: Robot, request: EmitRequest, findings: Findings) -> Emitted:
    out = request.output("USD is written to a file: give one with -o robot.usda|.usdc|.usd")
    if request.options.target_type != "none":
        _default_gains(robot, request, findings)
        # The source's own servos (an MJCF's) over the derived gains, where the user gave none.
        apply_source_gains(robot, request.options, request.given)
    from robodesc.emit.usd.emitter import emit_usd  # the writer loads when it writes

    findings.extend(emit_usd(robot, out, request.options))
    files = {"usd": out}
    extra: dict[str, Any] = {}
    if request.world is not None:
        files["world"], extra["world_expect"] = _write_world(robot, request, out, findings)
    return Emitted(files=files, extra=extra)


def _default_gains(robot: Robot, request: EmitRequest, findings: Findings) -> None:
    """Gains the user did not give are derived per joint, as the Isaac folder's and the MJCF's are
    (emit/common/gains.py): the old constants (100 N·m/rad, 1 N·m·s/rad) let ur10's shoulder sag
    1.1 rad and simple_humanoid's waist 1.3 rad in every engine (docs/dynamics.md). A floating
    robot's gains are those of the stance it stands in (the Isaac folder's default pose); the
    file itself still starts at the zero pose, or at ``initial_positions``."""
    from robodesc.emit.common.default_pose import default_pose
    from robodesc.emit.common.gains import fill_default_gains

    options: UsdOptions = request.options
    if {"stiffness", "damping"} <= request.given:
        return
    floating = not options.fix_base and robot.root.name != "world"
    wanted = dict(options.initial_positions or {})
    # The stance's own findings belong to the Isaac folder, which writes it; here it only sizes gains.
    stance = default_pose(robot, wanted, floating, Findings(), STAGE)
    fill_default_gains(robot, options, request.given, stance, floating, findings, STAGE)


def _write_world(robot: Robot, request: EmitRequest, out: str, findings: Findings) -> tuple[str, dict[str, Any]]:
    """The world stage beside the robot, the robot on its ground in the zero pose USD starts it in."""
    import os

    from robodesc.emit.common.stance import Stance, complete
    from robodesc.emit.usd.world import robot_friction, world_file_name, write_world

    placed = request.world
    assert placed is not None
    final = request.final or out
    floating = not request.options.fix_base and robot.root.name != "world"
    roots = placed.root_positions(robot, Stance(complete(robot, {}), "zeros"), floating)
    path = os.path.join(os.path.dirname(os.path.abspath(out)), world_file_name(final))
    contacts = any(s.type.value == "contact" for s in robot.sensors)
    expect = write_world(
        path, final, robot.name, placed, roots, findings, contacts=contacts, robot_mu=robot_friction(robot)
    )
    return path, expect


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
    derives_gains=True,
    # A layered asset owns its payload folder beside the file.
    owned=lambda options, out: (PAYLOAD_DIR,) if options.layered else (),
    worlds=True,
    world_files=lambda options, out: (world_file_name(out),),
    world_alone=write_world_alone,
    # Mesh geometry is embedded (a copied mesh would be an unused file, and outside the roots the
    # writer reads from); textures stay files the layer refers to.
    copies=frozenset({"textures"}),
    options_title="USD and Isaac Sim (-t usd, --isaac-sim; see docs/usd.md, docs/isaac.md)",
)
