"""Reading the triangles of a COLLADA (.dae) file with lxml and numpy.

This replaces pycollada on the conversion path: pycollada builds Python objects for every effect,
material and source and parses every float array (normals and texture coordinates too), which costs
about a second on a mesh-heavy robot. Here only what the scene instances is read: the visual scene's
node tree, the ``<vertices>`` position source of each instanced geometry and the vertex column of
its primitives' index lists.

The numbers follow pycollada bit for bit, because the golden files were written with it: positions
and node transforms are parsed to float32 (NaN positions become 0), each node's matrix is the
float32 product of its transforms, and an instance's points are ``positions @ R.T + t`` in float32.
The result is widened to float64 and scaled by ``<asset><unit meter>`` (as ROS's loaders do).
``<up_axis>`` is ignored, as pycollada and ROS's loaders ignore it.

Read: ``<triangles>``, ``<polylist>`` and ``<polygons>`` (fan-triangulated), ``<tristrips>`` and
``<trifans>``; node transforms ``matrix``, ``translate``, ``rotate``, ``scale``, ``lookat`` and
``skew``; ``instance_geometry`` and ``instance_node`` (to ``library_nodes`` or other nodes).
Skipped, as pycollada skips them: ``<lines>``/``<linestrips>``, ``<polygons>``' ``<ph>`` (polygons
with holes), non-mesh geometry, skinned geometry (``instance_controller``) and references to other
files. Broken references and bad numbers raise :class:`MeshReadError`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from lxml import etree
from numpy.typing import NDArray

from robodesc.emit.mesh_data import MeshReadError as MeshReadError
from robodesc.emit.number_text import parse_floats, parse_ints

F32 = NDArray[np.float32]
F64 = NDArray[np.float64]
I64 = NDArray[np.int64]

# Deep node trees are legal but a reference cycle is not: stop well before Python's recursion limit.
_MAX_DEPTH = 200

_PRIMITIVES = frozenset({"triangles", "polylist", "polygons", "tristrips", "trifans"})


def read_collada(path: str) -> F64:
    """(m, 3, 3) triangles of every geometry instance in a COLLADA file's scene, node transforms
    applied and scaled by the file's ``<unit meter>``."""
    points, corners = read_collada_indexed(path)
    return np.take(points, corners, axis=0).reshape(-1, 3, 3)


def read_collada_indexed(path: str) -> tuple[F64, I64]:
    """:func:`read_collada` as (n, 3) points and three corner indices into them per triangle: the
    position sources of every instance, moved. Cheaper to weld than the triangles' corners."""
    doc = _Document(_parse(path))
    out = _Output()
    for node in doc.scene_nodes():
        _walk(doc, node, None, out, 0)
    if not out.corners:
        raise MeshReadError("COLLADA file has no triangles")
    points = np.concatenate(out.points).astype(np.float64)
    unit = doc.unit_meter()
    if unit is not None and unit > 0 and unit != 1.0:
        points = points * unit
    return points, np.concatenate(out.corners)


def _parse(path: str) -> etree._Element:
    # Entities and network access are off: a mesh file must not make the converter read other files.
    # Ids are looked up here, not through libxml2's id table (collect_ids off: a tenth of the parse).
    parser = etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        huge_tree=True,
        remove_comments=True,
        remove_pis=True,
        collect_ids=False,
    )
    try:
        return etree.parse(path, parser).getroot()
    except etree.XMLSyntaxError as exc:
        raise MeshReadError(f"COLLADA file is not valid XML: {exc}") from None


@dataclass(slots=True)
class _Output:
    points: list[F32] = field(default_factory=list)  # moved position sources
    corners: list[I64] = field(default_factory=list)  # per primitive, indices into all points so far
    count: int = 0  # points so far


@dataclass(slots=True)
class _Mesh:
    # Per primitive: (n, 3) positions in the geometry's frame (shared between primitives that use the
    # same source) and (k, 3) indices into them.
    parts: list[tuple[F32, I64]]


