"""``scene.xml`` with a world: the robot on the world's terrain, under the world's physics.

MuJoCo collides a mesh as its convex hull, so a terrain reaches it as an ``<hfield>`` made from the
heightfield grid (emit/common/world.py), its heights inline (``elevation``): no further file to find
through ``meshdir``, and the scene stays one file written atomically. MuJoCo reads inline rows from
the +y edge down (as an image) and normalizes them to ``[0, size[2]]``; the grid's rows run from -y,
so they are written reversed, relative to the lowest height. A flat grid is a box. Boxes, spheres,
cylinders and planes are written as they are; friction is the world's ``mu`` (MuJoCo has one
isotropic coefficient).
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass

import numpy as np

from robodesc.emit.common.numbers import fmt, fmt_vec
from robodesc.emit.common.target import WorldAlone
from robodesc.emit.common.world import HFIELD_BASE, PlacedWorld, TerrainGrid
from robodesc.emit.mjcf.contact_params import ROLL, TORSION
from robodesc.emit.mjcf.scene import SCENE
from robodesc.ir.diagnostics import Findings
from robodesc.ir.geometry import Box, Cylinder, Mesh, Sphere, Vec3
from robodesc.ir.rigid import Frame, pose_frame
from robodesc.ir.world import CordField, HeightImage, Plane, StaticBody, WorldCollider

STAGE = "emit:mjcf"


@dataclass(slots=True, frozen=True)
class RobotSurface:
    """What the robot's colliders bring to a contact: their friction range and geom priority."""

    mu_low: float = 1.0
    mu_high: float = 1.0
    priority: int = 0


@dataclass(slots=True, frozen=True)
class Copies:
    """Several copies of robot.xml in one scene, each brought in by MuJoCo's ``<attach>`` under a
    name prefix (``<stem>_<i>/``). ``<include>`` cannot prefix names, so it holds one robot only."""

    option: dict[str, str]  # robot.xml's <option>: an attached model's options do not carry over
    qpos: list[float]  # robot.xml's home keyframe
    ctrl: list[float]
    floating: bool  # robot.xml's root body has a free joint
    roots: tuple[tuple[Vec3, float], ...]  # each copy's root in the zero pose, and its home height

    @classmethod
    def of(cls, robot_text: str, roots: tuple[tuple[Vec3, float], ...]) -> Copies:
        root = ET.fromstring(robot_text)
        option = root.find("option")
        key = root.find("keyframe/key[@name='home']")
        qpos = key.get("qpos", "") if key is not None else ""
        ctrl = key.get("ctrl", "") if key is not None else ""
        return cls(
            option=dict(option.attrib) if option is not None else {},
            qpos=[float(v) for v in qpos.split()],
            ctrl=[float(v) for v in ctrl.split()],
            floating=root.find("worldbody/body/freejoint") is not None,
            roots=roots,
        )

    def home(self, cords: int) -> ET.Element:
        """The scene's ``home`` keyframe: every copy in its stance at its own spawn, the cords
        hanging (``cords`` ball joints). Each attached copy brings its own ``<prefix>home`` too, but
        MuJoCo does not move an attached keyframe's free joint by the frame: those start every copy
        at the first one's place."""
        qpos: list[float] = []
        for (x, y, _), height in self.roots:
            qpos.extend([x, y, height, *self.qpos[3:]] if self.floating else self.qpos)
        qpos.extend([1.0, 0.0, 0.0, 0.0] * cords)
        keyframe = ET.Element("keyframe")
        attrs = {"name": "home", "qpos": fmt_vec(qpos)}
        if self.ctrl:
            attrs["ctrl"] = fmt_vec(self.ctrl * len(self.roots))
        ET.SubElement(keyframe, "key", attrs)
        return keyframe


def copy_prefix(stem: str, index: int) -> str:
    return f"{stem}_{index}/"


