"""Reading mesh files into the arrays a UsdGeom.Mesh needs, with numpy.

:mod:`robodesc.meshes.data` reads STL, plain OBJ and COLLADA without numpy (through the C
extensions) and comes here for the rest: broken STL files (for their error message), OBJ files that
need the line reader, and other formats through trimesh (importing trimesh alone costs over a
second). Without the C extensions every file comes here, and the same arithmetic runs in numpy
(COLLADA's per-point work in :mod:`robodesc.meshes.collada`'s numpy branches). The tests hold
the two paths to the same bits. Texture coordinates are only read through trimesh (not for STL,
OBJ, DAE yet).
"""

from __future__ import annotations

from array import array
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robodesc.ir.geometry import Vec3
from robodesc.meshes.buffers import MeshData, finish, obj_text
from robodesc.meshes.buffers import MeshReadError as MeshReadError
from robodesc.meshes.collada import read_collada_indexed
from robodesc.meshes.text_numbers import parse_floats, parse_ints
from robodesc.meshes.trimesh_io import load_trimesh

try:
    from robodesc.meshes import _weld as _cweld
except ImportError:  # installed without a C compiler: the numpy weld and normals below (same bits, slower)
    _cweld = None  # type: ignore[assignment]

F32 = NDArray[np.float32]
I32 = NDArray[np.int32]


_STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("v", "<f4", (3, 3)), ("attr", "<u2")])


def read_triangles(path: str) -> tuple[NDArray[np.float64], I32, NDArray[np.float64] | None]:
    """(vertices, triangle indices, per-vertex uv or None) of a mesh file, in file units."""
    lower = path.lower()
    if lower.endswith(".stl"):
        return (*_weld(_read_stl(path)), None)
    elif lower.endswith(".dae"):
        points, corners = read_collada_indexed(path)
        grid = np.frombuffer(points, dtype=np.float64).reshape(-1, 3)
        return (*_weld_indexed(grid, np.frombuffer(corners, dtype=np.int64)), None)
    elif lower.endswith(".obj"):
        return (*_read_obj(path), None)
    return _read_trimesh(path)


def _read_obj(path: str) -> tuple[NDArray[np.float64], I32]:
    """Vertices and fan-triangulated faces of every object in a Wavefront OBJ file."""
    with open(path, "rb") as handle:
        data = handle.read()
    fast = _read_obj_fast(data)
    return fast if fast is not None else _read_obj_lines(data)


def _read_obj_lines(data: bytes) -> tuple[NDArray[np.float64], I32]:
    """The reference reader, one line at a time: used for whatever the vectorised reader does not
    take (relative indices, unusual whitespace, bad numbers), so results and messages stay its own."""
    text = data.decode("utf-8", "replace")
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
    _check_obj_indices(indices, len(vertices))
    return vertices, indices


def _check_obj_indices(indices: I32, count: int) -> None:
    if len(indices) and (indices.min() < 0 or indices.max() >= count):
        raise MeshReadError("a face refers to a vertex that does not exist")


def _read_obj_fast(data: bytes) -> tuple[NDArray[np.float64], I32] | None:
    """:func:`_read_obj_lines` with numpy over all ``v``/``f`` lines at once, or None when the file
    needs the line reader: the result is then the same, and so is the error."""
    text = obj_text(data)
    if text is None:
        return None
    lines = _LineIndex.of(text)
    vertices = _obj_vertices(lines.select(b"v"))
    if vertices is None:
        return None
    faces = _obj_faces(lines.select(b"f"))
    if faces is None:
        return None
    indices = faces.reshape(-1).astype(np.int32)
    _check_obj_indices(indices, len(vertices))
    return vertices, indices


@dataclass(slots=True, frozen=True)
class _LineIndex:
    """Where each line of a text starts and ends. Picking lines by keyword with numpy and slicing
    runs of them out is several times faster than splitlines() and a list comprehension."""

    data: bytes
    chars: NDArray[np.uint8]  # the text and two newlines, so every line has two bytes to look at
    starts: NDArray[np.intp]
    ends: NDArray[np.intp]  # exclusive, at the newline

    @staticmethod
    def of(data: bytes) -> _LineIndex:
        chars = np.frombuffer(data + b"\n\n", dtype=np.uint8)
        ends = np.flatnonzero(chars[: len(data)] == 10)
        starts = np.concatenate(([0], ends + 1))
        ends = np.concatenate((ends, [len(data)]))
        return _LineIndex(data, chars, starts, ends)

    def select(self, keyword: bytes) -> tuple[bytes, int]:
        """The lines that start with ``keyword`` and a space (like startswith(b"v ")), joined by
        newlines, and how many there are."""
        picked = (self.chars[self.starts] == keyword[0]) & (self.chars[self.starts + 1] == 32)
        count = int(np.count_nonzero(picked))
        if count == 0:
            return b"", 0
        # Lines of one keyword come in blocks: one slice per block of consecutive lines.
        edges = np.diff(picked.view(np.int8), prepend=np.int8(0), append=np.int8(0))
        firsts = np.flatnonzero(edges == 1)
        lasts = np.flatnonzero(edges == -1) - 1
        blocks = zip(self.starts[firsts].tolist(), self.ends[lasts].tolist(), strict=True)
        return b"\n".join(self.data[begin:end] for begin, end in blocks), count


