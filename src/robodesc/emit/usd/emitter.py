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
from dataclasses import dataclass

from robodesc.emit.usd.bodies import emit_articulation, emit_body, emit_physics_scene, emit_robot_schema
from robodesc.emit.usd.contact import PhysicsMaterials
from robodesc.emit.usd.context import (
    CONTACT_SCOPE,
    JOINTS_SCOPE,
    LOOPS_SCOPE,
    PHYSICS,
    RESERVED_LINK_CHILDREN,
    RESERVED_ROBOT_CHILDREN,
    UsdContext,
    check_identifier,
)
from robodesc.emit.usd.geometry import approximation_notes, emit_link_geometry
from robodesc.emit.usd.joints import emit_joint, emit_loop_joint, loop_scope_paths
from robodesc.emit.usd.layers import PAYLOAD_DIR, LayerSet, robot_prim, stage_metadata, write_layers
from robodesc.emit.usd.materials import MaterialLibrary
from robodesc.emit.usd.options import FORMATS, UsdOptions
from robodesc.emit.usd.sensors import emit_fixed_frame, emit_sensor
from robodesc.ir.diagnostics import BrokenReferenceError, ConfigError, Findings, UnsupportedError
from robodesc.ir.model import FixedFrame, Robot, Sensor
from robodesc.ir.rigid import link_frames
from robodesc.usdfile.spec import Layer, Prim

__all__ = ["PhysicsOpinions", "UsdOptions", "emit_usd", "physics_opinions"]


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
        findings=findings,
        layer_dir=os.path.join(out_dir, PAYLOAD_DIR) if opts.layered else out_dir,
        layers=layers.roles,
    )
    build_layers(ctx, layers)
    write_layers(layers, path, ctx.robot_path[1:])
    return findings


@dataclass
class PhysicsOpinions:
    """What the emitter's ``Physics`` role holds for a robot (the layered layout's Physics layer),
    in memory: for a layer that carries robodesc's physics onto another asset (emit/isaac)."""

    layer: Layer
    scene: Prim | None  # the /PhysicsScene (options.physics_scene)
    robot_path: str  # the robot prim, e.g. "/quadruped"
    joints_scope: str = JOINTS_SCOPE  # <robot_path>/<joints_scope>/<joint>
    materials_scope: str = CONTACT_SCOPE  # <robot_path>/<materials_scope>/<contact material>
    loops_scope: str = LOOPS_SCOPE  # <robot_path>/<loops_scope>/<loop joint>


def physics_opinions(robot: Robot, options: UsdOptions, findings: Findings) -> PhysicsOpinions:
    """Author the robot as :func:`emit_usd` does, keep its physics opinions, write nothing."""
    layers = LayerSet.create("robot.usda", layered=True)
    ctx = UsdContext(robot=robot, options=options, findings=findings, layer_dir=os.getcwd(), layers=layers.roles)
    build_layers(ctx, layers)
    scene = layers.interface.find("/PhysicsScene") if layers.interface is not None else None
    return PhysicsOpinions(layers.roles[PHYSICS], scene, ctx.robot_path)


def build_layers(ctx: UsdContext, layers: LayerSet) -> None:
    """Author the whole asset into ``layers`` (nothing is written to disk)."""
    robot = ctx.robot
    _plan_paths(ctx)
    try:
        root = robot.root
    except ValueError as exc:
        raise UnsupportedError(f"{exc}: USD needs one tree", element=f"robot {robot.name!r}", loc=robot.src) from None
    ctx.link_poses = link_frames(robot)
    name = ctx.robot_path[1:]
    stage_metadata(layers.main, name)
    robot_prim(layers.main, name, robot.display_name)
    if layers.interface is not None:
        robot_prim(layers.interface, name, robot.display_name)

    looks = MaterialLibrary(ctx)
    contacts = PhysicsMaterials(ctx)
    attached: dict[str, list[FixedFrame | Sensor]] = {}
    for frame in robot.fixed_frames:
        attached.setdefault(frame.parent, []).append(frame)
    for sensor in robot.sensors:
        attached.setdefault(sensor.parent, []).append(sensor)
    for link in robot.links:
        emit_body(ctx, link)
        emit_link_geometry(ctx, link, looks, contacts)
        for node in attached.get(link.name, []):
            path = f"{ctx.link_paths[link.name]}/{node.name}"
            if isinstance(node, FixedFrame):
                emit_fixed_frame(ctx, node, path)
            else:
                emit_sensor(ctx, node, path)

    ctx.define(PHYSICS, f"{ctx.robot_path}/{JOINTS_SCOPE}", "Scope")
    for joint in robot.joints:
        emit_joint(ctx, joint)
    emit_articulation(ctx, root)
    approximation_notes(ctx)
    emit_robot_schema(ctx)
    loops = loop_scope_paths(ctx)
    if loops:
        ctx.define(PHYSICS, f"{ctx.robot_path}/{LOOPS_SCOPE}", "Scope")
        for loop in robot.loop_joints:
            emit_loop_joint(ctx, loop, loops[loop.name])
    if ctx.options.physics_scene:
        # Outside the default prim: in the interface layer when the asset is layered.
        emit_physics_scene(layers.interface if layers.interface is not None else layers.main)


def _plan_paths(ctx: UsdContext) -> None:
    """Check every name the layout needs before authoring anything."""
    robot = ctx.robot
    name = check_identifier(robot.name, f"robot {robot.name!r}", robot.src)
    ctx.robot_path = f"/{name}"
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
        ctx.link_paths[link.name] = f"{ctx.robot_path}/{link.name}"
    scope = f"{ctx.robot_path}/{JOINTS_SCOPE}"
    for joint in robot.joints:
        label = f"joint {joint.name!r}"
        check_identifier(joint.name, label, joint.src)
        if joint.name in ctx.joint_paths:
            raise UnsupportedError("two joints share this name", element=label, loc=joint.src)
        for end in (joint.parent, joint.child):
            if end not in ctx.link_paths:
                raise BrokenReferenceError(f"refers to unknown link {end!r}", element=label, loc=joint.src)
        ctx.joint_paths[joint.name] = f"{scope}/{joint.name}"
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
