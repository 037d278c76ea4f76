"""Volume, centre of volume and inertia tensor of a triangle mesh, at unit density, in numpy.

What trimesh computes for ``trimesh.load(path, force="mesh")`` then ``is_watertight``,
``convex_hull``, ``volume``, ``center_mass`` and ``moment_inertia``, without importing trimesh
(over a second with scipy, more than compiling a robot to MJCF):

- **Reading**: robodesc's own readers (:func:`robodesc.meshes.readers.read_triangles`: the C STL,
  OBJ and COLLADA paths), trimesh only for the formats they do not read.
- **Merging**: as trimesh's default processing (``grouping.merge_vertices``): vertices that faces
  use are grouped by their coordinates times 10⁸ rounded to integers (``tol.merge`` = 1e-8), each
  group kept as its first vertex; faces with a non-finite coordinate are dropped first. STL stores
  every corner on its own, so this is what makes its closed surfaces closed.
- **Watertight**: trimesh's ``graph.is_watertight``: every edge (unordered vertex pair) is shared by
  exactly two faces.
- **Integrals**: the signed-tetrahedron sums of D. Eberly, *Polyhedral Mass Properties (Revisited)*
  (Geometric Tools, 2002; https://www.geometrictools.com/Documentation/PolyhedralMassProperties.pdf),
  written as trimesh's ``triangles.mass_properties`` writes them, term for term, so that the two
  agree to rounding. For triangle (p0, p1, p2) with normal d = (p1 - p0) × (p2 - p1)::

      f1 = p0 + p1 + p2                       (per coordinate)
      f2 = p0² + p1² + p0 p1 + p2 f1
      f3 = p0³ + p0² p1 + p0 p1² + p1³ + p2 f2
      gi = f2 + (pi + f1) pi
      V  = Σ dx f1x / 6          ∫x = Σ dx f2x / 24 (same for y, z)
      ∫x² = Σ dx f3x / 60        ∫xy = Σ dx (x0 g0y + x1 g1y + x2 g2y) / 120 (cyclic: xy, yz, zx)

  and the tensor about the centre c = ∫(x, y, z) / V is ixx = ∫y² + ∫z² - V (cy² + cz²),
  ixy = -(∫xy - V cx cy), and so on. Sums only: no eigen-decomposition, so no BLAS-dependent bits.
- **Open meshes**: the convex hull of the merged points (``scipy.spatial.ConvexHull`` with trimesh's
  qhull options ``QbB Pp Qt``, imported only here), its faces wound outwards and its points merged
  again as trimesh's hull mesh merges them.

A surface wound inside out (negative volume) is turned over (trimesh's ``invert``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from robodesc.meshes.buffers import MeshReadError

try:
    from robodesc.meshes import _weld as _cweld
except ImportError:  # installed without a C compiler: np.unique does the merge
    _cweld = None  # type: ignore[assignment]

F64 = NDArray[np.float64]
Ints = NDArray[np.int64]

MERGE_DIGITS = 8  # trimesh's tol.merge = 1e-8 as digits
QHULL_OPTIONS = "QbB Pp Qt"  # trimesh.convex.convex_hull's default


@dataclass(slots=True, frozen=True)
class Solid:
    """Unit-density properties: ``volume`` (m³), ``com`` (m), ``tensor`` about ``com`` (m⁵)."""

    volume: float
    com: F64
    tensor: F64
    watertight: bool  # False: the properties are the convex hull's


def read_merged(path: str) -> tuple[F64, Ints]:
    """A mesh file's vertices (float64, file units) and faces ((n, 3) indices), vertices merged as
    trimesh merges them. Raises :class:`MeshReadError` for an unreadable file."""
    # Imported here: a robot whose inertia comes from primitives alone needs no mesh reader.
    from robodesc.meshes.readers import read_triangles

    vertices, indices, _ = read_triangles(path)
    faces = np.asarray(indices, dtype=np.int64).reshape(-1, 3)
    return merge_vertices(np.asarray(vertices, dtype=np.float64).reshape(-1, 3), faces)


def merge_vertices(vertices: F64, faces: Ints) -> tuple[F64, Ints]:
    """trimesh's ``merge_vertices`` (default digits, no UV or normals): the used vertices grouped by
    ``round(v * 1e8)``, each group kept as its first member, in order of first appearance."""
    if len(faces) and (faces.min() < 0 or faces.max() >= len(vertices)):
        raise MeshReadError("a face refers to a vertex that does not exist")
    finite = np.asarray(np.isfinite(vertices).all(axis=1), dtype=bool)
    if not finite.all():  # trimesh's remove_infinite_values: such faces go
        faces = faces[finite[faces].all(axis=1)]
    used = np.zeros(len(vertices), dtype=bool)
    used[faces] = True
    where = np.flatnonzero(used)
    # Rounded in float64 (exact integers below 2^53) rather than int64: the C weld takes float rows.
    # Adding 0.0 makes -0.0 into 0.0, which the integer keys of trimesh do not tell apart.
    keys = np.ascontiguousarray(np.round(vertices[where] * 10**MERGE_DIGITS) + 0.0)
    if _cweld is not None:
        first_raw, inverse_raw = _cweld.weld(keys, None)
        first = np.frombuffer(first_raw, dtype=np.int64)
        inverse = np.frombuffer(inverse_raw, dtype=np.int32).astype(np.int64)
    else:
        _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
        inverse = inverse.reshape(-1)
    remap = np.zeros(len(vertices), dtype=np.int64)
    remap[where] = inverse
    return vertices[where[first]], remap[faces]


def is_watertight(faces: Ints) -> bool:
    """Every edge shared by exactly two faces (trimesh's ``graph.is_watertight``)."""
    if len(faces) == 0:
        return False
    edges = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    edges.sort(axis=1)
    codes = edges[:, 0] * (int(faces.max()) + 1) + edges[:, 1]
    if len(codes) % 2:
        return False
    codes.sort()
    # Sorted, a closed surface's edges come in pairs: each pair equal, each pair unlike the next.
    return bool(np.all(codes[0::2] == codes[1::2]) and np.all(codes[1:-1:2] != codes[2::2]))


def integrals(triangles: F64) -> tuple[float, F64, F64]:
    """Signed volume, centre of volume and the tensor about it of closed (n, 3, 3) triangles."""
    p0, p1, p2 = triangles[:, 0, :], triangles[:, 1, :], triangles[:, 2, :]
    edges = triangles[:, 1:, :] - triangles[:, :2, :]
    crosses = np.cross(edges[:, 0], edges[:, 1])
    f1 = p0 + p1 + p2
    f2 = p0**2 + p1**2 + p0 * p1 + p2 * f1
    f3 = p0**3 + p0**2 * p1 + p0 * p1**2 + p1**3 + p2 * f2
    g0 = f2 + (p0 + f1) * p0
    g1 = f2 + (p1 + f1) * p1
    g2 = f2 + (p2 + f1) * p2
    terms = np.zeros((10, len(f1)))
    terms[0] = crosses[:, 0] * f1[:, 0]
    terms[1:4] = (crosses * f2).T
    terms[4:7] = (crosses * f3).T
    for i in range(3):
        j = (i + 1) % 3
        terms[i + 7] = crosses[:, i] * (p0[:, j] * g0[:, i] + p1[:, j] * g1[:, i] + p2[:, j] * g2[:, i])
    s = terms.sum(axis=1) / np.array([6, 24, 24, 24, 60, 60, 60, 120, 120, 120], dtype=np.float64)
    volume = float(s[0])
    com = s[1:4] / volume
    cx, cy, cz = com
    tensor = np.zeros((3, 3))
    tensor[0, 0] = s[5] + s[6] - volume * (cy**2 + cz**2)
    tensor[1, 1] = s[4] + s[6] - volume * (cx**2 + cz**2)
    tensor[2, 2] = s[4] + s[5] - volume * (cx**2 + cy**2)
    tensor[0, 1] = tensor[1, 0] = -(s[7] - volume * (cx * cy))
    tensor[1, 2] = tensor[2, 1] = -(s[8] - volume * (cy * cz))
    tensor[0, 2] = tensor[2, 0] = -(s[9] - volume * (cx * cz))
    return volume, com, tensor


def convex_hull(vertices: F64) -> tuple[F64, Ints]:
    """The hull's points and triangles, wound outwards (scipy's qhull, imported here only)."""
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = ConvexHull(vertices, qhull_options=QHULL_OPTIONS)
    except QhullError:  # flat or degenerate: trimesh retries with joggled input
        hull = ConvexHull(vertices, qhull_options="QJ")
    faces = np.asarray(hull.simplices, dtype=np.int64)
    points = np.asarray(hull.points, dtype=np.float64)
    tri = points[faces]
    crosses = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 1])
    inward = np.einsum("ij,ij->i", crosses, hull.equations[:, :3]) < 0.0
    faces[inward] = faces[inward][:, ::-1]
    # trimesh makes the hull a processed Trimesh: its points merged again (at 1e-8, after the scale).
    return merge_vertices(points, faces)


def solid(vertices: F64, faces: Ints) -> Solid:
    """Properties of the merged mesh, or of its convex hull when it is not watertight."""
    watertight = is_watertight(faces)
    if not watertight:
        vertices, faces = convex_hull(vertices)
    with np.errstate(invalid="ignore", divide="ignore"):  # degenerate meshes: the caller checks
        volume, com, tensor = integrals(vertices[faces])
        if volume < 0:  # inside out, or mirrored by a negative scale: turned over
            volume, com, tensor = integrals(vertices[faces[:, ::-1]])
    return Solid(volume, com, tensor, watertight)