@dataclass(slots=True, frozen=True)
class _Lines:
    """OBJ lines of one keyword ("v" or "f", then a space), joined by newlines, as bytes."""

    text: NDArray[np.uint8]
    gap: NDArray[np.bool_]  # space, tab or newline
    begins: NDArray[np.bool_]  # the first byte of a token
    starts: NDArray[np.intp]  # the first byte of each line: its keyword

    @staticmethod
    def of(joined: bytes) -> _Lines | None:
        text = np.frombuffer(joined, dtype=np.uint8)
        if np.count_nonzero(text > 126):
            return None  # str.split() also splits at non-ASCII spaces: leave those to the line reader
        gap = (text == 32) | (text == 9) | (text == 10)
        begins = ~gap
        begins[1:] &= gap[:-1]
        starts = np.concatenate(([0], np.flatnonzero(text == 10) + 1))
        return _Lines(text, gap, begins, starts)

    def tokens_per_line(self) -> NDArray[np.intp]:
        bounds = np.searchsorted(np.flatnonzero(self.begins), np.append(self.starts, len(self.text)))
        return np.diff(bounds)

    def without_keywords(self) -> NDArray[np.uint8]:
        text = self.text.copy()
        text[self.starts] = 32
        return text


def _obj_vertices(lines: tuple[bytes, int]) -> NDArray[np.float64] | None:
    text_in, count = lines
    if count == 0:
        return np.zeros((0, 3), dtype=np.float64)
    joined = _Lines.of(text_in)
    if joined is None:
        return None
    counts = joined.tokens_per_line()
    if counts.min() < 4:
        return None  # the line reader reports the short line
    text = joined.without_keywords()
    if counts.max() > 4:
        # Like line.split()[1:4]: drop what follows z (w, vertex colours).
        first_bytes = np.flatnonzero(joined.begins)
        line = np.searchsorted(joined.starts, first_bytes, side="right") - 1
        rank = np.arange(len(first_bytes)) - (np.cumsum(counts) - counts)[line]
        token = np.cumsum(joined.begins) - 1  # of each byte (a gap counts with the token before it)
        text[~joined.gap & (rank[token] > 3)] = 32
    parsed = parse_floats(text.tobytes())
    if parsed is None or len(parsed) != 3 * count:
        return None
    return np.frombuffer(parsed, dtype=np.float64).reshape(-1, 3)


def _obj_faces(lines: tuple[bytes, int]) -> NDArray[np.int64] | None:
    if lines[1] == 0:
        return np.zeros((0, 3), dtype=np.int64)
    joined = _Lines.of(lines[0])
    if joined is None:
        return None
    text = joined.without_keywords()
    # Like int(tok.split("/", 1)[0]): a corner's vertex index ends at its first slash. A byte is cut
    # when there are more slashes up to it than up to the last gap before it.
    slashes = np.cumsum(text == 47, dtype=np.int32)
    at_gap = np.maximum.accumulate(np.where(joined.gap, slashes, 0))
    parsed = parse_ints(text[slashes <= at_gap].tobytes())
    corners = joined.tokens_per_line() - 1
    if parsed is None or len(parsed) != int(corners.sum()):
        return None  # an empty index ("/2") or junk: the line reader reports it
    values = np.frombuffer(parsed, dtype=np.int64)
    if len(values) and values.min() <= 0:
        return None  # relative (negative) indices count the vertices read so far: line reader
    return fan_triangulate(values - 1, corners)


def fan_triangulate(corners: NDArray[np.int64], counts: NDArray[np.int64]) -> NDArray[np.int64]:
    """(k, 3) fan triangulation of polygons of ``counts`` corners each, listed one after another in
    ``corners``: (v0, v1, v2), (v0, v2, v3), ... A polygon of fewer than three corners gives none.
    Counts must be non-negative and sum to at most ``len(corners)``. (The numpy twin of
    :func:`robodesc.emit.mesh_collada.fan_triangulate`, for OBJ faces.)"""
    if len(counts) and counts.min() == 3 and counts.max() == 3:
        return corners[: 3 * len(counts)].reshape(-1, 3)  # already triangles: the common case
    starts = np.cumsum(counts) - counts
    fans = np.maximum(counts - 2, 0)
    first = np.repeat(starts, fans)
    # k-th triangle of its polygon (from 1): corners first, first + k, first + k + 1.
    k = np.arange(len(first)) - np.repeat(np.cumsum(fans) - fans, fans) + 1
    return np.stack([corners[first], corners[first + k], corners[first + k + 1]], axis=1)


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


