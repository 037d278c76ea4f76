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
from robodesc.ir.geometry import Box, Cylinder, Mesh, Pose, Sphere
from robodesc.ir.world import HeightImage, Plane, WorldCollider

if TYPE_CHECKING:
    from robodesc.emit.common.world import PlacedWorld

E = etree.SubElement


def world_models(world: etree._Element, placed: PlacedWorld, options: SdfOptions) -> None:
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
