"""Reading mesh files into the arrays a UsdGeom.Mesh needs.

STL (binary and ASCII) and OBJ are read with numpy directly and COLLADA with pycollada: importing trimesh alone costs
over a second, more than converting a whole robot. Other formats go through trimesh, imported on
first use. Texture coordinates are only read through trimesh (not for STL, OBJ, DAE yet). Results are cached per (file, scale) for one emitter run,
because visuals and colliders often share a file.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from robodesc.ir.geometry import Vec3

F32 = NDArray[np.float32]
I32 = NDArray[np.int32]


@dataclass(slots=True, frozen=True)
class MeshData:
    points: F32  # (n, 3), scale applied
    face_vertex_counts: I32  # (m,)
    face_vertex_indices: I32  # (sum counts,)
    normals: F32  # (sum counts, 3): faceVarying, one per face corner
    extent: F32  # (2, 3)
    uv: F32 | None = None  # (n, 2) per vertex, when the file has texture coordinates


class MeshReadError(Exception):
    pass


_STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("v", "<f4", (3, 3)), ("attr", "<u2")])


def read_triangles(path: str) -> tuple[NDArray[np.float64], I32, NDArray[np.float64] | None]:
    """(vertices, triangle indices, per-vertex uv or None) of a mesh file, in file units."""
    lower = path.lower()
    if lower.endswith(".stl"):
        return (*_weld(_read_stl(path)), None)
    elif lower.endswith(".dae"):
        return (*_weld(_read_collada(path)), None)
    elif lower.endswith(".obj"):
        return (*_read_obj(path), None)
    return _read_trimesh(path)


def _read_obj(path: str) -> tuple[NDArray[np.float64], I32]:
    """Vertices and fan-triangulated faces of every object in a Wavefront OBJ file."""
    with open(path, "rb") as handle:
        text = handle.read().decode("utf-8", "replace")
    coords: list[list[str]] = []
    tris: list[int] = []
    for line in text.splitlines():
        if line.startswith("v "):
            coords.append(line.split()[1:4])
        elif line.startswith("f "):
            count = len(coords)
            try:
                idx = [int(tok.split("/", 1)[0]) for tok in line.split()[1:]]
            except ValueError:
                raise MeshReadError(f"bad face line {line.strip()!r}") from None
            idx = [i - 1 if i > 0 else count + i for i in idx]
            for k in range(1, len(idx) - 1):
                tris.extend((idx[0], idx[k], idx[k + 1]))
    try:
        vertices = np.array(coords, dtype=np.float64).reshape(-1, 3)
    except ValueError:
        raise MeshReadError("bad vertex line") from None
    indices = np.array(tris, dtype=np.int32)
    if len(indices) and (indices.min() < 0 or indices.max() >= len(vertices)):
        raise MeshReadError("a face refers to a vertex that does not exist")
    return vertices, indices


def _read_stl(path: str) -> NDArray[np.float64]:
    """(m, 3, 3) triangles of a binary or ASCII STL."""
    with open(path, "rb") as handle:
        data = handle.read()
    if len(data) < 84:
        raise MeshReadError("file is too short to be an STL mesh")
    count = int(np.frombuffer(data, dtype="<u4", count=1, offset=80)[0])
    if 84 + count * 50 != len(data):
        if data.lstrip()[:5].lower() == b"solid":
            return _read_ascii_stl(data)
        raise MeshReadError(f"binary STL says {count} triangles but has {len(data)} bytes")
    records = np.frombuffer(data, dtype=_STL_RECORD, count=count, offset=84)
    return records["v"].astype(np.float64)


def _read_ascii_stl(data: bytes) -> NDArray[np.float64]:
    tokens = np.array(data.lower().split())
    at = np.nonzero(tokens == b"vertex")[0]
    if len(at) == 0 or len(at) % 3 or at[-1] + 3 >= len(tokens):
        raise MeshReadError("ASCII STL without complete triangles")
    try:
        coords = tokens[at[:, None] + np.arange(1, 4)].astype(np.float64)
    except ValueError:
        raise MeshReadError("ASCII STL has a bad vertex line") from None
    out: NDArray[np.float64] = coords.reshape(-1, 3, 3)
    return out


def _read_collada(path: str) -> NDArray[np.float64]:
    """(m, 3, 3) triangles of every geometry instance in a COLLADA scene, node transforms applied
    and scaled by the file's ``<unit meter>`` (as ROS's loaders do; trimesh ignores it)."""
    import collada  # type: ignore[import-untyped]

    ignore = [
        collada.common.DaeIncompleteError,
        collada.common.DaeBrokenRefError,
        collada.common.DaeMalformedError,
        collada.common.DaeUnsupportedError,
    ]
    try:
        dae = collada.Collada(path, ignore=ignore)
    except Exception as exc:  # pycollada raises many types for bad files
        raise MeshReadError(f"{type(exc).__name__}: {exc}") from None
    parts: list[NDArray[np.float64]] = []
    if dae.scene is not None:
        for geometry in dae.scene.objects("geometry"):
            for prim in geometry.primitives():
                if isinstance(prim, collada.polylist.BoundPolylist | collada.polygons.BoundPolygons):
                    prim = prim.triangleset()
                if not isinstance(prim, collada.triangleset.BoundTriangleSet) or prim.vertex is None:
                    continue
                if len(prim.vertex_index) == 0:
                    continue
                parts.append(np.asarray(prim.vertex, dtype=np.float64)[np.asarray(prim.vertex_index)])
    if not parts:
        raise MeshReadError("COLLADA file has no triangles")
    tri = np.concatenate(parts).reshape(-1, 3, 3)
    unit = dae.assetInfo.unitmeter
    if unit is not None and unit > 0 and unit != 1.0:
        tri = tri * float(unit)
    return tri


def _weld(tri: NDArray[np.float64]) -> tuple[NDArray[np.float64], I32]:
    """Merge identical corners so points are shared (STL stores each corner on its own)."""
    flat = np.ascontiguousarray(tri.reshape(-1, 3))
    if len(flat) == 0:
        return flat, np.zeros(0, dtype=np.int32)
    keys = flat.view(np.dtype((np.void, flat.dtype.itemsize * 3))).ravel()
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    # np.unique sorts by bytes; renumber by first appearance so the output follows the file order.
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    return flat[first[order]], rank[inverse.ravel()].astype(np.int32)


def _read_trimesh(path: str) -> tuple[NDArray[np.float64], I32, NDArray[np.float64] | None]:
    import trimesh

    try:
        loaded = trimesh.load(path, force="mesh", process=False)
    except Exception as exc:  # trimesh raises many types for bad files
        raise MeshReadError(f"{type(exc).__name__}: {exc}") from None
    if not isinstance(loaded, trimesh.Trimesh):
        raise MeshReadError("file holds no triangle mesh")
    vertices = np.asarray(loaded.vertices, dtype=np.float64)
    faces = np.asarray(loaded.faces, dtype=np.int32).reshape(-1)
    uv = None
    visual = getattr(loaded, "visual", None)
    raw_uv = getattr(visual, "uv", None)
    if raw_uv is not None and len(raw_uv) == len(vertices):
        uv = np.asarray(raw_uv, dtype=np.float64)
    return vertices, faces, uv


def build_mesh(path: str, scale: Vec3 | None) -> MeshData:
    if not os.path.isfile(path):
        raise MeshReadError("file does not exist")
    vertices, indices, uv = read_triangles(path)
    if len(indices) == 0 or len(vertices) == 0:
        raise MeshReadError("mesh has no triangles")
    tri = indices.reshape(-1, 3)
    if scale is not None:
        s = np.asarray(scale, dtype=np.float64)
        vertices = vertices * s
        if float(np.prod(s)) < 0:
            # A mirroring scale turns the faces inside out: flip the winding back.
            tri = tri[:, ::-1]
    corners = vertices[tri]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.divide(normals, length, out=np.zeros_like(normals), where=length > 0)
    normals += 0.0  # no negative zeros in the text output
    points = vertices.astype(np.float32)
    extent = np.stack([points.min(axis=0), points.max(axis=0)])
    return MeshData(
        points=points,
        face_vertex_counts=np.full(len(tri), 3, dtype=np.int32),
        face_vertex_indices=np.ascontiguousarray(tri.reshape(-1), dtype=np.int32),
        normals=np.repeat(normals, 3, axis=0).astype(np.float32),
        extent=extent,
        uv=uv.astype(np.float32) if uv is not None else None,
    )


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
