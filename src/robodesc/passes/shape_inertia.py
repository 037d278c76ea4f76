"""Mass properties of shapes: closed forms for primitives, :mod:`robodesc.meshes.mass` for meshes,
composites.

Everything here works at unit density: a :class:`MassProps` holds the volume, the centre of
volume and the tensor about it for ρ = 1 kg/m³, so a given mass ``M`` scales it by ``M / volume``
(mass split between shapes by volume) and a density ``ρ`` by ``ρ``.

>>> p = primitive_props(Box((1.0, 2.0, 3.0)))
>>> p.volume, float(p.tensor[0, 0])  # ρ=1: m = 6, ixx = 6 (2² + 3²) / 12
(6.0, 6.5)
"""

from __future__ import annotations

import functools
import math
import os
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Inertial, Mesh, Pose, Sphere
from robodesc.ir.inertia import balance, from_tensor, parallel_axis, rotate
from robodesc.ir.model import Link
from robodesc.ir.transforms import rpy_to_matrix
from robodesc.meshes.buffers import MeshReadError
from robodesc.meshes.mass import read_merged, solid

Vec = NDArray[np.float64]


@dataclass(slots=True)
class MassProps:
    """Unit-density mass properties: ``volume`` (m³), ``com`` (m), ``tensor`` about ``com`` (m⁵)."""

    volume: float
    com: Vec
    tensor: Vec
    notes: list[str] = field(default_factory=list)


def primitive_props(geom: Box | Cylinder | Sphere | Capsule) -> MassProps:
    """Closed forms, centred on the shape's frame (cylinder and capsule along local Z)."""
    zero = np.zeros(3)
    if isinstance(geom, Box):
        a, b, c = (abs(s) for s in geom.size)
        v = a * b * c
        return MassProps(v, zero, np.diag([b * b + c * c, a * a + c * c, a * a + b * b]) * v / 12.0)
    if isinstance(geom, Sphere):
        r = geom.radius
        v = 4.0 / 3.0 * math.pi * r**3
        return MassProps(v, zero, np.eye(3) * 0.4 * v * r * r)
    if isinstance(geom, Cylinder):
        r, h = geom.radius, geom.length
        v = math.pi * r * r * h
        ixx = v * (3 * r * r + h * h) / 12.0
        return MassProps(v, zero, np.diag([ixx, ixx, v * r * r / 2.0]))
    # Capsule: a cylinder of length L plus two hemispherical caps (a sphere's volume in total).
    r, h = geom.radius, geom.length
    vc = math.pi * r * r * h
    vs = 4.0 / 3.0 * math.pi * r**3
    izz = vc * r * r / 2.0 + 0.4 * vs * r * r
    # Each cap's centroid sits 3r/8 from its flat face; the parallel-axis terms sum to this.
    ixx = vc * (h * h / 12.0 + r * r / 4.0) + vs * (0.4 * r * r + h * h / 4.0 + 3.0 * h * r / 8.0)
    return MassProps(vc + vs, zero, np.diag([ixx, ixx, izz]))


@functools.lru_cache(maxsize=256)
def _mesh_props_cached(
    path: str, mtime: float, scale: tuple[float, float, float]
) -> tuple[float, tuple[float, ...], tuple[float, ...], str | None]:
    try:
        vertices, faces = read_merged(path)
    except MeshReadError as exc:
        raise ValueError(str(exc)) from None
    if len(faces) == 0:
        raise ValueError("no triangles")
    found = solid(vertices * np.asarray(scale, dtype=np.float64), faces)
    if not found.volume > 1e-18 or not np.all(np.isfinite(found.com)):
        raise ValueError("zero volume")
    note = None
    if not found.watertight:
        note = f"mesh {os.path.basename(path)!r} is not watertight: its convex hull was used"
    return found.volume, tuple(float(x) for x in found.com), tuple(float(x) for x in found.tensor.ravel()), note


def mesh_props(mesh: Mesh) -> MassProps:
    """Volume, centre and tensor of a mesh file (convex hull when it is not watertight).

    Raises ``ValueError`` when the file is missing or has no volume.
    """
    if mesh.path is None or not os.path.isfile(mesh.path):
        raise ValueError(f"mesh file {mesh.path or mesh.uri!r} is not available")
    scale = mesh.scale or (1.0, 1.0, 1.0)
    try:
        volume, com, tensor, note = _mesh_props_cached(mesh.path, os.path.getmtime(mesh.path), scale)
    except ValueError as exc:
        raise ValueError(f"mesh {mesh.path!r}: {exc}") from None
    except Exception as exc:  # readers (and trimesh, for other formats) raise many types on bad files
        raise ValueError(f"mesh {mesh.path!r} could not be read: {exc}") from None
    return MassProps(volume, np.array(com), np.array(tensor).reshape(3, 3), [note] if note else [])


def geometry_props(geom: Geometry) -> MassProps:
    if isinstance(geom, Mesh):
        return mesh_props(geom)
    return primitive_props(geom)


def place(props: MassProps, pose: Pose | None) -> MassProps:
    """Express shape-frame properties in the link frame."""
    if pose is None:
        return props
    r = rpy_to_matrix(pose.rpy)
    com = r @ props.com + np.asarray(pose.xyz, dtype=float)
    return MassProps(props.volume, com, rotate(props.tensor, r), list(props.notes))


def combine(parts: list[MassProps]) -> MassProps:
    """One body from several shapes of the same density (parallel-axis theorem)."""
    volume = sum(p.volume for p in parts)
    com = sum((p.volume * p.com for p in parts), np.zeros(3)) / volume
    tensor = sum((parallel_axis(p.tensor, p.volume, p.com - com) for p in parts), np.zeros((3, 3)))
    return MassProps(volume, com, tensor, [n for p in parts for n in p.notes])


def link_props(link: Link) -> tuple[MassProps, str] | None:
    """Unit-density properties of the link's collision shapes, else its visual shapes."""
    for source, shapes in (
        ("collision", [(c.geometry, c.origin) for c in link.collisions]),
        ("visual", [(v.geometry, v.origin) for v in link.visuals]),
    ):
        if not shapes:
            continue
        try:
            parts = [place(geometry_props(g), o) for g, o in shapes]
        except ValueError:
            continue
        return combine(parts), source
    return None


def inertial_from_props(props: MassProps, *, mass: float, origin: Pose | None = None) -> Inertial:
    """An inertial of ``mass`` with the shape's distribution.

    With ``origin`` ``None`` the centre of mass is the shape's and the tensor is in link axes. A given
    origin is kept (the input said where the centre of mass is) and the tensor is taken about it.
    """
    scale = mass / props.volume
    # Flat shapes sit on the triangle-inequality boundary; nudge them strictly inside (ir.inertia.balance).
    tensor, _ = balance(props.tensor * scale)
    if origin is None:
        xyz = (float(props.com[0]), float(props.com[1]), float(props.com[2]))
        return Inertial(mass=mass, origin=Pose(xyz=xyz), inertia=from_tensor(tensor))
    p = np.asarray(origin.xyz, dtype=float)
    about_p = parallel_axis(tensor, mass, props.com - p)
    r = rpy_to_matrix(origin.rpy)
    local = r.T @ about_p @ r
    return Inertial(mass=mass, origin=Pose(xyz=origin.xyz, rpy=origin.rpy), inertia=from_tensor(local))
