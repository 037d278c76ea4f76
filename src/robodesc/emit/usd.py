"""IR → Isaac-ready UsdPhysics (``.usda``, ``.usdc`` or ``.usd``).

Layout (single file; ``docs/usd.md`` has the layered variant)::

    /robot                    Xform, default prim, kind=component [ArticulationRootAPI if fixed base]
        /<link>               Xform + RigidBodyAPI + MassAPI, pose in the robot frame (flat siblings)
            /visuals/<name>   Cube | Sphere | Cylinder | Capsule | Mesh, material bound
            /collisions/<n>   same shapes, purpose=guide, CollisionAPI [+ MeshCollisionAPI]
            /<fixed frame>    Xform
            /<sensor>         Camera | Xform
        /Looks/<material>     UsdPreviewSurface materials, one per distinct look
        /joints/<joint>       UsdPhysics joints (+ root_joint for a fixed base)
        /loop_joints/<joint>  loop closures, excludeFromArticulation = true
    /PhysicsScene             optional, outside the default prim

Prims are authored in IR order, so the same IR gives byte-identical files.
"""

from __future__ import annotations

import os

from pxr import Sdf, Usd, UsdGeom, UsdPhysics

from robodesc.emit.usd_bodies import emit_articulation, emit_body, emit_physics_scene
from robodesc.emit.usd_context import (
    JOINTS_SCOPE,
    LOOPS_SCOPE,
    PHYSICS,
    RESERVED_LINK_CHILDREN,
    RESERVED_ROBOT_CHILDREN,
    UsdContext,
    check_identifier,
    set_display_name,
)
from robodesc.emit.usd_geometry import emit_link_geometry
from robodesc.emit.usd_joints import emit_joint, emit_loop_joint, loop_scope_paths
from robodesc.emit.usd_layers import LayerSet, write_layers
from robodesc.emit.usd_materials import MaterialLibrary
from robodesc.emit.usd_options import FORMATS, UsdOptions
from robodesc.emit.usd_sensors import emit_fixed_frame, emit_sensor
from robodesc.ir.diagnostics import BrokenReferenceError, ConfigError, Findings, UnsupportedError
from robodesc.ir.model import Robot
from robodesc.ir.transforms import forward_kinematics

__all__ = ["UsdOptions", "emit_usd"]


def emit_usd(robot: Robot, path: str, options: UsdOptions | None = None) -> Findings:
    """Write ``robot`` to ``path`` (atomically) and return what the emitter noticed."""
    opts = options or UsdOptions()
    opts.check()
    ext = os.path.splitext(path)[1].lower()
    if ext not in FORMATS:
        raise ConfigError(f"USD output must end with {', '.join(FORMATS)}; got {path!r}")
    findings = Findings()
    out_dir = os.path.dirname(os.path.abspath(path))
    layers = LayerSet.create(path, opts.layered)
    ctx = UsdContext(
        robot=robot,
        options=opts,
        stage=layers.stage,
        findings=findings,
        layer_dir=layers.payload_dir if opts.layered else out_dir,
        layers=layers.roles,
    )
    try:
        build_stage(ctx)
        if opts.physics_scene:
            layers.add_physics_scene(lambda stage: emit_physics_scene(_scene_ctx(ctx, stage)))
        write_layers(layers, robot, path)
    finally:
        layers.discard()
    return findings


def _scene_ctx(ctx: UsdContext, stage: Usd.Stage) -> UsdContext:
    return UsdContext(robot=ctx.robot, options=ctx.options, stage=stage, findings=ctx.findings, layer_dir=ctx.layer_dir)


