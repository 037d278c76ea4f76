"""The Isaac Sim target: one folder with everything Isaac Sim and Isaac Lab need.

- ``<robot>.usda``: the UsdPhysics articulation (drives, armature, limits in degrees ...);
- ``<robot>.urdf``: the Isaac-flavoured URDF (``<loop_joint>``, ``<fixed_frame>``, ``<sensor>``,
  ``dont_collapse``, a ``<limit>`` on every revolute/prismatic joint);
- ``importer_settings.json``: the same choices in Isaac Sim 5.x ``ImportConfig`` and Isaac Lab
  ``UrdfConverterCfg`` vocabularies, for users who import the URDF themselves;
- ``<robot>_isaaclab.py``: an Isaac Lab ``ArticulationCfg`` (plain data, importable anywhere);
- ``validation.md`` / ``validation.json``: what the independent consumers saw;
- ``findings.md``: every finding of the compile.

One :class:`IsaacSettings` feeds all of them, so they cannot disagree.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import TYPE_CHECKING

from robodesc._files import staged_folder, write_files
from robodesc._version import __version__
from robodesc.emit.common.naming import file_stem
from robodesc.emit.common.paths import PathMode
from robodesc.emit.isaac.lab import isaac_lab_module
from robodesc.emit.isaac.settings import IsaacSettings, importer_settings_json
from robodesc.emit.urdf import UrdfOptions, emit_urdf, ros_equivalent
from robodesc.emit.usd import UsdOptions, emit_usd
from robodesc.ir.diagnostics import Finding, Findings, SourceLoc
from robodesc.ir.model import Robot

if TYPE_CHECKING:  # the world's placement reads meshes (numpy): imported only where a world is given
    from robodesc.emit.common.world import PlacedWorld
    from robodesc.emit.isaac.world import IsaacWorld


def usd_options(settings: IsaacSettings, initial: Mapping[str, float] | None = None) -> UsdOptions:
    return UsdOptions(
        initial_positions=initial,
        fix_base=settings.fix_base,
        drive_type=settings.drive_type,
        target_type=settings.target_type,
        stiffness=settings.stiffness,
        damping=settings.damping,
        collision_approximation=settings.collision_approximation,
        layered=settings.layered,
        solver_position_iterations=settings.solver_position_iterations,
        solver_velocity_iterations=settings.solver_velocity_iterations,
        self_collision=settings.self_collision,
        contact_offset=settings.contact_offset,
        rest_offset=settings.rest_offset,
        physics_scene=settings.physics_scene,
        friction_combine=settings.friction_combine,
        default_friction=settings.default_friction,
        isaac_version=settings.isaac_version,
        motor_envelope=settings.motor_envelope,
    )


def isaac_file_names(robot: Robot) -> dict[str, str]:
    """Named after the input file (``emit/common/naming.py``), not the robot's name attribute."""
    stem = file_stem(robot)
    return {
        "usd": f"{stem}.usda",
        "urdf": f"{stem}.urdf",
        "importer_settings": "importer_settings.json",
        "isaaclab": f"{stem}_isaaclab.py",
        "physics_layer": f"{stem}_physics.usda",
    }


def world_file_names(robot: Robot) -> dict[str, str]:
    """The files a world adds to the folder (emit/isaac/world.py)."""
    stem = file_stem(robot)
    return {"world": f"{stem}_world.usda", "terrain": f"{stem}_terrain.usda"}


