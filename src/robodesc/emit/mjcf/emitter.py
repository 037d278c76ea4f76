"""Assemble robot.xml (and scene.xml) from the IR."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from typing import TYPE_CHECKING

from robodesc._files import write_atomic
from robodesc.emit.common.approximation import TRIANGLE_MODES, asked, mode_for
from robodesc.emit.common.paths import PathMode
from robodesc.emit.mjcf.actuators import actuators
from robodesc.emit.mjcf.bodies import BodyWriter, bounding_radius
from robodesc.emit.mjcf.constraints import contact, equality
from robodesc.emit.mjcf.context import MjcfContext
from robodesc.emit.mjcf.defaults import defaults
from robodesc.emit.mjcf.floor import floor_height
from robodesc.emit.mjcf.keyframe import home_keyframe
from robodesc.emit.mjcf.options import MjcfOptions
from robodesc.emit.mjcf.scene import scene_name, scene_text
from robodesc.emit.mjcf.sensors import sites_and_sensors
from robodesc.ir.diagnostics import Findings, UnsupportedError
from robodesc.ir.geometry import Mesh
from robodesc.ir.model import Collision, Robot, Visual
from robodesc.ir.rigid import Frame, link_frames, pose_frame

if TYPE_CHECKING:
    from robodesc.emit.common.world import PlacedWorld
    from robodesc.emit.mjcf.world import Copies, RobotSurface

# MuJoCo reads MJCF with tinyxml2, which refuses an element nested 500 deep
# (XML_ELEMENT_DEPTH_EXCEEDED): <mujoco>, <worldbody>, the nested bodies and a body's <joint> or
# <geom> leave room for 496 nested bodies (measured with MuJoCo 4.0: 496 load, 497 do not).
MAX_BODY_DEPTH = 496


def check_depth(robot: Robot) -> None:
    """Refuse, before anything is written, a tree MuJoCo cannot read: one body per link, nested as
    the links are (the world link is MuJoCo's own world body, not nested)."""
    depth = robot.tree_depth() + (0 if robot.root.name == "world" else 1)
    if depth > MAX_BODY_DEPTH:
        raise UnsupportedError(
            f"the kinematic tree is {depth} bodies deep; MuJoCo reads MJCF with tinyxml2, which refuses "
            f"elements nested 500 deep, so an MJCF file holds at most {MAX_BODY_DEPTH} nested bodies. "
            "Nothing was written; -t urdf, sdf and usd take any depth (docs/mjcf.md#limits)",
            element=f"robot {robot.name!r}",
            loc=robot.src,
        )


def build_mjcf(
    robot: Robot,
    options: MjcfOptions,
    findings: Findings,
    out_dir: str,
    mesh_paths: PathMode = PathMode.RELATIVE,
    given: frozenset[str] = frozenset(),
) -> tuple[str, dict[str, str]]:
    """robot.xml's text and the files written for it (converted meshes), by role."""
    options.check()
    check_depth(robot)
    ctx = MjcfContext(robot, options, findings, out_dir, mesh_paths, given)
    floating = _floating(robot, options)
    root = ET.Element("mujoco", model=robot.name)
    ET.SubElement(root, "compiler", angle="radian", autolimits="true", inertiafromgeom="false")
    option = ET.SubElement(root, "option", integrator=options.integrator)
    if options.cone is not None:
        option.set("cone", options.cone)
    if options.impratio is not None:
        option.set("impratio", f"{options.impratio:g}")
    writer = BodyWriter(ctx)
    worldbody = writer.worldbody(_root_pose(robot, options, floating), floating)
    act = actuators(ctx)
    # Sites and constraints are attached to the bodies, so they come before <default> pulls values.
    sensor = sites_and_sensors(ctx)
    eq = equality(ctx)
    root.append(defaults(ctx, worldbody, act))
    if len(ctx.asset):
        root.append(ctx.asset)
    root.append(worldbody)
    for part in (contact(ctx), eq, act, sensor, home_keyframe(ctx, worldbody, act)):
        if part is not None:
            root.append(part)
    _approximation_notes(ctx)
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="unicode") + "\n", ctx.written


