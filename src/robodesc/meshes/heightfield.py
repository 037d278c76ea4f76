"""A terrain mesh as a heightfield: the height of its upward surface on a regular grid.

MuJoCo collides a mesh as its convex hull, so a concave terrain (a step, a gap, rough ground) must
reach it as an ``<hfield>``. A terrain is a height function when every vertical line meets its
upward-facing surface once; Quad-SDK's terrains are closed slabs whose top is one. The grid takes the
highest upward surface at each point; a point where two upward surfaces lie further apart than
:data:`OVERHANG_TOLERANCE` is an overhang (a bridge, a cave), which a heightfield cannot hold.

A grid point under no upward surface (a gap in the terrain) has nothing to stand on; it is given
the lowest height of the grid less ``gap_depth``, deep enough that a foot stepping in falls.

The error is measured where the mesh is exact, at its upward vertices: the grid's height there,
interpolated as MuJoCo's triangles interpolate it, against the vertex's height. Step edges give the
largest error (a step becomes a ramp one cell wide); a finer resolution shrinks it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]

DEFAULT_RESOLUTION = 0.02  # m: 2 cm cells, under a quadruped's foot radius
OVERHANG_TOLERANCE = 1e-3  # m
UP = 1e-6  # a triangle whose normal's z exceeds this faces up
MAX_CELLS = 16_000_000  # a 4000 x 4000 grid: 64 MB of float32 at most


@dataclass(slots=True)
class HeightGrid:
    """Heights ``z[row, col]`` at ``x0 + col * step``, ``y0 + row * step`` (row 0 at the lowest y)."""

    z: Array
    x0: float
    y0: float
    step: float
    max_error: float  # m, at the mesh's upward vertices
    overhang_points: int  # grid points where two upward surfaces differ by more than the tolerance
    gap_points: int  # grid points under no upward surface

    @property
    def shape(self) -> tuple[int, int]:
        rows, cols = self.z.shape
        return int(rows), int(cols)

    @property
    def size(self) -> tuple[float, float]:
        rows, cols = self.shape
        return (cols - 1) * self.step, (rows - 1) * self.step

    def height_at(self, x: Array, y: Array) -> Array:
        """The grid's height at points, interpolated on the two triangles of each cell (MuJoCo's)."""
        return _interpolate(self, np.asarray(x, float), np.asarray(y, float))


class HeightfieldError(ValueError):
    """The mesh cannot be rasterized (no upward surface, or a grid over :data:`MAX_CELLS`)."""


def rasterize(
    vertices: Array, triangles: NDArray[np.int64], resolution: float = DEFAULT_RESOLUTION, gap_depth: float = 1.0
) -> HeightGrid:
    """The heightfield of a terrain mesh (vertices in metres, in the terrain's own frame)."""
    if not resolution > 0:
        raise HeightfieldError(f"resolution must be positive, got {resolution:g}")
    v = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    t = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    corners = v[t]  # (n, 3, 3)
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    lengths = np.linalg.norm(normals, axis=1)
    up = normals[:, 2] > UP * np.maximum(lengths, 1e-300)
    if not up.any():
        raise HeightfieldError("the mesh has no upward-facing triangle: it is not a terrain")
    top = corners[up]
    lo, hi = top[:, :, :2].min(axis=(0, 1)), top[:, :, :2].max(axis=(0, 1))
    cols = int(np.floor((hi[0] - lo[0]) / resolution + 1e-9)) + 1
    rows = int(np.floor((hi[1] - lo[1]) / resolution + 1e-9)) + 1
    if rows * cols > MAX_CELLS:
        raise HeightfieldError(
            f"a {cols} x {rows} grid at {resolution:g} m exceeds {MAX_CELLS:,} points; give a coarser --terrain-resolution"
        )
    highest = np.full((rows, cols), -np.inf)
    lowest = np.full((rows, cols), np.inf)
    for tri in top:
        _splat(tri, lo, resolution, highest, lowest)
    covered = np.isfinite(highest)
    if not covered.any():
        raise HeightfieldError("no grid point lies under the mesh's upward surface; give a finer --terrain-resolution")
    overhang = covered & (highest - lowest > OVERHANG_TOLERANCE)
    floor = float(highest[covered].min()) - gap_depth
    z = np.where(covered, highest, floor)
    grid = HeightGrid(z, float(lo[0]), float(lo[1]), resolution, 0.0, int(overhang.sum()), int((~covered).sum()))
    grid.max_error = _vertex_error(grid, top.reshape(-1, 3))
    return grid


def _vertex_error(grid: HeightGrid, points: Array) -> float:
    """The largest |grid - terrain| at the upward vertices. The terrain's height at a vertex is the
    highest upward vertex at the same x, y: the top of a wall, as the grid takes it."""
    keys = np.round(points[:, :2] / 1e-9).astype(np.int64)
    _, inverse = np.unique(keys, axis=0, return_inverse=True)
    top = np.full(int(inverse.max()) + 1, -np.inf)
    np.maximum.at(top, inverse.ravel(), points[:, 2])
    exact = top[inverse.ravel()]
    return float(np.max(np.abs(grid.height_at(points[:, 0], points[:, 1]) - exact)))


def _splat(tri: Array, lo: Array, step: float, highest: Array, lowest: Array) -> None:
    """Every grid point inside triangle ``tri`` (projected on xy) takes its height there."""
    (x0, y0, z0), (x1, y1, z1), (x2, y2, z2) = tri
    c0 = int(np.ceil((min(x0, x1, x2) - lo[0]) / step - 1e-3))
    c1 = int(np.floor((max(x0, x1, x2) - lo[0]) / step + 1e-3))
    r0 = int(np.ceil((min(y0, y1, y2) - lo[1]) / step - 1e-3))
    r1 = int(np.floor((max(y0, y1, y2) - lo[1]) / step + 1e-3))
    rows, cols = highest.shape
    c0, r0, c1, r1 = max(c0, 0), max(r0, 0), min(c1, cols - 1), min(r1, rows - 1)
    if c1 < c0 or r1 < r0:
        return
    xs = lo[0] + np.arange(c0, c1 + 1) * step
    ys = lo[1] + np.arange(r0, r1 + 1) * step
    gx, gy = np.meshgrid(xs, ys)
    det = (y1 - y2) * (x0 - x2) + (x2 - x1) * (y0 - y2)
    w0 = ((y1 - y2) * (gx - x2) + (x2 - x1) * (gy - y2)) / det
    w1 = ((y2 - y0) * (gx - x2) + (x0 - x2) * (gy - y2)) / det
    w2 = 1.0 - w0 - w1
    # STL stores float32: an edge at 4.7 m reads 4.69999981. A tolerance in barycentric units keeps
    # grid points on an edge inside (1e-5 of a 10 m triangle is 0.1 mm).
    eps = 1e-5
    inside = (w0 >= -eps) & (w1 >= -eps) & (w2 >= -eps)
    if not inside.any():
        return
    z = w0 * z0 + w1 * z1 + w2 * z2
    window_hi = highest[r0 : r1 + 1, c0 : c1 + 1]
    window_lo = lowest[r0 : r1 + 1, c0 : c1 + 1]
    np.maximum(window_hi, np.where(inside, z, -np.inf), out=window_hi)
    # Only points strictly inside count towards an overhang: a point on a step's edge lies on both
    # the lower and the upper tread, which is a wall, not an overhang.
    strict = (w0 > 1e-3) & (w1 > 1e-3) & (w2 > 1e-3)
    np.minimum(window_lo, np.where(strict, z, np.inf), out=window_lo)


def _interpolate(grid: HeightGrid, x: Array, y: Array) -> Array:
    rows, cols = grid.shape
    u = np.clip((x - grid.x0) / grid.step, 0.0, cols - 1.0)
    w = np.clip((y - grid.y0) / grid.step, 0.0, rows - 1.0)
    c = np.minimum(np.floor(u).astype(np.int64), cols - 2) if cols > 1 else np.zeros_like(u, dtype=np.int64)
    r = np.minimum(np.floor(w).astype(np.int64), rows - 2) if rows > 1 else np.zeros_like(w, dtype=np.int64)
    fu, fw = u - c, w - r
    z = grid.z
    c1 = np.minimum(c + 1, cols - 1)
    r1 = np.minimum(r + 1, rows - 1)
    z00, z10, z01, z11 = z[r, c], z[r, c1], z[r1, c], z[r1, c1]
    # Two triangles per cell, split along the diagonal from (c, r) to (c + 1, r + 1).
    lower = fu >= fw
    return np.asarray(
        np.where(
            lower,
            z00 + fu * (z10 - z00) + fw * (z11 - z10),
            z00 + fw * (z01 - z00) + fu * (z11 - z01),
        ),
        dtype=np.float64,
    )


class TerrainSurface:
    """The exact height of a terrain mesh's upward surface at any x, y: the highest upward triangle
    over the point, NaN where there is none (a gap, or off the terrain). What a target that keeps the
    mesh (USD, SDF) collides with; the spawn needs only a few such heights, so no grid is made for it.

    Triangles are bucketed by their x, y box into square cells about twice a typical triangle's
    size, so a query tests only the triangles of its own cell (rough_25cm: ~60 of 10,900)."""

    _SPREAD = 256  # a triangle over more cells than this (a 10 m flat quad) is tested everywhere

    def __init__(self, vertices: Array, triangles: NDArray[np.int64]) -> None:
        v = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
        t = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
        corners = v[t]
        normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        up = normals[:, 2] > UP * np.maximum(np.linalg.norm(normals, axis=1), 1e-300)
        if not up.any():
            raise HeightfieldError("the mesh has no upward-facing triangle: it is not a terrain")
        self.triangles = corners[up]
        lo = self.triangles[:, :, :2].min(axis=1)
        hi = self.triangles[:, :, :2].max(axis=1)
        self.cell = max(2.0 * float(np.median((hi - lo).max(axis=1))), 1e-3)
        self.origin = lo.min(axis=0)
        first = np.floor((lo - self.origin) / self.cell).astype(np.int64)
        last = np.floor((hi - self.origin) / self.cell).astype(np.int64)
        buckets: dict[tuple[int, int], list[int]] = {}
        everywhere: list[int] = []
        for i, (a, b) in enumerate(zip(first.tolist(), last.tolist(), strict=True)):
            if (b[0] - a[0] + 1) * (b[1] - a[1] + 1) > self._SPREAD:
                everywhere.append(i)
                continue
            for cx in range(a[0], b[0] + 1):
                for cy in range(a[1], b[1] + 1):
                    buckets.setdefault((cx, cy), []).append(i)
        self._buckets = {k: np.array(ids + everywhere, dtype=np.int64) for k, ids in buckets.items()}
        self._everywhere = np.array(everywhere, dtype=np.int64)

    def height_at(self, x: Array, y: Array) -> Array:
        """Heights at the points (arrays of one shape); NaN where no upward triangle lies over them."""
        px, py = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
        shape = np.broadcast(px, py).shape
        px, py = np.broadcast_to(px, shape).ravel(), np.broadcast_to(py, shape).ravel()
        out = np.full(px.shape, np.nan)
        cells = np.floor((np.stack([px, py], axis=1) - self.origin) / self.cell).astype(np.int64)
        keys, inverse = np.unique(cells, axis=0, return_inverse=True)
        for k, key in enumerate(keys.tolist()):
            ids = self._buckets.get((key[0], key[1]), self._everywhere)
            if not len(ids):
                continue
            at = np.flatnonzero(inverse.ravel() == k)
            out[at] = _highest(self.triangles[ids], px[at], py[at])
        return out.reshape(shape)


def _highest(tris: Array, x: Array, y: Array) -> Array:
    """For each point, the highest of ``tris`` (n, 3, 3) over it, NaN where none is (barycentric
    test with the rasterizer's tolerance, so an edge shared by two triangles belongs to both)."""
    x0, y0, z0 = tris[:, 0, 0], tris[:, 0, 1], tris[:, 0, 2]
    x1, y1, z1 = tris[:, 1, 0], tris[:, 1, 1], tris[:, 1, 2]
    x2, y2, z2 = tris[:, 2, 0], tris[:, 2, 1], tris[:, 2, 2]
    det = (y1 - y2) * (x0 - x2) + (x2 - x1) * (y0 - y2)
    gx, gy = x[:, None], y[:, None]
    w0 = ((y1 - y2) * (gx - x2) + (x2 - x1) * (gy - y2)) / det
    w1 = ((y2 - y0) * (gx - x2) + (x0 - x2) * (gy - y2)) / det
    w2 = 1.0 - w0 - w1
    eps = 1e-5
    inside = (w0 >= -eps) & (w1 >= -eps) & (w2 >= -eps)
    z = np.where(inside, w0 * z0 + w1 * z1 + w2 * z2, -np.inf)
    best = z.max(axis=1)
    return np.where(np.isfinite(best), best, np.nan)
