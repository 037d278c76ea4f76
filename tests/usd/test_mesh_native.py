"""The C mesh code (``robodesc.meshes._weld``, ``robodesc.meshes._numtext.obj``) against robodesc's numpy
code, bit for bit.

The numpy code is the fallback when the extensions are not built, and the path for COLLADA and the
formats trimesh reads; it was itself checked against np.unique, np.cross and the line-by-line OBJ
reader (test_mesh_readers.py). Here both run on the same input and must agree exactly: the weld and
normals on hand-made edge cases, random meshes and every STL and COLLADA file of the corpora, and
whole meshes (binary STL, OBJ and COLLADA read, welded and finished without numpy) on every STL,
OBJ and COLLADA file.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest
from numpy.typing import NDArray
from test_mesh_readers import SHARED_CORPUS, corpus_files

from robodesc.emit.usd import UsdOptions, emit_usd
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions
from robodesc.meshes import buffers as mesh_buffers
from robodesc.meshes import collada as mesh_collada
from robodesc.meshes import data as mesh_data
from robodesc.meshes import readers as usd_meshio
from robodesc.meshes import text_numbers as number_text
from robodesc.meshes.collada import read_collada_indexed
from robodesc.passes.options import PassOptions
from robodesc.passes.pipeline import run_passes
from robodesc.validation.corpora import all_robots

DATA = Path(__file__).parent / "data"


@contextmanager
def numpy_only() -> Iterator[None]:
    modules = (usd_meshio, mesh_data, mesh_collada, mesh_buffers)
    native = [m._cweld for m in modules]
    for m in modules:
        m._cweld = None  # type: ignore[assignment]
    try:
        yield
    finally:
        for m, weld in zip(modules, native, strict=True):
            m._cweld = weld


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
    assert usd_meshio._cweld is not None, "robodesc.meshes._weld is not built: pip install -e . compiles it"
    assert mesh_data._cweld is not None and mesh_data._numtext is not None


def assert_same_mesh(got: mesh_data.MeshData, expected: mesh_data.MeshData, what: str) -> None:
    for name in ("points", "face_vertex_counts", "face_vertex_indices", "normals"):
        a, b = getattr(got, name), getattr(expected, name)
        assert a.typecode == b.typecode and a.tobytes() == b.tobytes(), (what, name)
    assert np.array_equal(got.extent, expected.extent, equal_nan=True), what
    assert [math.copysign(1, v) for v in np.ravel(got.extent)] == [
        math.copysign(1, v) for v in np.ravel(expected.extent)
    ]


def both_builds(path: str, scale: tuple[float, float, float] | None) -> None:
    """The numpy-free build of a mesh file against the numpy reader and finish."""
    try:
        got = mesh_data.build_mesh(path, scale)
    except mesh_data.MeshReadError as exc:
        with pytest.raises(mesh_data.MeshReadError) as expected_error, numpy_only():
            usd_meshio.build_mesh_numpy(path, scale)
        assert str(exc) == str(expected_error.value), path
        return
    with numpy_only():
        expected = usd_meshio.build_mesh_numpy(path, scale)
    assert_same_mesh(got, expected, f"{path} scale {scale}")


@pytest.mark.parametrize("scale", [None, (0.001, 0.001, 0.001), (1.0, -2.0, 0.5)])
def test_whole_meshes_of_the_test_data(scale: tuple[float, float, float] | None) -> None:
    for name in ("wedge.stl", "wedge.obj"):
        both_builds(str(DATA / name), scale)


def test_obj_edge_cases(tmp_path: Path) -> None:
    cases = {
        "quad_and_pentagon": "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\nf 1/1 2//2 3/3/3 4 5\n",
        "extra_coords_and_tabs": "v\t9 9 9\nv 0 0 0 1 0.5 0.5\nv 1 0 0\nv  0\t1 0 \nf 1 2 3\n",
        "crlf": "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n",
        "relative": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n",
        "out_of_range": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
        "short_vertex": "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "bad_number": "v 0 0 x\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "bad_index": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 /3\n",
        "two_corners": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 1 2 3\n",
        "no_faces": "v 0 0 0\n",
        "non_ascii_comment": "# caf\u00e9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3",
        "nan_and_exponents": "v nan 0 0\nv 1e0 -0 0\nv 0 1.5E-3 +2\nf 1 2 3\n",
    }
    for name, text in cases.items():
        path = tmp_path / f"{name}.obj"
        path.write_bytes(text.encode())
        both_builds(str(path), None)
        both_builds(str(path), (2.0, 2.0, -1.0))
    # The C reader takes the plain files and leaves the others to the line reader.
    native = {name for name, text in cases.items() if mesh_data._numtext.obj(text.replace("\r", "").encode())}
    assert native == {
        "quad_and_pentagon",
        "extra_coords_and_tabs",
        "crlf",
        "two_corners",
        "no_faces",
        "non_ascii_comment",
        "nan_and_exponents",
    }


def test_stl_edge_cases(tmp_path: Path) -> None:
    good = (DATA / "wedge.stl").read_bytes()
    cases = {
        "truncated": good[:-7],
        "empty_binary": bytes(80) + (0).to_bytes(4, "little"),
        "too_short": b"solid",
        "ascii": b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n",
        "ascii_exponents": b"solid t\nfacet normal 0 0 1\nouter loop\nVERTEX -0 1e-3 2.5E+1\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
        b"facet normal 0 0 1\nouter loop\nvertex -0 0.001 25\nvertex 0 1 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid\n",
        "ascii_bad_number": b"solid t\nouter loop\nvertex 0 0 x\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendsolid\n",
        "ascii_incomplete": b"solid t\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendsolid\n",
    }
    for name, data in cases.items():
        path = tmp_path / f"{name}.stl"
        path.write_bytes(data)
        both_builds(str(path), None)


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
    weld = usd_meshio._cweld
    assert weld is not None
    with pytest.raises(ValueError, match="refers to row"):
        weld.weld(np.zeros((2, 3)), np.array([0, 2], dtype=np.int64))
    with pytest.raises(ValueError, match="out of range"):
        weld.face_normals(np.zeros((2, 3)), np.array([0, 1, 2], dtype=np.int32))
    with pytest.raises((BufferError, ValueError), match="contiguous"):
        weld.weld(np.zeros((4, 3))[::2], None)  # not contiguous


@pytest.mark.slow
def test_corpus_whole_meshes() -> None:
    files = corpus_files(".stl") + corpus_files(".obj") + corpus_files(".dae")
    if not files:
        pytest.skip("no mesh corpus installed")
    for path in files:
        both_builds(path, None)
    for path in files[::10]:
        both_builds(path, (0.5, -1.0, 2.0))


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
            flat, indexed = read_collada_indexed(path)
        except usd_meshio.MeshReadError:
            continue
        points = np.frombuffer(flat, dtype=np.float64).reshape(-1, 3)
        corners = np.frombuffer(indexed, dtype=np.int64)
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
    monkeypatch.setattr(usd_meshio, "_cweld", None)
    monkeypatch.setattr(mesh_data, "_cweld", None)
    monkeypatch.setattr(mesh_collada, "_cweld", None)
    monkeypatch.setattr(mesh_buffers, "_cweld", None)
    monkeypatch.setattr(number_text, "_numtext", None)
    assert convert("numpy") == native
