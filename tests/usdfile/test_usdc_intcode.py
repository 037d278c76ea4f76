"""Compressed int arrays in .usdc (mesh indices): the C coder, the numpy coder and the Python reference
give the same bytes, and usd-core reads every array back exactly, compressed or not."""

from __future__ import annotations

import gc
import struct
from array import array
from pathlib import Path

import numpy as np
import pytest
from pxr import Sdf

from robodesc.usdfile import usdc_encoding
from robodesc.usdfile.spec import Attribute, Layer
from robodesc.usdfile.usdc import usdc_bytes
from robodesc.usdfile.usdc_encoding import _encode_numpy, encode_int32_bytes, encode_ints


def _lists() -> list[list[int]]:
    rng = np.random.default_rng(11)
    edges = [127, 128, -128, -129, 32767, 32768, -32768, -32769, 2**31 - 1, -(2**31), 0, 1, -1]
    mesh_like = (np.arange(90_000) // 3 + np.tile([0, 1, 2], 30_000)).tolist()  # > the direct table's threshold
    return [
        [],
        [7],
        [3] * 15,
        [3] * 16,
        rng.integers(-(2**31), 2**31, 5000).tolist(),
        rng.integers(0, 300, 5000).tolist(),
        rng.choice(edges, 20_000).tolist(),
        rng.choice([0, 40_000, 80_000, 120_000], 70_000).tolist(),  # every delta far from zero
        mesh_like,
        rng.permutation(100_000).tolist(),
    ]


@pytest.mark.parametrize("values", _lists(), ids=lambda v: f"{len(v)}")
def test_c_numpy_and_python_coders_agree(values: list[int]) -> None:
    data = struct.pack(f"<{len(values)}i", *values)
    want = encode_ints(values)
    assert encode_int32_bytes(data) == want
    if values:
        assert _encode_numpy(data) == want


def test_without_the_c_coder_the_file_is_the_same(monkeypatch: pytest.MonkeyPatch) -> None:
    layer = _mesh_layer()
    with_c = usdc_bytes(layer)
    monkeypatch.setattr(usdc_encoding, "_intcode", None)
    assert usdc_bytes(layer) == with_c


def _mesh_layer() -> Layer:
    rng = np.random.default_rng(3)
    layer = Layer()
    prim = layer.prim("/Mesh", "Mesh")
    prim.attr("faceVertexCounts", "int[]", array("i", [3]) * 40_000)
    prim.attr("faceVertexIndices", "int[]", array("i", rng.integers(0, 60_000, 120_000).tolist()))
    prim.attr("short", "int[]", [5, -7, 2**31 - 1])  # below 16: stored as is, as Sdf does
    prim.attr("sixteen", "int[]", list(range(-8, 8)))
    prim.attr("extremes", "int[]", [2**31 - 1, -(2**31)] * 20)
    return layer


def test_usd_core_reads_compressed_int_arrays(tmp_path: Path) -> None:
    layer = _mesh_layer()
    path = tmp_path / "mesh.usdc"
    path.write_bytes(usdc_bytes(layer))
    sdf = Sdf.Layer.FindOrOpen(str(path))
    assert sdf is not None
    for name, attr in layer.root.children["Mesh"].properties.items():
        got = np.asarray(sdf.GetAttributeAtPath(f"/Mesh.{name}").default, dtype=np.int32)
        assert isinstance(attr, Attribute)
        assert got.tolist() == list(attr.value), name
    # Compressed: 40,000 counts of 3 are a few kilobytes, not 160.
    raw_ints = (40_000 + 120_000) * 4
    assert path.stat().st_size < raw_ints * 0.6


def test_one_array_object_on_two_prims_is_stored_once(tmp_path: Path) -> None:
    indices = array("i", np.random.default_rng(5).integers(0, 50_000, 90_000).tolist())
    one, two = Layer(), Layer()
    one.prim("/A", "Mesh").attr("faceVertexIndices", "int[]", indices)
    for name in ("A", "B"):  # a visual and a collider of one mesh file share its arrays
        two.prim(f"/{name}", "Mesh").attr("faceVertexIndices", "int[]", indices)
    assert len(usdc_bytes(two)) - len(usdc_bytes(one)) < 200
    path = tmp_path / "two.usdc"
    path.write_bytes(usdc_bytes(two))
    sdf = Sdf.Layer.FindOrOpen(str(path))
    for name in ("A", "B"):
        got = np.asarray(sdf.GetAttributeAtPath(f"/{name}.faceVertexIndices").default, dtype=np.int32)
        assert got.tobytes() == indices.tobytes()


def test_kept_arrays_are_packed_once_and_forgotten_with_them(monkeypatch: pytest.MonkeyPatch) -> None:
    from robodesc.usdfile import usdc

    indices = array("i", np.random.default_rng(9).integers(0, 5000, 3000).tolist())
    layer = Layer()
    layer.prim("/A", "Mesh").attr("faceVertexIndices", "int[]", indices)
    plain = usdc_bytes(layer)
    usdc.keep_packed(indices)
    assert usdc_bytes(layer) == plain  # packs it and keeps the bytes
    calls: list[bytes] = []

    def counted(body: bytes) -> bytes:
        calls.append(body)
        return b""

    monkeypatch.setattr(usdc, "compressed_int32_bytes", counted)
    assert usdc_bytes(layer) == plain  # a later layer reuses them: nothing coded again
    assert not calls
    key = id(indices)
    del layer, indices
    gc.collect()  # a layer's prims refer to their parents
    assert key not in usdc._kept  # gone with the array


def test_chunks_view_float_arrays_and_join_to_the_file(tmp_path: Path) -> None:
    from robodesc._files import write_atomic
    from robodesc.usdfile.usdc import usdc_chunks

    points = array("f", np.random.default_rng(2).standard_normal(30_000).astype(np.float32).tobytes())
    layer = Layer()
    layer.prim("/Mesh", "Mesh").attr("points", "point3f[]", points)
    chunks = usdc_chunks(layer)
    assert any(isinstance(c, memoryview) and c.obj is points for c in chunks)  # not a copy
    path = tmp_path / "m.usdc"
    write_atomic(str(path), chunks)
    assert path.read_bytes() == usdc_bytes(layer)
    sdf = Sdf.Layer.FindOrOpen(str(path))  # held: a spec does not keep its layer alive
    got = np.asarray(sdf.GetAttributeAtPath("/Mesh.points").default, dtype=np.float32)
    assert got.tobytes() == points.tobytes()