def _weld(tri: NDArray[np.float64]) -> tuple[NDArray[np.float64], I32]:
    """Merge identical corners so points are shared (STL stores each corner on its own).

    Corners are identical when their coordinates are equal bit for bit (so 0.0 and -0.0 stay apart)
    and points come in the order of their first corner. Sorting 64-bit keys (a hash of the corner
    over its index) is about 5x faster than np.unique on 24-byte rows; a hash collision between
    different corners is detected and handled by an exact sort. When the C extension is built, its
    hash table gives the same result in one pass."""
    flat = np.ascontiguousarray(tri.reshape(-1, 3))
    n = len(flat)
    if n == 0:
        return flat, np.zeros(0, dtype=np.int32)
    if _cweld is not None:
        return _native_weld(flat, None)
    rows = flat.view(np.uint64)
    order, same_hash = _hash_order(rows)
    changed = _row_changes(rows, order)
    if np.any(changed & same_hash):
        # Two different corners share a hash and may interleave: sort the rows themselves (stable, so
        # equal rows stay in corner order).
        order = np.lexsort((rows[:, 2], rows[:, 1], rows[:, 0]))
        changed = _row_changes(rows, order)
    starts = np.empty(n, dtype=bool)
    starts[0] = True
    starts[1:] = changed
    # Sorted rows come in runs of equal corners, each run in corner order: its first is a point.
    first = order[starts]
    is_first = np.zeros(n, dtype=bool)
    is_first[first] = True
    # Points are numbered by first appearance: the count of first corners before each one.
    number = np.cumsum(is_first) - 1
    indices = np.empty(n, dtype=np.int32)
    indices[order] = number[first][np.cumsum(starts) - 1]
    return flat[is_first], indices


def _weld_indexed(points: NDArray[np.float64], corners: NDArray[np.int64]) -> tuple[NDArray[np.float64], I32]:
    """``_weld(points[corners])``, the same points and indices, without welding every corner: the
    points are welded, then numbered by the first corner that uses them."""
    k = len(corners)
    if _cweld is not None:
        return _native_weld(np.ascontiguousarray(points, dtype=np.float64), corners)
    if len(points) >= k:
        return _weld(np.take(points, corners, axis=0))  # mostly unused points: weld the corners
    unique, row_class = _weld(points)
    group = np.take(row_class, corners)
    first = np.full(len(unique), k, dtype=np.intp)
    np.minimum.at(first, group, np.arange(k))
    used = first[first < k]  # the first corner of each point some corner uses
    is_first = np.zeros(k, dtype=bool)
    is_first[used] = True
    # A point's number: how many first corners come before its own.
    number = np.empty(len(unique), dtype=np.intp)
    number[group[used]] = (np.cumsum(is_first) - 1)[used]
    return np.take(unique, group[is_first], axis=0), np.take(number, group).astype(np.int32)


def _native_weld(rows: NDArray[np.float64], corners: NDArray[np.int64] | None) -> tuple[NDArray[np.float64], I32]:
    """:func:`_weld` (or :func:`_weld_indexed` with ``corners``) through the C hash table."""
    wanted = None if corners is None else np.ascontiguousarray(corners, dtype=np.int64)
    first, indices = _cweld.weld(rows, wanted)
    return np.take(rows, np.frombuffer(first, dtype=np.int64), axis=0), np.frombuffer(indices, dtype=np.int32)


def _hash_order(rows: NDArray[np.uint64]) -> tuple[NDArray[np.intp], NDArray[np.bool_]]:
    """Corner indices sorted by a hash of the corner, then by index; and whether each sorted corner's
    hash equals the previous one's. The index sits in the key's low bits: np.sort on one uint64 is
    several times faster than np.argsort."""
    n = len(rows)
    bits = np.uint64(max(n - 1, 1).bit_length())
    # A full mix per coordinate: floats widened from float32 (STL, COLLADA) have 29 zero low bits,
    # which a plain multiply-and-xor leaves as collisions in about a third of the corpus' files.
    key = _mix64(rows[:, 2].copy())
    key ^= rows[:, 1]
    key = _mix64(key)
    key ^= rows[:, 0]
    key = _mix64(key)
    key = (key >> bits) << bits
    key |= np.arange(n, dtype=np.uint64)
    key.sort()
    order = (key & ((np.uint64(1) << bits) - np.uint64(1))).astype(np.intp)
    hashes = key >> bits
    return order, hashes[1:] == hashes[:-1]


