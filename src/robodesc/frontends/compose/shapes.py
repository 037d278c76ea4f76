"""Shape constructors for compositions, and the volumes that turn a density into a mass.

>>> box(0.1, 0.2, 0.3).size
(0.1, 0.2, 0.3)
"""

from __future__ import annotations

import math

from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Mesh, Sphere, Vec3


def box(x: float, y: float, z: float) -> Box:
    """A box of extents ``x, y, z`` (m), centred on its origin."""
    return Box(size=(float(x), float(y), float(z)))


def cylinder(radius: float, length: float) -> Cylinder:
    """A cylinder along local Z, centred on its origin."""
    return Cylinder(radius=float(radius), length=float(length))


def sphere(radius: float) -> Sphere:
    return Sphere(radius=float(radius))


def capsule(radius: float, length: float) -> Capsule:
    """A capsule along local Z; ``length`` is the cylinder part without the caps."""
    return Capsule(radius=float(radius), length=float(length))


def mesh(uri: str, scale: float | Vec3 | None = None) -> Mesh:
    """A mesh file: a relative path (against the composition's folder), absolute, or ``package://``."""
    if isinstance(scale, int | float):
        s = float(scale)
        return Mesh(uri=uri, scale=(s, s, s))
    return Mesh(uri=uri, scale=None if scale is None else (float(scale[0]), float(scale[1]), float(scale[2])))


def volume(geom: Geometry) -> float | None:
    """Volume in m³; ``None`` for meshes (their volume needs the file)."""
    if isinstance(geom, Box):
        return geom.size[0] * geom.size[1] * geom.size[2]
    if isinstance(geom, Cylinder):
        return math.pi * geom.radius**2 * geom.length
    if isinstance(geom, Sphere):
        return 4.0 / 3.0 * math.pi * geom.radius**3
    if isinstance(geom, Capsule):
        return math.pi * geom.radius**2 * geom.length + 4.0 / 3.0 * math.pi * geom.radius**3
    return None


def mesh_volume(path: str) -> float | None:
    """Volume of a watertight mesh file (scaled by nothing), or ``None`` when it cannot be known."""
    try:
        import trimesh
    except ImportError:  # pragma: no cover - trimesh is a dependency
        return None
    try:
        loaded = trimesh.load(path, force="mesh")
    except Exception:  # trimesh raises many types for unreadable files
        return None
    if not getattr(loaded, "is_watertight", False):
        return None
    return abs(float(getattr(loaded, "volume", 0.0)))
