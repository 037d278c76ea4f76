"""Terrain meshes as heightfields (robodesc.meshes.heightfield): exact where the grid meets the
mesh's vertices, walls kept as the top of the wall, overhangs and gaps counted."""

from __future__ import annotations

import numpy as np
import pytest

from robodesc.meshes.heightfield import HeightfieldError, rasterize


def slab(x0: float, x1: float, y0: float, y1: float, top: float, bottom: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """A closed box: its top faces up, its bottom down, its walls sideways."""
    v = np.array(
        [[x, y, z] for z in (bottom, top) for y in (y0, y1) for x in (x0, x1)],
        dtype=np.float64,
    )
    faces = [
        (4, 5, 7), (4, 7, 6),  # top (counter-clockwise seen from above: normal +z)
        (0, 2, 3), (0, 3, 1),  # bottom
        (0, 1, 5), (0, 5, 4), (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5),
    ]  # fmt: skip
    return v, np.array(faces, dtype=np.int64)


def merged(*parts: tuple[np.ndarray, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    vertices, faces, offset = [], [], 0
    for v, f in parts:
        vertices.append(v)
        faces.append(f + offset)
        offset += len(v)
    return np.vstack(vertices), np.vstack(faces)


def test_a_step_is_exact_on_the_grid() -> None:
    v, f = merged(slab(0, 1, 0, 1, 0.1), slab(1, 2, 0, 1, 0.3))
    grid = rasterize(v, f, resolution=0.1)
    assert grid.shape == (11, 21)
    assert grid.overhang_points == 0 and grid.gap_points == 0
    assert grid.max_error == pytest.approx(0.0, abs=1e-12)
    assert np.allclose(grid.z[:, :10], 0.1) and np.allclose(grid.z[:, 11:], 0.3)
    assert np.allclose(grid.z[:, 10], 0.3)  # the wall's column takes the top of the wall
    # Between grid points the wall becomes a ramp one cell wide.
    assert grid.height_at(np.array([0.95]), np.array([0.5]))[0] == pytest.approx(0.2)


def test_a_slope_is_exact_between_grid_points() -> None:
    v = np.array([[0, 0, 0], [2, 0, 1], [2, 1, 1], [0, 1, 0]], dtype=np.float64)
    f = np.array([[0, 1, 2], [0, 2, 3]])
    grid = rasterize(v, f, resolution=0.25)
    x = np.array([0.3, 1.1, 1.9])
    assert np.allclose(grid.height_at(x, np.array([0.4, 0.6, 0.2])), x / 2)


def test_a_gap_lies_below_the_lowest_surface() -> None:
    v, f = merged(slab(0, 1, 0, 1, 0.1), slab(1.5, 2.5, 0, 1, 0.1))
    grid = rasterize(v, f, resolution=0.1, gap_depth=1.0)
    gap = grid.z[:, 11:15]
    assert np.allclose(gap, 0.1 - 1.0)
    assert grid.gap_points == gap.size
    assert grid.max_error == pytest.approx(0.0, abs=1e-12)


def test_an_overhang_is_counted() -> None:
    # A bridge over a lower slab: two upward surfaces over the same points.
    v, f = merged(slab(0, 2, 0, 1, 0.1), slab(0.5, 1.5, 0, 1, 1.0, bottom=0.8))
    grid = rasterize(v, f, resolution=0.1)
    assert grid.overhang_points > 0
    assert np.allclose(grid.z[5, 8], 1.0)  # the heightfield keeps the higher surface


def test_float32_edges_stay_on_the_grid() -> None:
    # STL stores float32: the far edge of a slab at 5.4 m reads 5.4000001.
    v, f = merged(slab(0, 5, 0, 1, 0.1), slab(float(np.float32(5.4)), 9, 0, 1, 0.1))
    grid = rasterize(v.astype(np.float32).astype(np.float64), f, resolution=0.02)
    assert grid.max_error == pytest.approx(0.0, abs=1e-6)
    assert grid.gap_points == 19 * grid.shape[0]


def test_refusals() -> None:
    v, f = slab(0, 1, 0, 1, 0.1)
    with pytest.raises(HeightfieldError, match="resolution"):
        rasterize(v, f, resolution=0.0)
    with pytest.raises(HeightfieldError, match="no upward-facing"):
        rasterize(v, f[2:4], resolution=0.1)  # the bottom only
    with pytest.raises(HeightfieldError, match="exceeds"):
        rasterize(v * 1e4, f, resolution=1e-3)


def test_the_surface_is_the_mesh_exactly() -> None:
    """TerrainSurface (what the spawn reads, no grid): each tread's own height, the higher one on the
    wall's line (a grid would ramp across a cell), NaN over the gap and off the terrain."""
    from robodesc.meshes.heightfield import TerrainSurface

    v, f = merged(slab(0, 1, 0, 1, 0.1), slab(1, 2, 0, 1, 0.3), slab(2.5, 3, 0, 1, 0.2))
    surface = TerrainSurface(v, f)
    x = np.array([0.5, 0.999, 1.0, 1.001, 1.5, 2.2, 2.7, 3.5])
    z = surface.height_at(x, np.full(len(x), 0.5))
    assert z[:2] == pytest.approx([0.1, 0.1], abs=1e-12)
    assert z[2:5] == pytest.approx([0.3, 0.3, 0.3], abs=1e-12)
    assert np.isnan(z[5]) and z[6] == pytest.approx(0.2, abs=1e-12) and np.isnan(z[7])
    # Where the grid meets the mesh's vertices, it and the surface agree.
    grid = rasterize(v, f, resolution=0.1)
    xs, ys = np.meshgrid(np.arange(0, 2.01, 0.1), np.arange(0, 1.01, 0.1))
    inside = (xs < 0.95) | (xs > 1.05)  # not the cell a wall ramps across
    assert np.max(np.abs(surface.height_at(xs, ys) - grid.height_at(xs, ys))[inside]) < 1e-9
