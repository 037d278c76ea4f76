"""Mass properties of HoloScript shapes URDF has no element for (cone, torus, regular polyhedra).

A composition writes such a shape as the closest primitive (a finding says so), but its inertia is
the true shape's: a cone's centre of mass sits a quarter of its height from the base, a torus is
hollow in the middle, a polyhedron is a little less round than its sphere. Every result here is
about the centre of mass, in the shape's own frame: the axis of a cone or torus is +z, a cone's apex
points to +z and its centre of mass is at ``com_z`` (the frame's origin is the middle of the
bounding box, as in three.js).

>>> props = cone(mass=3.0, radius=0.1, height=0.4)
>>> round(props.com_z, 6), round(props.inertia[2], 6)
(-0.1, 0.009)
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True, slots=True)
class SolidProps:
    inertia: tuple[float, float, float]  # ixx, iyy, izz about the centre of mass (principal)
    com_z: float = 0.0  # the centre of mass along the shape's axis, from the bounding box centre


def cone(mass: float, radius: float, height: float) -> SolidProps:
    """Solid cone: I_axis = 3/10 m r², I_perp = m (3r²/20 + 3h²/80) about the centre of mass."""
    axial = 0.3 * mass * radius**2
    perp = mass * (3.0 * radius**2 / 20.0 + 3.0 * height**2 / 80.0)
    return SolidProps((perp, perp, axial), com_z=-height / 4.0)


def torus(mass: float, major: float, minor: float) -> SolidProps:
    """Solid torus of centre-line radius ``major`` and tube radius ``minor``, axis +z:
    I_axis = m (R² + 3a²/4), I_perp = m (R²/2 + 5a²/8)."""
    axial = mass * (major**2 + 0.75 * minor**2)
    perp = mass * (0.5 * major**2 + 0.625 * minor**2)
    return SolidProps((perp, perp, axial))


_PHI = (1.0 + math.sqrt(5.0)) / 2.0


def _polyhedron_vertices(kind: str) -> np.ndarray:
    v: list[tuple[float, float, float]]
    if kind == "tetrahedron":
        v = [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]
    elif kind == "octahedron":
        v = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    elif kind == "icosahedron":
        v = [(0, s1, s2 * _PHI) for s1 in (-1, 1) for s2 in (-1, 1)]
        v += [(s1, s2 * _PHI, 0) for s1 in (-1, 1) for s2 in (-1, 1)]
        v += [(s2 * _PHI, 0, s1) for s1 in (-1, 1) for s2 in (-1, 1)]
    elif kind == "dodecahedron":
        v = [(a, b, c) for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)]
        g = 1.0 / _PHI
        v += [(0, s1 * g, s2 * _PHI) for s1 in (-1, 1) for s2 in (-1, 1)]
        v += [(s1 * g, s2 * _PHI, 0) for s1 in (-1, 1) for s2 in (-1, 1)]
        v += [(s2 * _PHI, 0, s1 * g) for s1 in (-1, 1) for s2 in (-1, 1)]
    else:
        raise ValueError(kind)
    pts = np.asarray(v, dtype=float)
    unit: np.ndarray = pts / np.linalg.norm(pts, axis=1, keepdims=True)  # circumradius 1
    return unit


@functools.cache
def _polyhedron_factor(kind: str) -> float:
    """k in I = k m R² for a solid regular polyhedron of circumradius R (its tensor is isotropic)."""
    import trimesh

    hull = trimesh.Trimesh(vertices=_polyhedron_vertices(kind)).convex_hull
    props = hull.mass_properties
    return float(props.inertia[0][0] / props.mass)


POLYHEDRA = ("tetrahedron", "octahedron", "icosahedron", "dodecahedron")


def polyhedron(kind: str, mass: float, circumradius: float) -> SolidProps:
    i = _polyhedron_factor(kind) * mass * circumradius**2
    return SolidProps((i, i, i))