class _Document:
    """Element look-ups by id, built on first use, and the geometries read so far."""

    def __init__(self, root: etree._Element) -> None:
        self.root = root
        tag = root.tag if isinstance(root.tag, str) else ""
        self.ns = tag[: tag.index("}") + 1] if tag.startswith("{") else ""
        self._geometries: dict[str, etree._Element] | None = None
        self._nodes: dict[str, etree._Element] | None = None
        self.meshes: dict[str, _Mesh | None] = {}

    def q(self, *names: str) -> str:
        """An ElementPath of names in the document's namespace."""
        return "/".join(self.ns + name for name in names)

    def local(self, element: etree._Element) -> str:
        tag = element.tag
        # Comments and processing instructions are removed by the parser; entities have no str tag.
        if not isinstance(tag, str):
            return ""
        return tag[len(self.ns) :] if tag.startswith(self.ns) else tag

    def unit_meter(self) -> float | None:
        unit = self.root.find(self.q("asset", "unit"))
        if unit is None:
            return None
        try:
            return float(unit.get("meter", ""))
        except ValueError:
            return None  # pycollada drops a bad unit and so keeps the file's numbers

    def scene_nodes(self) -> list[etree._Element]:
        instance = self.root.find(self.q("scene", "instance_visual_scene"))
        if instance is None:
            return []
        url = _local_url(instance, "instance_visual_scene")
        for scene in self.root.iterfind(self.q("library_visual_scenes", "visual_scene")):
            if scene.get("id") == url:
                return list(scene.iterfind(self.q("node")))
        raise MeshReadError(f"<scene> refers to a missing visual_scene '#{url}'")

    def geometry(self, gid: str) -> etree._Element:
        if self._geometries is None:
            self._geometries = {}
            for element in self.root.iterfind(self.q("library_geometries", "geometry")):
                self._geometries.setdefault(element.get("id", ""), element)
        found = self._geometries.get(gid)
        if found is None:
            raise MeshReadError(f"instance_geometry refers to a missing geometry '#{gid}'")
        return found

    def node(self, nid: str) -> etree._Element:
        if self._nodes is None:
            # Any node may be instanced (pycollada looks in the scene's top level, then library_nodes).
            self._nodes = {}
            for element in self.root.iter(self.ns + "node"):
                self._nodes.setdefault(element.get("id", ""), element)
        found = self._nodes.get(nid)
        if found is None:
            raise MeshReadError(f"instance_node refers to a missing node '#{nid}'")
        return found


def _local_url(element: etree._Element, what: str) -> str:
    url = element.get("url", "")
    if not url.startswith("#") or len(url) < 2:
        raise MeshReadError(f"<{what}> has url {url!r}, not a '#id' in the same file")
    return url[1:]


# --- scene graph -------------------------------------------------------------------------------


def _walk(doc: _Document, node: etree._Element, parent: F32 | None, out: _Output, depth: int) -> None:
    """Add the triangles under ``node`` to ``out`` in document order (as pycollada yields them)."""
    if depth > _MAX_DEPTH:
        raise MeshReadError("COLLADA node tree is too deep (an instance_node cycle?)")
    own = _node_matrix(doc, node)
    # pycollada: a top-level node's matrix is its own, a child's is np.dot(parent, own).
    matrix = own if parent is None else np.dot(parent, own)
    for child in node:
        name = doc.local(child)
        if name == "node":
            _walk(doc, child, matrix, out, depth + 1)
        elif name == "instance_node":
            url = child.get("url", "")
            if url.startswith("#"):  # a node in another file is not read (pycollada skips it too)
                _walk(doc, doc.node(url[1:]), matrix, out, depth + 1)
        elif name == "instance_geometry":
            url = child.get("url", "")
            if url.startswith("#"):
                _instance(doc, url[1:], matrix, out)


def _instance(doc: _Document, gid: str, matrix: F32, out: _Output) -> None:
    mesh = doc.meshes.get(gid)
    if gid not in doc.meshes:
        mesh = doc.meshes[gid] = _read_mesh(doc, doc.geometry(gid))
    if mesh is None:
        return
    offsets: dict[int, int] = {}
    for positions, tri in mesh.parts:
        offset = offsets.get(id(positions))
        if offset is None:
            offset = offsets[id(positions)] = out.count
            # Exactly pycollada's BoundTriangleSet: float32 positions times the float32 matrix.
            out.points.append(np.dot(positions, matrix[:3, :3].T) + matrix[:3, 3])
            out.count += len(positions)
        out.corners.append(tri.reshape(-1) + offset)


def _node_matrix(doc: _Document, node: etree._Element) -> F32:
    """The float32 product of a node's transforms, in document order, as pycollada computes it."""
    transforms = [m for m in (_transform(doc, child) for child in node) if m is not None]
    if len(transforms) == 1:
        return transforms[0]
    matrix = np.identity(4, dtype=np.float32)
    for m in transforms:
        matrix = np.dot(matrix, m)
    return matrix


