"""The SDF target as the pipeline sees it."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

from robodesc._files import write_atomic
from robodesc.emit.common.target import EmitRequest, Emitted, Target, WorldAlone
from robodesc.emit.sdf.check import check_sdf
from robodesc.emit.sdf.options import SdfOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot

if TYPE_CHECKING:
    from robodesc.emit.common.world import PlacedWorld


def emit_target(robot: Robot, request: EmitRequest, findings: Findings) -> Emitted:
    from robodesc.emit.sdf.emitter import build_sdf  # numpy and the writer: only when writing

    sdf_options: SdfOptions = request.options
    sdf_options.path_mode = request.mesh_paths
    sdf_options.out_dir = os.path.dirname(os.path.abspath(request.out)) if request.out else None
    if request.world is not None:
        _world(robot, request, findings)
    result = build_sdf(robot, sdf_options)
    findings.extend(result.findings)
    emitted = Emitted(
        text=result.text,
        extra={
            "link_names": result.names.by_kind.get("link", {}),
            "joint_names": result.names.by_kind.get("joint", {}),
            "sdf_options": sdf_options,
        },
    )
    if request.out:
        write_atomic(request.out, result.text)
        emitted.files["sdf"] = request.out
    emitted.files.update(result.files)
    return emitted


def _world(robot: Robot, request: EmitRequest, findings: Findings) -> None:
    """The world's models, physics and the robot's place in it (a given --init-pos... wins)."""
    from robodesc.emit.common.stance import Stance, complete
    from robodesc.ir.geometry import Pose

    options: SdfOptions = request.options
    placed = request.world
    assert placed is not None
    options.world = True
    options.placed_world = placed
    for cords, _ in placed.cords:
        if cords.stiffness or cords.damping:
            findings.warn(
                "sdf-cords-no-spring",
                f"SDF's ball joint has no axis, so no spring or damping: the {cords.count} cords hang limp in Gazebo "
                f"(stiffness {cords.stiffness:g} N·m/rad and damping {cords.damping:g} are lost); MJCF and USD keep them",
                element=f"cords {cords.name!r}",
                loc=cords.src,
                stage="emit:sdf",
            )
    physics = placed.world.physics
    if physics.step is not None:
        options.step_size = physics.step
    if physics.gravity is not None:
        options.gravity = physics.gravity
    floating = not options.fix_base and robot.root.name != "world"
    roots = placed.root_positions(robot, Stance(complete(robot, {}), "zeros"), floating)
    if options.model_pose is None:
        options.model_pose = Pose(roots[0], (0.0, 0.0, placed.yaw))
    options.copy_poses = [Pose(root, (0.0, 0.0, placed.yaw)) for root in roots[1:]]


def world_alone(placed: PlacedWorld, out: str, options: Any, findings: Findings, validate: bool) -> WorldAlone:
    """A world file given as the input, written alone (robodesc.emit.sdf.world.write_world_alone)."""
    from robodesc.emit.sdf.world import write_world_alone  # the writer loads when it writes

    return write_world_alone(placed, out, options, findings, validate)


TARGET = Target(
    name="sdf",
    emit=emit_target,
    summary="SDF for Gazebo Harmonic (or Classic); checked by Drake",
    suffixes=(".sdf",),
    options=SdfOptions,
    stdout=True,
    check=check_sdf,
    worlds=True,
    world_alone=world_alone,
    options_title="SDF (-t sdf; docs/sdf.md)",
)
