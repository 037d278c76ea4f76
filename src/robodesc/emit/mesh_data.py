"""Mesh files as the arrays a UsdGeom.Mesh needs, without numpy on the common path.

numpy's import costs about 0.1 s, more than converting a small robot's meshes. So STL,
plain OBJ and COLLADA (:mod:`robodesc.emit.mesh_collada`) files go through the C extensions from
the file to the finished arrays (welded points, triangles, face normals, extent), and the arrays
stay Python ``array.array`` buffers, which the .usdc writer copies to the file as they are.
Everything else (broken STL, OBJ that needs the line reader, trimesh's formats, an install without
a C compiler) goes through
:mod:`robodesc.emit.usd_meshio`'s numpy readers, imported on first use. Both give the same bits
(tests/usd/test_mesh_native.py).

Results are cached per (file, scale) for one emitter run: visuals and colliders often share a file.
"""

from __future__ import annotations

import os
from array import array
from dataclasses import dataclass

from robodesc.ir.geometry import Vec3

try:
    from robodesc import _meshweld, _numtext
except ImportError:  # installed without a C compiler: numpy does it all, more slowly
    _meshweld = None  # type: ignore[assignment]
    _numtext = None  # type: ignore[assignment]


class MeshReadError(Exception):
    """A mesh file could not be read."""


@dataclass(slots=True, frozen=True)
class MeshData:
    """Flat native-endian buffers, in the units of the scaled file."""

    points: array[float]  # float32 x, y, z per point
    face_vertex_counts: array[int]  # int32, 3 per triangle
    face_vertex_indices: array[int]  # int32, three per triangle
    normals: array[float]  # float32 x, y, z per triangle: uniform, one per face
    extent: tuple[Vec3, Vec3]  # per-axis minimum and maximum of the (float32) points
    uv: array[float] | None = None  # float32 u, v per point, when the file has texture coordinates


def build_mesh(path: str, scale: Vec3 | None) -> MeshData:
    if not os.path.isfile(path):
        raise MeshReadError("file does not exist")
    lower = path.lower()
    if _meshweld is not None and lower.endswith(".dae"):
        from robodesc.emit.mesh_collada import read_collada_indexed

        points, corners = read_collada_indexed(path)
        welded, indices = _meshweld.weld_take(points, corners)
        return finish(welded, indices, scale)
    if _meshweld is not None and (lower.endswith(".stl") or lower.endswith(".obj")):
        with open(path, "rb") as handle:
            data = handle.read()
        if lower.endswith(".stl"):
            found = _meshweld.stl(data)  # None for ASCII or a broken file
            if found is None and data.lstrip()[:5].lower() == b"solid":
                found = _ascii_stl(data)
        else:
            text = obj_text(data)
            found = None if text is None else _numtext.obj(text)  # None when the line reader must decide
        if found is not None:
            return finish(found[0], found[1], scale)
    from robodesc.emit.usd_meshio import build_mesh_numpy

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
    return _meshweld.weld_take(values, None)


def finish(vertices: object, triangles: object, scale: Vec3 | None, uv: array[float] | None = None) -> MeshData:
    """:class:`MeshData` of float64 points and int32 triangles (C-contiguous buffers) through the C
    extension: scaled, the winding reversed by a mirroring scale, normals, float32 points, extent."""
    if not memoryview(triangles).nbytes or not memoryview(vertices).nbytes:  # type: ignore[arg-type]
        raise MeshReadError("mesh has no triangles")
    # A mirroring scale turns the faces inside out: the winding is flipped back.
    flip = scale is not None and scale[0] * scale[1] * scale[2] < 0
    try:
        points, indices, normals, box = _meshweld.finish(vertices, triangles, scale, flip)
    except ValueError as exc:  # a triangle past the points: a broken file
        raise MeshReadError(str(exc)) from None
    return MeshData(
        points=_floats(points),
        face_vertex_counts=array("i", [3]) * (len(indices) // 12),
        face_vertex_indices=_ints(indices),
        normals=_floats(normals),
        extent=((box[0], box[1], box[2]), (box[3], box[4], box[5])),
        uv=uv,
    )


def _floats(raw: bytearray) -> array[float]:
    out = array("f")
    out.frombytes(raw)
    return out


def _ints(raw: bytearray) -> array[int]:
    out = array("i")
    out.frombytes(raw)
    return out


# Bytes that need no second look: printable ASCII, tab and line breaks; and the non-ASCII ones.
_PLAIN = bytes(range(32, 127)) + b"\t\n\r"
_NON_ASCII = bytes(range(128, 256))
# Line breaks that str.splitlines() knows and bytes.splitlines() does not (besides control bytes).
_UNICODE_BREAKS = ("\x85".encode(), "\u2028".encode(), "\u2029".encode())


def obj_text(data: bytes) -> bytes | None:
    """An OBJ file's bytes with every line break made "\\n", when its lines split the same way for
    str, bytes and the fast readers; None when only the line reader (str.splitlines) can tell."""
    odd = data.translate(None, _PLAIN)
    if odd:
        # Other control bytes split lines or tokens differently for str, bytes and fromstring.
        if odd.translate(None, _NON_ASCII):
            return None
        if any(mark in data for mark in _UNICODE_BREAKS):
            return None
    # The line breaks str.splitlines() sees in such a file: \r\n, \r and \n.
    if b"\r" in data:
        data = data.replace(b"\r\n", b"\n").replace(b"\r", b"\n")
    return data


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
