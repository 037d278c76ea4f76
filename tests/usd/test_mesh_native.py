"""The C weld and face normals (``robodesc._meshweld``) against robodesc's numpy code, bit for bit.

The numpy code is the fallback when the extension is not built, and was itself checked against
np.unique and np.cross (test_mesh_readers.py); here both run on the same input and must agree
exactly, on hand-made edge cases, random meshes and every STL and COLLADA file of the corpora.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest
from numpy.typing import NDArray
from test_mesh_readers import SHARED_CORPUS, corpus_files

from robodesc.emit import number_text, usd_meshio
from robodesc.emit.mesh_collada import read_collada_indexed
from robodesc.emit.usd import UsdOptions, emit_usd
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions
from robodesc.passes.options import PassOptions
from robodesc.passes.pipeline import run_passes
from robodesc.validation.corpora import all_robots


@contextmanager
def numpy_only() -> Iterator[None]:
    native = usd_meshio._meshweld
    usd_meshio._meshweld = None
    try:
        yield
    finally:
        usd_meshio._meshweld = native


def both_welds(tri: NDArray[np.float64]) -> None:
    got = usd_meshio._weld(tri)
    with numpy_only():
        expected = usd_meshio._weld(tri)
    assert got[0].tobytes() == expected[0].tobytes()
    assert got[1].dtype == expected[1].dtype == np.int32
    np.testing.assert_array_equal(got[1], expected[1])


def both_normals(vertices: NDArray[np.float64], corners: NDArray[np.int32]) -> None:
    got = usd_meshio.face_normals(vertices, corners)
    with numpy_only():
        expected = usd_meshio.face_normals(vertices, corners)
    assert got.dtype == expected.dtype == np.float32
    assert got.shape == expected.shape
    assert got.tobytes() == expected.tobytes()


def test_native_weld_is_built() -> None:
    assert usd_meshio._meshweld is not None, "robodesc._meshweld is not built: pip install -e . compiles it"


@pytest.mark.parametrize("seed", range(6))
def test_random_meshes(seed: int) -> None:
    rng = np.random.default_rng(seed)
    pool = rng.standard_normal((rng.integers(1, 400), 3)) * 10.0 ** rng.integers(-8, 8)
    pool[rng.random(len(pool)) < 0.05] = 0.0
    pool[rng.random(len(pool)) < 0.05] *= -0.0  # -0.0 stays apart from 0.0
    tri = pool[rng.integers(0, len(pool), (rng.integers(1, 3000), 3))]
    both_welds(tri)
    points, indices = usd_meshio._weld(tri)
    both_normals(points, indices)
    corners = rng.integers(0, len(pool), 3 * 500)
    got = usd_meshio._weld_indexed(pool, corners)
    with numpy_only():
        expected = usd_meshio._weld_indexed(pool, corners)
    assert got[0].tobytes() == expected[0].tobytes()
    np.testing.assert_array_equal(got[1], expected[1])


def test_edge_cases() -> None:
    nan = float("nan")
    tri = np.array(
        [
            [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
            [[0, 0, 0], [0, 0, 0], [0, 0, 0]],  # degenerate: normal 0
            [[-0.0, 0, 0], [1, 0, 0], [1, 0, 0]],
            [[nan, 0, 0], [nan, 0, 0], [0, 0, 1]],  # the same NaN bits weld
            [[1e308, 0, 0], [-1e308, 0, 0], [0, 1e308, 0]],  # overflowing cross product
            [[5e-324, 0, 0], [0, 5e-324, 0], [0, 0, 5e-324]],  # subnormal
        ],
        dtype=np.float64,
    )
    both_welds(tri)
    points, indices = usd_meshio._weld(tri)
    both_normals(points, indices)
    both_welds(np.zeros((0, 3, 3)))


def test_bad_input_is_an_error_not_a_crash() -> None:
    weld = usd_meshio._meshweld
    assert weld is not None
    with pytest.raises(ValueError, match="refers to row"):
        weld.weld(np.zeros((2, 3)), np.array([0, 2], dtype=np.int64))
    with pytest.raises(ValueError, match="out of range"):
        weld.face_normals(np.zeros((2, 3)), np.array([0, 1, 2], dtype=np.int32))
    with pytest.raises((BufferError, ValueError), match="contiguous"):
        weld.weld(np.zeros((4, 3))[::2], None)  # not contiguous


@pytest.mark.slow
def test_corpus_stl_and_collada() -> None:
    stl = corpus_files(".stl")
    dae = corpus_files(".dae")
    if not stl and not dae:
        pytest.skip("no mesh corpus installed")
    for path in stl:
        tri = usd_meshio._read_stl(path)
        both_welds(tri)
        points, indices = usd_meshio._weld(tri)
        both_normals(points, indices)
    for path in dae:
        try:
            points, corners = read_collada_indexed(path)
        except usd_meshio.MeshReadError:
            continue
        got = usd_meshio._weld_indexed(points, corners)
        with numpy_only():
            expected = usd_meshio._weld_indexed(points, corners)
        assert got[0].tobytes() == expected[0].tobytes(), path
        np.testing.assert_array_equal(got[1], expected[1])
        both_normals(*got)


def test_same_usd_with_and_without_the_extensions(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # A whole robot with COLLADA visuals and STL colliders, written both ways: the same bytes.
    found = [r for r in all_robots(str(SHARED_CORPUS)) if r.name == "ur_description/urdf/ur10_robot"]
    if not found:
        pytest.skip("example-robot-data is not installed")
    entry = found[0]

    def convert(name: str) -> bytes:
        robot = load_path(entry.path, LoadOptions(package_paths=entry.packages)).robot
        run_passes(robot, options=PassOptions(sanitize_names=True, unique_materials=True))
        out = tmp_path / name / "ur10.usda"
        emit_usd(robot, str(out), UsdOptions(layered=True))
        return (out.parent / "Payload" / "Geometry.usdc").read_bytes()

    native = convert("native")
    monkeypatch.setattr(usd_meshio, "_meshweld", None)
    monkeypatch.setattr(number_text, "_numtext", None)
    assert convert("numpy") == native