def _transform(doc: _Document, element: etree._Element) -> F32 | None:
    name = doc.local(element)
    if name not in _TRANSFORM_SIZES:
        return None
    values = _floats(element.text, f"<{name}>").astype(np.float32)
    if len(values) != _TRANSFORM_SIZES[name]:
        raise MeshReadError(f"<{name}> needs {_TRANSFORM_SIZES[name]} numbers, has {len(values)}")
    if name == "matrix":
        return values.reshape(4, 4)
    matrix = np.identity(4, dtype=np.float32)
    if name == "translate":
        matrix[:3, 3] = values
    elif name == "scale":
        matrix[0, 0], matrix[1, 1], matrix[2, 2] = values
    elif name == "rotate":
        matrix = _rotation(*values)
    elif name == "lookat":
        matrix = _look_at(values.astype(np.float64))
    else:
        matrix = _skew(values.astype(np.float64))
    return matrix


_TRANSFORM_SIZES = {"matrix": 16, "translate": 3, "rotate": 4, "scale": 3, "lookat": 9, "skew": 7}


def _rotation(x: np.float32, y: np.float32, z: np.float32, degrees: np.float32) -> F32:
    """pycollada's makeRotationMatrix, kept term for term (float32 scalars, axis not normalised) so
    rotated meshes stay bit-identical to what the golden files were written with."""
    angle = degrees * np.pi / 180.0
    c = np.cos(angle)
    s = np.sin(angle)
    t = 1 - c
    return np.array(
        [
            [t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0],
            [0, 0, 0, 1],
        ],
        dtype=np.float32,
    )


def _look_at(values: F64) -> F32:
    """The frame of a camera at ``eye`` looking at ``interest`` (local -Z) with ``up`` as local +Y.
    pycollada's version is not a rigid transform (it writes eye into the bottom row), so this one
    follows the COLLADA spec instead; no mesh in the corpora uses it."""
    eye, interest, up = values[0:3], values[3:6], values[6:9]
    back = _unit(eye - interest, "lookat eye and interest")
    side = _unit(np.cross(up, back), "lookat up and view direction")
    matrix = np.identity(4)
    matrix[:3, 0], matrix[:3, 1], matrix[:3, 2], matrix[:3, 3] = side, np.cross(back, side), back, eye
    return matrix.astype(np.float32)


def _skew(values: F64) -> F32:
    """RenderMan's skew (which COLLADA adopts): points move along the translation axis by
    tan(angle) times their distance along the rotation axis. pycollada ignores <skew>."""
    along = _unit(values[1:4], "skew rotation axis")
    shift = _unit(values[4:7], "skew translation axis")
    matrix = np.identity(4)
    matrix[:3, :3] += math.tan(math.radians(values[0])) * np.outer(shift, along)
    return matrix.astype(np.float32)


def _unit(vector: F64, what: str) -> F64:
    length = float(np.linalg.norm(vector))
    if not length > 0:
        raise MeshReadError(f"{what} are degenerate")
    return vector / length


# --- geometry ----------------------------------------------------------------------------------


def _read_mesh(doc: _Document, geometry: etree._Element) -> _Mesh | None:
    """Positions and triangle index lists of a ``<geometry>``; None for non-mesh geometry."""
    mesh = geometry.find(doc.q("mesh"))
    if mesh is None:
        return None  # convex_mesh, spline, brep: pycollada skips them as well
    gid = geometry.get("id", "")
    sources = {s.get("id", ""): s for s in mesh.iterfind(doc.q("source"))}
    vertices = mesh.find(doc.q("vertices"))
    positions: dict[str, F32] = {}
    parts: list[tuple[F32, I64]] = []
    for primitive in mesh:
        kind = doc.local(primitive)
        if kind not in _PRIMITIVES:
            continue
        where = f"geometry '{gid}' <{kind}>"
        sid, columns = _vertex_input(doc, primitive, vertices, where)
        tri = _PRIMITIVE_READERS[kind](doc, primitive, columns, where)
        if not len(tri):
            continue
        if sid not in positions:
            source = sources.get(sid)
            if source is None:
                raise MeshReadError(f"{where}: position source '#{sid}' is missing")
            positions[sid] = _positions(doc, source, f"geometry '{gid}' source '{sid}'")
        points = positions[sid]
        low, high = int(tri.min()), int(tri.max())
        if low < 0 or high >= len(points):
            bad = low if low < 0 else high
            raise MeshReadError(f"{where}: vertex index {bad} out of range for {len(points)} positions")
        parts.append((points, tri))
    return _Mesh(parts)