def _mix64(x: NDArray[np.uint64]) -> NDArray[np.uint64]:
    """MurmurHash3's 64-bit finaliser, in place: every output bit depends on every input bit."""
    x ^= x >> np.uint64(33)
    x *= np.uint64(0xFF51AFD7ED558CCD)
    x ^= x >> np.uint64(33)
    x *= np.uint64(0xC4CEB9FE1A85EC53)
    x ^= x >> np.uint64(33)
    return x


def _row_changes(rows: NDArray[np.uint64], order: NDArray[np.intp]) -> NDArray[np.bool_]:
    """Whether each row in ``order`` (after the first) differs from the one before it."""
    # np.take on axis 0 is several times faster than fancy indexing for this gather, and comparing
    # column by column than np.any(..., axis=1).
    ordered = np.take(rows, order, axis=0)
    changed: NDArray[np.bool_] = ordered[1:, 0] != ordered[:-1, 0]
    changed |= ordered[1:, 1] != ordered[:-1, 1]
    changed |= ordered[1:, 2] != ordered[:-1, 2]
    return changed


def _read_trimesh(path: str) -> tuple[NDArray[np.float64], I32, NDArray[np.float64] | None]:
    loaded = load_trimesh(path, process=False)
    vertices = np.asarray(loaded.vertices, dtype=np.float64)
    faces = np.asarray(loaded.faces, dtype=np.int32).reshape(-1)
    uv = None
    visual = getattr(loaded, "visual", None)
    raw_uv = getattr(visual, "uv", None)
    if raw_uv is not None and len(raw_uv) == len(vertices):
        uv = np.asarray(raw_uv, dtype=np.float64)
    return vertices, faces, uv


def build_mesh_numpy(path: str, scale: Vec3 | None) -> MeshData:
    """:func:`robodesc.emit.mesh_data.build_mesh` for the files it leaves to numpy: read here, then
    finished by the C extension when it is built (the same bits as :func:`finish_numpy`)."""
    vertices, indices, uv = read_triangles(path)
    packed_uv = None if uv is None else _packed(uv, np.float32)
    if _cweld is not None:
        return finish(
            np.ascontiguousarray(vertices, dtype=np.float64),
            np.ascontiguousarray(indices, dtype=np.int32),
            scale,
            packed_uv,
        )
    return finish_numpy(vertices, indices, scale, packed_uv)


def finish_numpy(
    vertices: NDArray[np.float64], indices: I32, scale: Vec3 | None, uv: array[float] | None = None
) -> MeshData:
    """:func:`robodesc.emit.mesh_data.finish` in numpy."""
    if len(indices) == 0 or len(vertices) == 0:
        raise MeshReadError("mesh has no triangles")
    tri = indices.reshape(-1, 3)
    if scale is not None:
        s = np.asarray(scale, dtype=np.float64)
        vertices = vertices * s
        if float(np.prod(s)) < 0:
            # A mirroring scale turns the faces inside out: flip the winding back.
            tri = tri[:, ::-1]
    face_vertex_indices = np.ascontiguousarray(tri.reshape(-1), dtype=np.int32)
    normals = face_normals(vertices, face_vertex_indices)
    points = vertices.astype(np.float32)
    # + 0.0: which of 0.0 and -0.0 a minimum keeps is up to numpy's loops; the extent has no -0.
    low, high = (points.min(axis=0) + 0.0).tolist(), (points.max(axis=0) + 0.0).tolist()
    return MeshData(
        points=_packed(points, np.float32),
        face_vertex_counts=array("i", [3]) * len(tri),
        face_vertex_indices=_packed(face_vertex_indices, np.int32),
        normals=_packed(normals, np.float32),
        extent=((low[0], low[1], low[2]), (high[0], high[1], high[2])),
        uv=uv,
    )


def _packed(values: NDArray[Any], dtype: type[np.float32] | type[np.int32]) -> array[Any]:
    out: array[Any] = array("f" if dtype is np.float32 else "i")
    out.frombytes(np.ascontiguousarray(values, dtype=dtype).tobytes())
    return out


def face_normals(vertices: NDArray[np.float64], corners: I32) -> F32:
    """(m, 3) float32 unit normals of the triangles ``corners`` (three point numbers each) lists:
    the cross product of the edges from the first corner, normalised; 0 for a degenerate one."""
    if _cweld is not None:
        raw = _cweld.face_normals(np.ascontiguousarray(vertices, dtype=np.float64), corners)
        return np.frombuffer(raw, dtype=np.float32).reshape(-1, 3)
    tri = vertices[corners.reshape(-1, 3)]
    with np.errstate(all="ignore"):  # overflow and inf - inf in a broken file: that normal is 0 or NaN
        normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        length = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.divide(normals, length, out=np.zeros_like(normals), where=length > 0)
    normals += 0.0  # no negative zeros in the text output
    return normals.astype(np.float32)
