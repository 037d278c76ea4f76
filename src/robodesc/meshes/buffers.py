"""The arrays a UsdGeom.Mesh needs, and the last step that makes them: every mesh reader ends here.

Kept apart from the readers so that each reader (:mod:`.data`'s C path, :mod:`.readers`,
:mod:`.collada`, :mod:`.trimesh_io`) can name the result and the error without importing the others.
"""

from __future__ import annotations

from array import array
from collections.abc import Sequence
from dataclasses import dataclass

from robodesc.ir.geometry import Vec3

try:
    from robodesc.meshes import _weld as _cweld
except ImportError:  # installed without a C compiler: numpy does it all, more slowly
    _cweld = None  # type: ignore[assignment]


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


def obj_bytes(points: Sequence[float], indices: Sequence[int], comment: str) -> bytes:
    """A Wavefront OBJ of flat xyz ``points`` and triangle ``indices`` (0-based). ``%.9g`` writes a
    float32 exactly and keeps float64 to float32 precision and more; equal input, equal bytes."""
    lines = [b"# %s\n" % comment.encode()]
    for i in range(0, len(points), 3):
        lines.append(b"v %.9g %.9g %.9g\n" % (points[i], points[i + 1], points[i + 2]))
    for i in range(0, len(indices), 3):
        lines.append(b"f %d %d %d\n" % (indices[i] + 1, indices[i + 1] + 1, indices[i + 2] + 1))
    return b"".join(lines)


# A mesh thinner than this (relative to its largest extent) has no convex hull: MuJoCo and PhysX
# need one for every mesh collider, so the targets put a thin box over its extent instead.
FLAT = 1e-9


def flat_box(data: MeshData, thickness: float) -> tuple[Vec3, Vec3] | None:
    """(size, centre in the mesh's frame) of a box of a flat mesh's extent, at least ``thickness``
    across; None for a mesh with volume (or no extent at all)."""
    lo, hi = data.extent
    size = [h - low for low, h in zip(lo, hi, strict=True)]
    if max(size) <= 0 or min(size) > FLAT * max(size):
        return None
    full = tuple(max(s, thickness) for s in size)
    centre = tuple((low + h) / 2 for low, h in zip(lo, hi, strict=True))
    return (full[0], full[1], full[2]), (centre[0], centre[1], centre[2])


def finish(vertices: object, triangles: object, scale: Vec3 | None, uv: array[float] | None = None) -> MeshData:
    """:class:`MeshData` of float64 points and int32 triangles (C-contiguous buffers) through the C
    extension: scaled, the winding reversed by a mirroring scale, normals, float32 points, extent."""
    if not memoryview(triangles).nbytes or not memoryview(vertices).nbytes:  # type: ignore[arg-type]
        raise MeshReadError("mesh has no triangles")
    # A mirroring scale turns the faces inside out: the winding is flipped back.
    flip = scale is not None and scale[0] * scale[1] * scale[2] < 0
    try:
        points, indices, normals, box = _cweld.finish(vertices, triangles, scale, flip)
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