@dataclass(slots=True, frozen=True)
class _Columns:
    stride: int  # index values per corner: the largest input offset + 1
    vertex: int  # which of them is the VERTEX index


def _vertex_input(
    doc: _Document, primitive: etree._Element, vertices: etree._Element | None, where: str
) -> tuple[str, _Columns]:
    """The position source id of a primitive and where its VERTEX index sits in each corner."""
    offsets: list[int] = []
    vertex: tuple[int, str] | None = None
    for item in primitive.iterfind(doc.q("input")):
        try:
            offset = int(item.get("offset", ""))
        except ValueError:
            raise MeshReadError(f"{where}: input with a bad offset {item.get('offset')!r}") from None
        if offset < 0:
            raise MeshReadError(f"{where}: input with a negative offset")
        offsets.append(offset)
        if item.get("semantic") == "VERTEX" and vertex is None:
            vertex = offset, item.get("source", "")
    if vertex is None:
        raise MeshReadError(f"{where} has no VERTEX input")
    offset, url = vertex
    if not url.startswith("#"):
        raise MeshReadError(f"{where}: VERTEX input source {url!r} is not a '#id'")
    return _position_source(doc, url[1:], vertices, where), _Columns(max(offsets) + 1, offset)


def _position_source(doc: _Document, sid: str, vertices: etree._Element | None, where: str) -> str:
    if vertices is None or vertices.get("id") != sid:
        return sid  # a VERTEX input may name the position source directly
    for item in vertices.iterfind(doc.q("input")):
        if item.get("semantic") == "POSITION":
            url = item.get("source", "")
            if not url.startswith("#"):
                raise MeshReadError(f"{where}: POSITION source {url!r} is not a '#id'")
            return url[1:]
    raise MeshReadError(f"{where}: <vertices id='{sid}'> has no POSITION input")


def _positions(doc: _Document, source: etree._Element, where: str) -> F32:
    """(n, 3) float32 positions of a ``<source>``, through its accessor's offset, stride and params."""
    array = source.find(doc.q("float_array"))
    if array is None:
        raise MeshReadError(f"{where} has no float_array")
    values = _floats(array.text, f"float_array in {where}")
    accessor = source.find(doc.q("technique_common", "accessor"))
    params = [] if accessor is None else accessor.findall(doc.q("param"))
    # A param without a name marks a value to skip; files that name none still mean x, y, z.
    named = [i for i, param in enumerate(params) if param.get("name")]
    columns = (named if len(named) >= 3 else list(range(max(len(params), 3))))[:3]
    try:
        stride = int(accessor.get("stride", len(params))) if accessor is not None else 3
        offset = int(accessor.get("offset", "0")) if accessor is not None else 0
    except ValueError:
        raise MeshReadError(f"{where}: accessor with a bad stride or offset") from None
    if stride <= columns[-1] or offset < 0:
        raise MeshReadError(f"{where}: accessor stride {stride} and offset {offset} do not fit x, y, z")
    # The accessor's count is not trusted (pycollada does not read it either): the array length is.
    count = max(len(values) - offset, 0) // stride
    block = values[offset : offset + count * stride].reshape(count, stride)[:, columns]
    positions = np.ascontiguousarray(block, dtype=np.float32)
    positions[np.isnan(positions)] = 0  # pycollada's rule; a NaN point would poison the extent
    return positions


def _corner_indices(doc: _Document, p: etree._Element | None, columns: _Columns, where: str) -> I64:
    """The VERTEX index of each corner listed in a ``<p>``."""
    values = _ints(None if p is None else p.text, f"<p> of {where}")
    if len(values) % columns.stride:
        raise MeshReadError(f"{where}: <p> has {len(values)} indices, not a multiple of {columns.stride} inputs")
    return values.reshape(-1, columns.stride)[:, columns.vertex]


def _read_triangles(doc: _Document, primitive: etree._Element, columns: _Columns, where: str) -> I64:
    # One <p> by the spec; pycollada reads only the first, so later ones are ignored here too.
    corners = _corner_indices(doc, primitive.find(doc.q("p")), columns, where)
    if len(corners) % 3:
        raise MeshReadError(f"{where}: {len(corners)} corners do not make whole triangles")
    return corners.reshape(-1, 3)


