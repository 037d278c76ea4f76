"""Meshes kept across emitter runs (``robodesc batch`` workers): a hit is the same data, a file
rewritten between runs is read again, the store keeps to its size, and errors stay errors."""

from __future__ import annotations

import os
import struct
from collections.abc import Iterator
from pathlib import Path

import pytest

from robodesc.meshes import data
from robodesc.meshes.buffers import MeshReadError
from robodesc.meshes.data import MeshCache, keep_across_runs


def _stl(path: Path, size: float, triangles: int = 1) -> None:
    body = b""
    for i in range(triangles):
        z = float(i)
        body += struct.pack("<12fH", 0, 0, 1, 0, 0, z, size, 0, z, 0, size, z, 0)
    path.write_bytes(bytes(80) + struct.pack("<I", triangles) + body)


@pytest.fixture
def keeping() -> Iterator[None]:
    keep_across_runs(1 << 20)
    yield
    keep_across_runs(0)


def test_runs_share_a_mesh(tmp_path: Path, keeping: None) -> None:
    path = tmp_path / "m.stl"
    _stl(path, 1.0)
    first = MeshCache().get(str(path), None)
    assert MeshCache().get(str(path), None) is first  # a second run: not read again
    assert MeshCache().get(str(path), (2.0, 2.0, 2.0)) is not first  # another scale is another mesh


def test_a_rewritten_file_is_read_again(tmp_path: Path, keeping: None) -> None:
    path = tmp_path / "m.stl"
    _stl(path, 1.0)
    first = MeshCache().get(str(path), None)
    _stl(path, 3.0, triangles=2)
    os.utime(path, ns=(1, 1))  # a new time as well, whatever the file system's clock resolution
    second = MeshCache().get(str(path), None)
    assert second is not first and second.extent[1][0] == pytest.approx(3.0)


def test_the_store_keeps_to_its_budget(tmp_path: Path) -> None:
    keep_across_runs(3000)
    try:
        paths = []
        for i in range(5):
            paths.append(tmp_path / f"m{i}.stl")
            _stl(paths[-1], 1.0 + i, triangles=10)  # ~ 600 bytes of arrays each
        for path in paths:
            MeshCache().get(str(path), None)
        store = data._shared
        assert store is not None and store.size <= 3000
        assert MeshCache().get(str(paths[-1]), None) is MeshCache().get(str(paths[-1]), None)
    finally:
        keep_across_runs(0)


def test_errors_are_kept_and_raised_afresh(tmp_path: Path, keeping: None) -> None:
    path = tmp_path / "broken.stl"
    path.write_bytes(b"not a mesh at all")
    with pytest.raises(MeshReadError) as first:
        MeshCache().get(str(path), None)
    with pytest.raises(MeshReadError) as second:
        MeshCache().get(str(path), None)
    assert str(first.value) == str(second.value) and first.value is not second.value


def test_off_by_default(tmp_path: Path) -> None:
    assert not data.keeping()
    path = tmp_path / "m.stl"
    _stl(path, 1.0)
    assert MeshCache().get(str(path), None) is not MeshCache().get(str(path), None)