def world_scene_text(
    robot_file: str | None,
    placed: PlacedWorld,
    findings: Findings,
    robot: RobotSurface | None,
    copies: Copies | None = None,
) -> str:
    """The scene with the world's ground instead of the plane floor, and its physics; with
    ``copies``, the robot attached once per copy instead of included. ``robot_file`` None: the
    world alone (a world file as the input), named ``placed.world.name``."""
    base = os.path.basename(robot_file) if robot_file is not None else ""
    stem = os.path.splitext(base)[0] if robot_file is not None else placed.world.name
    head = SCENE.format(stem=stem, robot=base, floor_pos="").partition("  <worldbody>")[0]
    option = _option(placed, copies.option if copies is not None else {})
    assets = ET.Element("asset")
    world = ET.Element("worldbody")
    ET.SubElement(world, "light", pos="0 0 3", dir="0 0 -1", directional="true")
    if not placed.world.bodies:
        # A world of cords alone stands on the scene's usual floor.
        ET.SubElement(world, "geom", name="floor", size="0 0 0.05", type="plane", material="groundplane")
    for body in placed.world.bodies:
        for collider in body.colliders:
            _collider(placed, body, collider, assets, world, findings, robot)
    tail = ""
    if robot_file is None:
        head = head.replace(f'  <include file="{base}"/>\n', "", 1).replace(f"{stem} scene", stem, 1)
    if copies is not None:
        head = head.replace(f'  <include file="{base}"/>\n', "", 1)
        ET.SubElement(assets, "model", name=stem, file=base)
        # robot.xml places the first copy; each frame moves a copy by its offset from the first.
        first = copies.roots[0][0]
        for i, ((x, y, z), _) in enumerate(copies.roots):
            offset = (x - first[0], y - first[1], z - first[2])
            frame = ET.SubElement(world, "frame", {"pos": fmt_vec(offset)} if any(offset) else {})
            ET.SubElement(frame, "attach", model=stem, prefix=copy_prefix(stem, i))
        tail = _indent(copies.home(sum(c.count * c.segments for c, _ in placed.cords)))
    for cords, anchors in placed.cords:
        _cords(world, cords, anchors)
    text = head.replace("  <asset>", (option + "\n" if option else "") + "  <asset>", 1)
    # The scene's own <asset> (sky, checker) stays; the terrain's hfields go in a second one.
    extra_assets = _indent(assets) if len(assets) else ""
    body_text = _indent(world)
    return text + extra_assets + body_text + tail + "</mujoco>\n"


def write_world_alone(placed: PlacedWorld, out: str, options: object, findings: Findings, validate: bool) -> WorldAlone:
    """``robodesc compile W.world -t mjcf -o world.xml``: the scene with no robot."""
    from robodesc._files import write_atomic

    text = world_scene_text(None, placed, findings, None)
    write_atomic(out, text)
    if not validate:
        return {"mjcf": out}, None
    from robodesc.validation.world import check_mjcf_world

    # Every geom written directly in the world body (the ground's), as MuJoCo should count them.
    body = ET.fromstring(text).find("worldbody")
    geoms = len(body.findall("geom")) if body is not None else 0
    return {"mjcf": out}, check_mjcf_world(out, placed.world.name, placed.world.physics, geoms)


def _option(placed: PlacedWorld, robot: dict[str, str]) -> str:
    """The world's step and gravity over ``robot`` (robot.xml's own options, which an attached
    copy does not bring: the scene says them once for every copy)."""
    physics = placed.world.physics
    attrs = dict(robot)
    if physics.step is not None:
        attrs["timestep"] = fmt(physics.step)
    if physics.gravity is not None:
        attrs["gravity"] = fmt_vec(physics.gravity)
    if not attrs:
        return ""
    return "  <option " + " ".join(f'{k}="{v}"' for k, v in attrs.items()) + "/>"


def _collider(
    placed: PlacedWorld,
    body: StaticBody,
    collider: WorldCollider,
    assets: ET.Element,
    world: ET.Element,
    findings: Findings,
    robot: RobotSurface | None,
) -> None:
    frame = pose_frame(body.pose) @ pose_frame(collider.origin)
    name = f"{body.name}/{collider.name}"
    attrs: dict[str, str] = {"name": name}
    surface = collider.surface
    mu = surface.mu if surface is not None and surface.mu is not None else 1.0  # ODE's default
    attrs["friction"] = fmt_vec((mu, TORSION, ROLL))
    if robot is not None:  # alone, a world has no robot whose friction to yield to or win over
        attrs["priority"] = str(_priority(mu, robot, collider, body, findings))
    shape = collider.shape
    grid = placed.grid_of(collider)
    if grid is not None:
        _heightfield(grid, name, attrs, assets, world)
        return
    if isinstance(shape, Plane):
        attrs.update(type="plane", size="0 0 0.05", material="groundplane")
    elif isinstance(shape, Box):
        attrs.update(type="box", size=fmt_vec(s / 2 for s in shape.size))
    elif isinstance(shape, Sphere):
        attrs.update(type="sphere", size=fmt(shape.radius))
    elif isinstance(shape, Cylinder):
        attrs.update(type="cylinder", size=fmt_vec((shape.radius, shape.length / 2)))
    elif isinstance(shape, Mesh | HeightImage):
        findings.warn(
            "mjcf-world-mesh-hull",
            "no heightfield could be made from this terrain (the warning above says why): it is left out of "
            "scene.xml, since MuJoCo would collide its convex hull",
            element=f"collision {collider.name!r} of {body.name!r}",
            loc=collider.src,
            stage=STAGE,
        )
        return
    ET.SubElement(world, "geom", _placed(attrs, frame))


