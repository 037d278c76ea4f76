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
"""

from __future__ import annotations

import os

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


class MeshCache:
    def __init__(self) -> None:
        self._data: dict[tuple[str, Vec3 | None], MeshData | MeshReadError] = {}

    def get(self, path: str, scale: Vec3 | None) -> MeshData:
        key = (path, scale)
        hit = self._data.get(key)
        if hit is None:
            try:
                hit = build_mesh(path, scale)
            except MeshReadError as exc:
                hit = exc
            except (OSError, ValueError, IndexError) as exc:
                hit = MeshReadError(f"{type(exc).__name__}: {exc}")
            self._data[key] = hit
        if isinstance(hit, MeshReadError):
            raise hit
        return hit