def write_isaac_folder(
    robot: Robot,
    out_dir: str,
    settings: IsaacSettings,
    findings: Findings,
    path_mode: PathMode,
    initial: Mapping[str, float] | None = None,
    world: tuple[IsaacWorld, PlacedWorld] | None = None,
) -> dict[str, str]:
    """Write the folder atomically (staged beside ``out_dir``, then moved in place). ``initial``: the
    joints' initial positions (the default pose), which the USD's joint state starts from. ``world``:
    the robot placed in a world (emit/isaac/world.py), whose files join the folder."""
    names = isaac_file_names(robot)
    lab_world_data = None
    if world is not None:
        from robodesc.emit.isaac.world import lab_world, write_world_files

        world_names = {**names, **world_file_names(robot)}
        lab_world_data = lab_world(world[0], world_names)
    with staged_folder(out_dir) as staging:
        if world is not None:
            written = write_world_files(robot, staging, world_names, world[0], world[1], findings)
            names = {**names, **{role: world_names[role] for role in written}}
        findings.extend(emit_usd(robot, os.path.join(staging, names["usd"]), usd_options(settings, initial)))
        # Relative mesh paths are computed against the final folder (a sibling of the staging one).
        # The URDF loads in urdfdom too: capsules and spherical joints lowered (emit/urdf/ros.py).
        urdf = emit_urdf(
            ros_equivalent(robot, "split", findings),
            UrdfOptions(path_mode=path_mode, out_dir=os.path.abspath(out_dir)),
            findings,
        )
        write_files(
            staging,
            {
                names["urdf"]: urdf,
                names["importer_settings"]: importer_settings_json(robot, settings),
                names["isaaclab"]: isaac_lab_module(
                    robot, settings, names["usd"], findings, __version__, lab_world_data
                ).text,
                names["physics_layer"]: importer_physics_layer(robot, settings, findings, initial),
            },
        )
        # A layered USD adds its payload folder: report every top-level entry.
        extra = {
            name: os.path.join(out_dir, name) for name in sorted(os.listdir(staging)) if name not in names.values()
        }
    return {**{role: os.path.join(out_dir, name) for role, name in names.items()}, **extra}


def importer_physics_layer(
    robot: Robot,
    settings: IsaacSettings,
    findings: Findings,
    initial: Mapping[str, float] | None = None,
    onto: str | None = None,
) -> str:
    """The physics layer for the USD Isaac Sim 6's importer makes of the folder's URDF (``onto``, or
    ``settings.importer_usd``: read the paths from that import; else the importer's naming rules)."""
    from robodesc.emit.isaac.importer_layout import layout_from_rules, layout_from_usd
    from robodesc.emit.isaac.physics_layer import physics_layer
    from robodesc.usdfile.usda import usda_text

    imported = onto or settings.importer_usd
    layout = layout_from_usd(imported, robot) if imported else layout_from_rules(robot)
    result = physics_layer(robot, usd_options(settings, initial), layout, findings)
    if result.missing:
        where = imported or "the importer's naming rules"
        # Links and joints first: a missing body or drive matters more than a collider's settings.
        missing = sorted(result.missing, key=lambda m: not m.startswith(("link ", "joint ")))
        findings.warn(
            "isaac-layer-missing",
            f"{len(missing)} prim(s) the physics layer cannot address in {where}, left out: "
            + ", ".join(missing[:20])
            + (" ..." if len(missing) > 20 else ""),
            element=f"robot {robot.name!r}",
            loc=robot.src,
            stage="emit:isaac",
        )
    return usda_text(result.layer)


def _portable(loc: SourceLoc, source_file: str | None) -> SourceLoc:
    """``loc`` with its file relative to the input's folder: the folder travels to other machines,
    and this machine's absolute paths mean nothing there (and say more than they should)."""
    if not loc.file or not os.path.isabs(loc.file.removesuffix(" (expanded)")):
        return loc
    path, expanded = loc.file.removesuffix(" (expanded)"), loc.file.endswith(" (expanded)")
    base = os.path.dirname(os.path.abspath(source_file)) if source_file else os.path.dirname(path)
    rel = os.path.relpath(path, base)
    shown = os.path.basename(path) if rel.startswith("..") else rel
    return SourceLoc(shown + (" (expanded)" if expanded else ""), loc.line, loc.column)


def findings_markdown(robot: Robot, findings: list[Finding]) -> str:
    lines = [f"# robodesc findings for {robot.name}", "", f"robodesc {__version__}; {len(findings)} findings.", ""]
    if findings:
        lines += ["| severity | stage | element | where | message |", "|---|---|---|---|---|"]
        for f in findings:
            where = str(_portable(f.loc, robot.source_file)) if f.loc else ""
            message = f.message.replace("|", "\\|")
            lines.append(f"| {f.severity.value} | {f.stage} | {f.element} | {where} | {message} |")
    return "\n".join(lines) + "\n"