def _cords(world: ET.Element, cords: CordField, anchors: list[Vec3]) -> None:
    """Each cord a chain of capsule bodies on ball joints (MuJoCo applies a ball joint's stiffness and
    damping to its rotation), hanging along -z from a body welded to the world at its anchor."""
    step = cords.length / cords.segments
    mass = cords.cord_mass / cords.segments
    for i, anchor in enumerate(anchors):
        parent = ET.SubElement(world, "body", name=f"{cords.name}_{i}", pos=fmt_vec(anchor))
        for k in range(cords.segments):
            attrs = {"name": f"{cords.name}_{i}_{k}"}
            if k:
                attrs["pos"] = fmt_vec((0.0, 0.0, -step))
            segment = ET.SubElement(parent, "body", attrs)
            ET.SubElement(
                segment,
                "joint",
                name=f"{cords.name}_{i}_{k}",
                type="ball",
                stiffness=fmt(cords.stiffness),
                damping=fmt(cords.damping),
                # robot.xml's top-level <default> (its joints' damping, friction, armature) holds for
                # the whole scene: a cord's joints say theirs.
                armature="0",
                frictionloss="0",
            )
            # Explicit inertia: robot.xml's <compiler inertiafromgeom="false"> holds for the whole scene.
            # A solid cylinder of the segment's length: the capsule's caps are a few percent more.
            side = mass * (3 * cords.radius**2 + step**2) / 12
            ET.SubElement(
                segment,
                "inertial",
                pos=fmt_vec((0.0, 0.0, -step / 2)),
                mass=fmt(mass),
                diaginertia=fmt_vec((side, side, mass * cords.radius**2 / 2)),
            )
            ET.SubElement(
                segment,
                "geom",
                type="capsule",
                fromto=fmt_vec((0.0, 0.0, 0.0, 0.0, 0.0, -step)),
                size=fmt(cords.radius),
            )
            parent = segment


def _priority(mu: float, robot: RobotSurface, collider: WorldCollider, body: StaticBody, findings: Findings) -> int:
    """Gazebo (ODE) takes the smaller friction of two surfaces; MuJoCo takes the larger, or the
    higher-priority geom's. A world that grips at least as much as every robot collider (Quad-SDK's
    terrains: mu 100) yields to the robot (priority below it), one that grips less wins over it:
    ODE's minimum either way. MuJoCo at mu 100 sinks the robot through its solver's soft contacts."""
    element = f"collision {collider.name!r} of {body.name!r}"
    if mu >= robot.mu_high:
        findings.info(
            "mjcf-world-friction",
            f"mu {mu:g}; the robot's colliders have {_range(robot)}: Gazebo uses the smaller of two, so the terrain "
            "yields to each robot collider's own friction (a lower geom priority)",
            element=element,
            loc=collider.src,
            stage=STAGE,
        )
        return robot.priority - 1
    if mu > robot.mu_low:
        findings.warn(
            "mjcf-world-friction-mixed",
            f"mu {mu:g} lies inside the robot's {_range(robot)}: MuJoCo applies the terrain's mu to every robot "
            "collider, where Gazebo keeps the smaller one (the robot's below it)",
            element=element,
            loc=collider.src,
            stage=STAGE,
        )
    return robot.priority + 1


def _range(robot: RobotSurface) -> str:
    if robot.mu_low == robot.mu_high:
        return f"mu {robot.mu_low:g}"
    return f"mu {robot.mu_low:g} to {robot.mu_high:g}"


def _heightfield(grid: TerrainGrid, name: str, attrs: dict[str, str], assets: ET.Element, world: ET.Element) -> None:
    field = grid.mujoco()
    width, depth = field.half
    if field.heights is None:
        attrs.update(type="box", size=fmt_vec((width, depth, HFIELD_BASE / 2)))
        ET.SubElement(world, "geom", _placed(attrs, field.frame))
        return
    rows, cols = field.heights.shape
    # Heights to 0.1 µm: float noise (2.8e-17) is no height.
    rel = np.round(field.heights, 7) + 0.0
    ET.SubElement(
        assets,
        "hfield",
        name=name,
        nrow=str(rows),
        ncol=str(cols),
        size=fmt_vec((width, depth, field.span, HFIELD_BASE)),
        elevation=" ".join(f"{v:.7g}" for v in rel.ravel()),
    )
    attrs.update(type="hfield", hfield=name)
    ET.SubElement(world, "geom", _placed(attrs, field.frame))


def _placed(attrs: dict[str, str], frame: Frame) -> dict[str, str]:
    out = dict(attrs)
    if any(abs(v) > 0 for v in frame.translation):
        out["pos"] = fmt_vec(frame.translation)
    quat = frame.quat()
    if abs(quat[0] - 1.0) > 1e-12:
        out["quat"] = fmt_vec(quat)
    return out


def _indent(element: ET.Element) -> str:
    ET.indent(element, space="  ", level=1)
    return "  " + ET.tostring(element, encoding="unicode") + "\n"