def build_stage(ctx: UsdContext) -> None:
    robot = ctx.robot
    _plan_paths(ctx)
    try:
        root = robot.root
    except ValueError as exc:
        raise UnsupportedError(f"{exc}: USD needs one tree", element=f"robot {robot.name!r}", loc=robot.src) from None
    ctx.link_poses = forward_kinematics(robot)
    stage = ctx.stage
    with Sdf.ChangeBlock():
        UsdGeom.SetStageMetersPerUnit(stage, 1.0)
        UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
        UsdPhysics.SetStageKilogramsPerUnit(stage, 1.0)
    robot_prim = UsdGeom.Xform.Define(stage, ctx.robot_path).GetPrim()
    stage.SetDefaultPrim(robot_prim)
    Usd.ModelAPI(robot_prim).SetKind("component")
    Usd.ModelAPI(robot_prim).SetAssetName(robot.name)
    set_display_name(robot_prim, robot.display_name)

    looks = MaterialLibrary(ctx)
    frames_by_link: dict[str, list[tuple[str, object]]] = {}
    for frame in robot.fixed_frames:
        frames_by_link.setdefault(frame.parent, []).append(("frame", frame))
    for sensor in robot.sensors:
        frames_by_link.setdefault(sensor.parent, []).append(("sensor", sensor))
    for link in robot.links:
        emit_body(ctx, link)
        emit_link_geometry(ctx, link, looks)
        for kind, node in frames_by_link.get(link.name, []):
            path = ctx.link_paths[link.name].AppendChild(node.name)  # type: ignore[attr-defined]
            if kind == "frame":
                emit_fixed_frame(ctx, node, path)  # type: ignore[arg-type]
            else:
                emit_sensor(ctx, node, path)  # type: ignore[arg-type]

    with ctx.layer(PHYSICS):
        stage.DefinePrim(ctx.robot_path.AppendChild(JOINTS_SCOPE), "Scope")
    for joint in robot.joints:
        emit_joint(ctx, joint)
    emit_articulation(ctx, root)
    loops = loop_scope_paths(ctx)
    if loops:
        with ctx.layer(PHYSICS):
            stage.DefinePrim(ctx.robot_path.AppendChild(LOOPS_SCOPE), "Scope")
        for loop in robot.loop_joints:
            emit_loop_joint(ctx, loop, loops[loop.name])


def _plan_paths(ctx: UsdContext) -> None:
    """Check every name the layout needs before authoring anything."""
    robot = ctx.robot
    name = check_identifier(robot.name, f"robot {robot.name!r}", robot.src)
    ctx.robot_path = Sdf.Path.absoluteRootPath.AppendChild(name)
    for link in robot.links:
        label = f"link {link.name!r}"
        check_identifier(link.name, label, link.src)
        if link.name in RESERVED_ROBOT_CHILDREN:
            raise UnsupportedError(
                f"a link may not be called {link.name!r} in USD (robodesc uses that prim); rename it",
                element=label,
                loc=link.src,
            )
        if link.name in ctx.link_paths:
            raise UnsupportedError("two links share this name", element=label, loc=link.src)
        ctx.link_paths[link.name] = ctx.robot_path.AppendChild(link.name)
    scope = ctx.robot_path.AppendChild(JOINTS_SCOPE)
    for joint in robot.joints:
        label = f"joint {joint.name!r}"
        check_identifier(joint.name, label, joint.src)
        if joint.name in ctx.joint_paths:
            raise UnsupportedError("two joints share this name", element=label, loc=joint.src)
        for end in (joint.parent, joint.child):
            if end not in ctx.link_paths:
                raise BrokenReferenceError(f"refers to unknown link {end!r}", element=label, loc=joint.src)
        ctx.joint_paths[joint.name] = scope.AppendChild(joint.name)
    for joint in robot.joints:
        if joint.mimic is not None and joint.mimic.joint not in ctx.joint_paths:
            raise BrokenReferenceError(
                f"mimics unknown joint {joint.mimic.joint!r}", element=f"joint {joint.name!r}", loc=joint.mimic.src
            )
    children: dict[str, set[str]] = {}
    nodes: list[tuple[str, str, str, object]] = [("fixed_frame", f.name, f.parent, f.src) for f in robot.fixed_frames]
    nodes += [("sensor", s.name, s.parent, s.src) for s in robot.sensors]
    for kind, node_name, parent, src in nodes:
        label = f"{kind} {node_name!r}"
        check_identifier(node_name, label, src)  # type: ignore[arg-type]
        if parent not in ctx.link_paths:
            raise BrokenReferenceError(f"is attached to unknown link {parent!r}", element=label, loc=src)  # type: ignore[arg-type]
        used = children.setdefault(parent, set(RESERVED_LINK_CHILDREN))
        if node_name in used:
            raise UnsupportedError(
                f"name is already used under link {parent!r} (visuals, collisions, frames and sensors share it)",
                element=label,
                loc=src,  # type: ignore[arg-type]
            )
        used.add(node_name)