def _approximation_notes(ctx: MjcfContext) -> None:
    """What MuJoCo does with the modes it has no word for: it collides every mesh geom as its convex
    hull (docs/contact.md)."""
    modes = asked(ctx.options.collision_approximation)
    bounding = sorted(modes & {"boundingCube", "boundingSphere"})
    if bounding:
        ctx.warn(
            "mjcf-approximation",
            f"collision approximation {', '.join(bounding)}: MuJoCo collides meshes as convex hulls, which "
            "is what is written",
            "option 'collision_approximation'",
        )
    spec = ctx.options.collision_approximation
    exact = [
        link.name
        for link in ctx.robot.links
        if mode_for(spec, link.name) in TRIANGLE_MODES and any(isinstance(c.geometry, Mesh) for c in link.collisions)
    ]
    if exact:
        shown = ", ".join(exact[:5]) + (f" and {len(exact) - 5} more" if len(exact) > 5 else "")
        ctx.warn(
            "mjcf-triangle-mesh",
            f"collision approximation {'/'.join(sorted(modes & set(TRIANGLE_MODES)))} (exact triangles) on {shown}: "
            "MuJoCo collides every mesh geom as its convex hull, which is what it will use; for a concave "
            "part use convexDecomposition (robodesc writes CoACD's convex parts)",
            "option 'collision_approximation'",
        )


def emit_mjcf(
    robot: Robot,
    out: str,
    options: MjcfOptions | None = None,
    findings: Findings | None = None,
    *,
    mesh_paths: PathMode = PathMode.RELATIVE,
    given: frozenset[str] = frozenset(),
    final_name: str | None = None,
    world: PlacedWorld | None = None,
) -> dict[str, str]:
    """Write ``out`` (robot.xml) and, with ``options.scene``, the scene beside it. ``final_name`` is
    the robot file's name once it is moved into place (the scene includes it by that name).
    Returns every written file by role: "mjcf", "scene", "mesh:<path>"."""
    options = options or MjcfOptions()
    findings = findings if findings is not None else Findings()
    out_dir = os.path.dirname(os.path.abspath(out))
    text, written = build_mjcf(robot, options, findings, out_dir, mesh_paths, given)
    write_atomic(out, text)
    files = {"mjcf": out, **written}
    if options.scene:
        name = final_name or os.path.basename(out)
        scene = os.path.join(out_dir, scene_name(name))
        if world is not None:
            from robodesc.emit.mjcf.world import world_scene_text

            data = world_scene_text(name, world, findings, _surface(robot, options), copies(text, options)).encode()
        else:
            data = scene_text(name, _scene_floor(robot, options, findings)).encode()
        if not (os.path.isfile(scene) and _read(scene) == data):
            write_atomic(scene, data)
        files["scene"] = scene
    return files


def copies(robot_text: str, options: MjcfOptions) -> Copies | None:
    """Several copies of the robot in the world scene: what each is attached with (emit/mjcf/world.py)."""
    if len(options.copies) < 2:
        return None
    from robodesc.emit.mjcf.world import Copies

    return Copies.of(robot_text, options.copies)


def _surface(robot: Robot, options: MjcfOptions) -> RobotSurface:
    """The robot colliders' friction range (MuJoCo's default 1 where none is given) and priority."""
    from robodesc.emit.mjcf.world import RobotSurface

    mus = [
        contact.mu if (contact := link.collision_contact(c)) is not None and contact.mu is not None else 1.0
        for link in robot.links
        for c in link.collisions
    ] or [1.0]
    return RobotSurface(min(mus), max(mus), 1 if options.friction_combine == "min" else 0)


def _read(path: str) -> bytes:
    with open(path, "rb") as handle:
        return handle.read()


def _floating(robot: Robot, options: MjcfOptions) -> bool:
    return not options.fix_base and robot.root.name != "world"


def _scene_floor(robot: Robot, options: MjcfOptions, findings: Findings) -> float:
    """The floor's height in the scene: under the lowest collider of a welded robot (floor.py)."""
    if _floating(robot, options):
        return 0.0
    height = floor_height(robot, _root_pose(robot, options, False))
    if height:
        findings.info(
            "mjcf-floor-lowered",
            f"the robot is welded and has colliders below z = 0: the scene's floor is at z = {height:.4g} m, "
            "under them, so it does not cut through the robot",
            element="scene floor",
            stage="emit:mjcf",
        )
    return height


def _root_pose(robot: Robot, options: MjcfOptions, floating: bool) -> Frame:
    """Where the root body starts: ``init_pos``, else the composition's placement, else (floating
    only) high enough that no primitive collider starts below the floor, so it falls onto its feet."""
    placement = pose_frame(robot.placement) if robot.placement is not None else None
    if options.init_pos is not None:
        rotation = placement.rotation if placement is not None else Frame().rotation
        return Frame(rotation, tuple(options.init_pos))  # type: ignore[arg-type]
    if placement is not None:
        return placement
    if not floating:
        return Frame()
    lowest = 0.0
    frames = link_frames(robot)
    for link in robot.links:
        shapes: list[Collision | Visual] = [*link.collisions, *link.visuals]
        for shape in shapes:
            at = frames[link.name] @ pose_frame(shape.origin)
            lowest = min(lowest, at.translation[2] - bounding_radius(shape.geometry))
    return Frame(translation=(0.0, 0.0, -lowest))


__all__ = ["build_mjcf", "emit_mjcf"]
