"""A world's static models in SDF (``-t sdf --world FILE``): each static body a ``<static>`` model,
its colliders as written (a terrain mesh collides as its triangles in Gazebo, which is what the
world's author saw), a visual of the same shape, and ODE's friction. The world's own physics step
and gravity go in the world's ``<physics>`` (emit/sdf/world.py)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from lxml import etree

from robodesc.emit.common.numbers import fmt, fmt_vec
from robodesc.emit.common.paths import PathMode, mesh_reference
from robodesc.emit.sdf.options import SdfOptions
from robodesc.ir.geometry import Box, Cylinder, Mesh, Pose, Sphere, Vec3
from robodesc.ir.world import CordField, HeightImage, Plane, WorldCollider

if TYPE_CHECKING:
    from robodesc.emit.common.world import PlacedWorld

E = etree.SubElement


def world_models(world: etree._Element, placed: PlacedWorld, options: SdfOptions) -> None:
    for cords, anchors in placed.cords:
        _cords(world, cords, anchors)
    for body in placed.world.bodies:
        model = E(world, "model", name=body.name)
        E(model, "static").text = "true"
        E(model, "pose").text = _pose(body.pose)
        link = E(model, "link", name="link")
        for collider in body.colliders:
            geometry = _geometry(collider, options)
            if geometry is None:
                continue
            for tag in ("collision", "visual"):
                el = E(link, tag, name=f"{collider.name}" if tag == "collision" else f"{collider.name}_visual")
                E(el, "pose").text = _pose(collider.origin)
                el.append(_copy(geometry))
                if tag == "collision" and collider.surface is not None and collider.surface.mu is not None:
                    ode = E(E(E(el, "surface"), "friction"), "ode")
                    E(ode, "mu").text = fmt(collider.surface.mu)
                    E(ode, "mu2").text = fmt(
                        collider.surface.mu2 if collider.surface.mu2 is not None else collider.surface.mu
                    )


def _cords(world: etree._Element, cords: CordField, anchors: list[Vec3]) -> None:
    """Each cord a model: capsule links on ``ball`` joints, the first to the world at the anchor. SDF's
    ball joint has no axis, so no spring or damping: the bending stiffness is lost (the target warns)."""
    step = cords.length / cords.segments
    mass = cords.cord_mass / cords.segments
    side = mass * (3 * cords.radius**2 + step**2) / 12
    for i, anchor in enumerate(anchors):
        model = E(world, "model", name=f"{cords.name}_{i}")
        E(model, "pose").text = fmt_vec((*anchor, 0.0, 0.0, 0.0))
        parent = "world"
        for k in range(cords.segments):
            name = f"s{k}"
            link = E(model, "link", name=name)
            E(link, "pose").text = fmt_vec((0.0, 0.0, -k * step, 0.0, 0.0, 0.0))
            inertial = E(link, "inertial")
            E(inertial, "pose").text = fmt_vec((0.0, 0.0, -step / 2, 0.0, 0.0, 0.0))
            E(inertial, "mass").text = fmt(mass)
            inertia = E(inertial, "inertia")
            for tag, value in (("ixx", side), ("iyy", side), ("izz", mass * cords.radius**2 / 2)):
                E(inertia, tag).text = fmt(value)
            for tag in ("collision", "visual"):
                el = E(link, tag, name=tag)
                E(el, "pose").text = fmt_vec((0.0, 0.0, -step / 2, 0.0, 0.0, 0.0))
                capsule = E(E(el, "geometry"), "capsule")
                E(capsule, "radius").text = fmt(cords.radius)
                E(capsule, "length").text = fmt(step)
            joint = E(model, "joint", name=f"j{k}", type="ball")
            E(joint, "parent").text = parent
            E(joint, "child").text = name
            parent = name


def _geometry(collider: WorldCollider, options: SdfOptions) -> etree._Element | None:
    geometry = etree.Element("geometry")
    shape = collider.shape
    if isinstance(shape, Mesh):
        mesh = E(geometry, "mesh")
        mode = options.path_mode if isinstance(options.path_mode, PathMode) else PathMode.RELATIVE
        E(mesh, "uri").text = mesh_reference(shape, mode, options.out_dir)
        if shape.scale is not None:
            E(mesh, "scale").text = fmt_vec(shape.scale)
    elif isinstance(shape, HeightImage):
        heightmap = E(geometry, "heightmap")
        E(heightmap, "uri").text = shape.path
        E(heightmap, "size").text = fmt_vec(shape.size)
    elif isinstance(shape, Box):
        E(E(geometry, "box"), "size").text = fmt_vec(shape.size)
    elif isinstance(shape, Sphere):
        E(E(geometry, "sphere"), "radius").text = fmt(shape.radius)
    elif isinstance(shape, Cylinder):
        cylinder = E(geometry, "cylinder")
        E(cylinder, "radius").text = fmt(shape.radius)
        E(cylinder, "length").text = fmt(shape.length)
    elif isinstance(shape, Plane):
        plane = E(geometry, "plane")
        E(plane, "normal").text = fmt_vec(shape.normal)
        E(plane, "size").text = "100 100"
    else:  # pragma: no cover - the world IR has no other shape
        return None
    return geometry


def _pose(pose: Pose) -> str:
    return fmt_vec((*pose.xyz, *pose.rpy))


def _copy(element: etree._Element) -> etree._Element:
    return etree.fromstring(etree.tostring(element))
