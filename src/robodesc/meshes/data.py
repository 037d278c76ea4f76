"""Mesh files as the arrays a UsdGeom.Mesh needs, without numpy on the common path.

numpy's import costs about 0.1 s, more than converting a small robot's meshes. So STL,
plain OBJ and COLLADA (:mod:`robodesc.meshes.collada`) files go through the C extensions from
the file to the finished arrays (welded points, triangles, face normals, extent), and the arrays
stay Python ``array.array`` buffers, which the .usdc writer copies to the file as they are.
Everything else (broken STL, OBJ that needs the line reader, trimesh's formats, an install without
a C compiler) goes through
:mod:`robodesc.meshes.readers`'s numpy readers, imported on first use. Both give the same bits
(tests/usd/test_mesh_native.py).

Results are cached per (file, scale) for one emitter run: visuals and colliders often share a file.
A process that compiles many robots (a ``robodesc batch`` worker) can also keep them across runs
(:func:`keep_across_runs`): a robot family, or the variants of a sweep, read the same meshes.
"""

from __future__ import annotations

import os
from collections import OrderedDict

from robodesc.ir.geometry import Vec3
from robodesc.meshes.buffers import MeshData, MeshReadError, finish, obj_text

try:
    from robodesc.meshes import _numtext
    from robodesc.meshes import _weld as _cweld
except ImportError:  # installed without a C compiler: numpy does it all, more slowly
    _cweld = None  # type: ignore[assignment]
    _numtext = None  # type: ignore[assignment]


def build_mesh(path: str, scale: Vec3 | None) -> MeshData:
    if not os.path.isfile(path):
        raise MeshReadError("file does not exist")
    lower = path.lower()
    if _cweld is not None and lower.endswith(".dae"):
        from robodesc.meshes.collada import read_collada_indexed

        points, corners = read_collada_indexed(path)
        welded, indices = _cweld.weld_take(points, corners)
        return finish(welded, indices, scale)
    if _cweld is not None and (lower.endswith(".stl") or lower.endswith(".obj")):
        with open(path, "rb") as handle:
            data = handle.read()
        if lower.endswith(".stl"):
            found = _cweld.stl(data)  # None for ASCII or a broken file
            if found is None and data.lstrip()[:5].lower() == b"solid":
                found = _ascii_stl(data)
        else:
            text = obj_text(data)
            found = None if text is None else _numtext.obj(text)  # None when the line reader must decide
        if found is not None:
            return finish(found[0], found[1], scale)
    from robodesc.meshes.readers import build_mesh_numpy

    return build_mesh_numpy(path, scale)


def _ascii_stl(data: bytes) -> tuple[bytearray, bytearray] | None:
    """An ASCII STL's welded points and triangles: the three numbers after each ``vertex``, parsed
    as usd_meshio's numpy reader parses them; None when that reader must report a broken file."""
    tokens = data.lower().split()
    at = [i for i, token in enumerate(tokens) if token == b"vertex"]
    if not at or len(at) % 3 or at[-1] + 3 >= len(tokens):
        return None
    try:
        values = _numtext.parse(b" ".join(b" ".join(tokens[i + 1 : i + 4]) for i in at), False)
    except ValueError:
        return None
    return _cweld.weld_take(values, None)


def _nbytes(data: MeshData | MeshReadError) -> int:
    if isinstance(data, MeshReadError):
        return 256
    arrays = (data.points, data.face_vertex_counts, data.face_vertex_indices, data.normals, data.uv)
    return 256 + sum(a.itemsize * len(a) for a in arrays if a is not None)


class _SharedStore:
    """Meshes kept across emitter runs, least recently used out first, up to a size in bytes.

    A key names the file's identity, size and modification time besides its path and scale: a file
    rewritten between two robots is read again. MeshData is frozen and its arrays are only ever read
    (the writers copy them out), so runs can share one object.
    """

    def __init__(self, budget: int) -> None:
        self.budget = budget
        self.size = 0
        self._items: OrderedDict[tuple[object, ...], MeshData | MeshReadError] = OrderedDict()

    def get(self, key: tuple[object, ...]) -> MeshData | MeshReadError | None:
        hit = self._items.get(key)
        if hit is not None:
            self._items.move_to_end(key)
        return hit

    def put(self, key: tuple[object, ...], data: MeshData | MeshReadError) -> None:
        size = _nbytes(data)
        if size > self.budget:
            return
        self._items[key] = data
        self.size += size
        while self.size > self.budget:
            _, old = self._items.popitem(last=False)
            self.size -= _nbytes(old)


_shared: _SharedStore | None = None


def keep_across_runs(budget_bytes: int) -> None:
    """Keep up to ``budget_bytes`` of meshes in this process across emitter runs (0: stop keeping)."""
    global _shared
    _shared = _SharedStore(budget_bytes) if budget_bytes > 0 else None


def keeping() -> bool:
    return _shared is not None


def _build(path: str, scale: Vec3 | None) -> MeshData | MeshReadError:
    try:
        return build_mesh(path, scale)
    except MeshReadError as exc:
        return exc
    except (OSError, ValueError, IndexError) as exc:
        return MeshReadError(f"{type(exc).__name__}: {exc}")


def _shared_get(path: str, scale: Vec3 | None) -> MeshData | MeshReadError:
    assert _shared is not None
    try:
        info = os.stat(path)
    except OSError:
        return _build(path, scale)  # the reader names what is wrong with the path
    key = (path, scale, info.st_dev, info.st_ino, info.st_size, info.st_mtime_ns)
    hit = _shared.get(key)
    if hit is None:
        hit = _build(path, scale)
        _shared.put(key, hit)
    return hit


class MeshCache:
    def __init__(self) -> None:
        self._data: dict[tuple[str, Vec3 | None], MeshData | MeshReadError] = {}

    def get(self, path: str, scale: Vec3 | None) -> MeshData:
        key = (path, scale)
        hit = self._data.get(key)
        if hit is None:
            hit = _build(path, scale) if _shared is None else _shared_get(path, scale)
            self._data[key] = hit
        if isinstance(hit, MeshReadError):
            raise MeshReadError(str(hit))  # a new one: raising the kept one again would grow its traceback
        return hit