def _read_polylist(doc: _Document, primitive: etree._Element, columns: _Columns, where: str) -> I64:
    vcount = primitive.find(doc.q("vcount"))
    counts = _ints(None if vcount is None else vcount.text, f"<vcount> of {where}")
    corners = _corner_indices(doc, primitive.find(doc.q("p")), columns, where)
    return _fan(corners, counts, where)


def _read_polygons(doc: _Document, primitive: etree._Element, columns: _Columns, where: str) -> I64:
    # Only direct <p> children: a <ph> (polygon with holes) is skipped whole, as pycollada does.
    polygons = [_corner_indices(doc, p, columns, where) for p in primitive.iterfind(doc.q("p"))]
    if not polygons:
        return np.zeros((0, 3), dtype=np.int64)
    counts = np.array([len(polygon) for polygon in polygons], dtype=np.int64)
    return _fan(np.concatenate(polygons), counts, where)


def _read_strips(doc: _Document, primitive: etree._Element, columns: _Columns, where: str) -> I64:
    parts: list[I64] = []
    for p in primitive.iterfind(doc.q("p")):
        strip = _corner_indices(doc, p, columns, where)
        if len(strip) < 3:
            continue
        # pycollada's order: the even triangles of a strip, then the odd ones (winding kept).
        parts.append(np.stack([strip[0:-2:2], strip[1:-1:2], strip[2::2]], axis=1))
        parts.append(np.stack([strip[2:-1:2], strip[1:-2:2], strip[3::2]], axis=1))
    return np.concatenate(parts) if parts else np.zeros((0, 3), dtype=np.int64)


def _read_fans(doc: _Document, primitive: etree._Element, columns: _Columns, where: str) -> I64:
    parts: list[I64] = []
    for p in primitive.iterfind(doc.q("p")):
        fan = _corner_indices(doc, p, columns, where)
        if len(fan) >= 3:
            parts.append(np.stack([np.full(len(fan) - 2, fan[0]), fan[1:-1], fan[2:]], axis=1))
    return np.concatenate(parts) if parts else np.zeros((0, 3), dtype=np.int64)


_PRIMITIVE_READERS = {
    "triangles": _read_triangles,
    "polylist": _read_polylist,
    "polygons": _read_polygons,
    "tristrips": _read_strips,
    "trifans": _read_fans,
}


def _fan(corners: I64, counts: I64, where: str) -> I64:
    if len(counts) and counts.min() < 0:
        raise MeshReadError(f"{where}: negative vertex count")
    if int(counts.sum()) > len(corners):
        raise MeshReadError(f"{where}: vcount lists {int(counts.sum())} corners but <p> has {len(corners)}")
    return fan_triangulate(corners, counts)


def fan_triangulate(corners: I64, counts: I64) -> I64:
    """(k, 3) fan triangulation of polygons of ``counts`` corners each, listed one after another in
    ``corners``: (v0, v1, v2), (v0, v2, v3), ... A polygon of fewer than three corners gives none.
    Counts must be non-negative and sum to at most ``len(corners)``."""
    if len(counts) and counts.min() == 3 and counts.max() == 3:
        return corners[: 3 * len(counts)].reshape(-1, 3)  # already triangles: the common case
    starts = np.cumsum(counts) - counts
    fans = np.maximum(counts - 2, 0)
    first = np.repeat(starts, fans)
    # k-th triangle of its polygon (from 1): corners first, first + k, first + k + 1.
    k = np.arange(len(first)) - np.repeat(np.cumsum(fans) - fans, fans) + 1
    return np.stack([corners[first], corners[first + k], corners[first + k + 1]], axis=1)


# --- numbers -----------------------------------------------------------------------------------


def _floats(text: str | None, what: str) -> F64:
    values = parse_floats(text)
    if values is None:
        raise MeshReadError(f"bad number in {what}: {_first_bad(text or '', float)!r}")
    return values


def _ints(text: str | None, what: str) -> I64:
    values = parse_ints(text)
    if values is None:
        raise MeshReadError(f"bad integer in {what}: {_first_bad(text or '', int)!r}")
    return values


def _first_bad(text: str, kind: type[float] | type[int]) -> str:
    """The first token that does not parse, for the error message (only run on failure)."""
    for token in text.split():
        try:
            kind(token)
        except ValueError:
            return token[:40]
    return text.strip()[:40]
