"""Reading the triangles of a COLLADA (.dae) file with lxml, without numpy.

This replaces pycollada on the conversion path: pycollada builds Python objects for every effect,
material and source and parses every float array (normals and texture coordinates too), which costs
about a second on a mesh-heavy robot. Here only what the scene instances is read: the visual scene's
node tree, the ``<vertices>`` position source of each instanced geometry and the vertex column of
its primitives' index lists. Numbers live in ``array.array`` buffers, and the per-point work runs
in the C extension ``robodesc.meshes._weld`` (numpy, imported then, when it is not built: the same
arithmetic, the same bits).

The numbers follow pycollada's rules: positions are float32 (NaN positions become 0), a node's
matrix is the product of its transforms in document order, a child's is its parent's times its
own, and an instance's points are ``R p + t`` rounded to float32. The products are computed in
float64 and rounded once (pycollada rounds to float32 after every operation, so points can differ
from its by a float32 rounding step). The result is widened to float64 and scaled by
``<asset><unit meter>`` (as ROS's loaders do). ``<up_axis>`` is ignored, as pycollada and ROS's
loaders ignore it.

Read: ``<triangles>``, ``<polylist>`` and ``<polygons>`` (fan-triangulated), ``<tristrips>`` and
``<trifans>``; node transforms ``matrix``, ``translate``, ``rotate``, ``scale``, ``lookat`` and
``skew``; ``instance_geometry`` and ``instance_node`` (to ``library_nodes`` or other nodes).
Skipped, as pycollada skips them: ``<lines>``/``<linestrips>``, ``<polygons>``' ``<ph>`` (polygons
with holes), non-mesh geometry, skinned geometry (``instance_controller``) and references to other
files. Broken references and bad numbers raise :class:`MeshReadError`.
"""

from __future__ import annotations

import math
from array import array
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, TypeAlias

from lxml import etree

from robodesc.meshes.buffers import MeshReadError as MeshReadError
from robodesc.meshes.text_numbers import parse_floats, parse_ints

try:
    from robodesc.meshes import _weld as _cweld
except ImportError:  # installed without a C compiler: numpy does the per-point work
    _cweld = None  # type: ignore[assignment]

# Quoted: array.array takes a subscript at run time only from Python 3.12.
Floats: TypeAlias = "array[float]"  # flat: x, y, z, x, y, z ...
Ints: TypeAlias = "array[int]"  # int64
Matrix = tuple[tuple[float, float, float, float], ...]  # 4x4, row-major

IDENTITY: Matrix = ((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))

# Deep node trees are legal but a reference cycle is not: stop well before Python's recursion limit.
_MAX_DEPTH = 200
# Instancing multiplies: a node that instances another twice, 30 levels deep, stays within the depth
# limit and asks for 2^30 copies. The walk counts what it produces and stops at these.
MAX_INSTANCED_CORNERS = 3 * 20_000_000  # triangle corners over all instances (20 M triangles)
MAX_NODE_VISITS = 100_000  # real files have a few thousand; each visit costs ~20 µs

_PRIMITIVES = frozenset({"triangles", "polylist", "polygons", "tristrips", "trifans"})


def read_collada(path: str) -> Any:
    """(m, 3, 3) numpy array of the triangles of every geometry instance in a COLLADA file's scene,
    node transforms applied and scaled by the file's ``<unit meter>`` (for tests and tools)."""
    import numpy as np

    points, corners = read_collada_indexed(path)
    grid = np.frombuffer(points, dtype=np.float64).reshape(-1, 3)
    return np.take(grid, np.frombuffer(corners, dtype=np.int64), axis=0).reshape(-1, 3, 3)


def read_collada_indexed(path: str) -> tuple[Floats, Ints]:
    """:func:`read_collada` as flat float64 points (x, y, z per point) and three corner indices into
    them per triangle: the position sources of every instance, moved. Cheaper to weld than the
    triangles' corners."""
    doc = _Document(_parse(path))
    unit = doc.unit_meter()
    out = _Output(1.0 if unit is None or not unit > 0 else unit)
    for node in doc.scene_nodes():
        _walk(doc, node, None, out, 0)
    if not out.corners:
        raise MeshReadError("COLLADA file has no triangles")
    points: Floats = array("d")
    for part in out.points:
        points.frombytes(part)
    corners: Ints = array("q")
    for indices in out.corners:
        corners.frombytes(indices)
    return points, corners


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
    unit: float  # metres per file unit
    points: list[bytes | bytearray] = field(default_factory=list)  # moved position sources, float64
    corners: list[bytes | bytearray] = field(default_factory=list)  # per primitive, int64 into all points
    count: int = 0  # points so far
    corners_total: int = 0  # triangle corners so far, bounded by MAX_INSTANCED_CORNERS
    visits: int = 0  # nodes walked, bounded by MAX_NODE_VISITS


@dataclass(slots=True)
class _Mesh:
    # Per primitive: float32 positions in the geometry's frame (shared between primitives that use
    # the same source) and three indices into them per triangle.
    parts: list[tuple[Floats, Ints]]


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


def _walk(doc: _Document, node: etree._Element, parent: Matrix | None, out: _Output, depth: int) -> None:
    """Add the triangles under ``node`` to ``out`` in document order (as pycollada yields them)."""
    if depth > _MAX_DEPTH:
        raise MeshReadError("COLLADA node tree is too deep (an instance_node cycle?)")
    out.visits += 1
    if out.visits > MAX_NODE_VISITS:
        raise MeshReadError(f"COLLADA instancing visits more than {MAX_NODE_VISITS} nodes; refused")
    own = _node_matrix(doc, node)
    # pycollada: a top-level node's matrix is its own, a child's is parent @ own.
    matrix = own if parent is None else _product(parent, own)
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


def _instance(doc: _Document, gid: str, matrix: Matrix, out: _Output) -> None:
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
            out.points.append(_place(positions, matrix, out.unit))
            out.count += len(positions) // 3
        out.corners_total += len(tri)
        if out.corners_total > MAX_INSTANCED_CORNERS:
            raise MeshReadError(
                f"COLLADA instancing yields more than {MAX_INSTANCED_CORNERS // 3} triangles "
                "(instance_node fan-out); refused"
            )
        out.corners.append(_shift(tri, offset))


def _matrix(rows: Sequence[Sequence[float]]) -> Matrix:
    return tuple((row[0], row[1], row[2], row[3]) for row in rows)


def _product(a: Matrix, b: Matrix) -> Matrix:
    return _matrix([[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)])


def _node_matrix(doc: _Document, node: etree._Element) -> Matrix:
    """The product of a node's transforms, in document order."""
    matrix: Matrix | None = None
    for child in node:
        m = _transform(doc, child)
        if m is not None:
            matrix = m if matrix is None else _product(matrix, m)
    return IDENTITY if matrix is None else matrix


def _transform(doc: _Document, element: etree._Element) -> Matrix | None:
    name = doc.local(element)
    if name not in _TRANSFORM_SIZES:
        return None
    values = _floats(element.text, f"<{name}>").tolist()
    if len(values) != _TRANSFORM_SIZES[name]:
        raise MeshReadError(f"<{name}> needs {_TRANSFORM_SIZES[name]} numbers, has {len(values)}")
    if name == "matrix":
        return _matrix([values[4 * i : 4 * i + 4] for i in range(4)])
    if name == "translate":
        x, y, z = values
        return ((1.0, 0.0, 0.0, x), (0.0, 1.0, 0.0, y), (0.0, 0.0, 1.0, z), IDENTITY[3])
    if name == "scale":
        x, y, z = values
        return ((x, 0.0, 0.0, 0.0), (0.0, y, 0.0, 0.0), (0.0, 0.0, z, 0.0), IDENTITY[3])
    if name == "rotate":
        return _rotation(*values)
    if name == "lookat":
        return _look_at(values)
    return _skew(values)


_TRANSFORM_SIZES = {"matrix": 16, "translate": 3, "rotate": 4, "scale": 3, "lookat": 9, "skew": 7}


def _rotation(x: float, y: float, z: float, degrees: float) -> Matrix:
    """pycollada's makeRotationMatrix, term for term (the axis is not normalised)."""
    angle = degrees * math.pi / 180.0
    c = math.cos(angle)
    s = math.sin(angle)
    t = 1 - c
    return (
        (t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0.0),
        (t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0.0),
        (t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0.0),
        IDENTITY[3],
    )


def _look_at(values: list[float]) -> Matrix:
    """The frame of a camera at ``eye`` looking at ``interest`` (local -Z) with ``up`` as local +Y.
    pycollada's version is not a rigid transform (it writes eye into the bottom row), so this one
    follows the COLLADA spec instead; no mesh in the corpora uses it."""
    eye, interest, up = values[0:3], values[3:6], values[6:9]
    back = _unit([e - i for e, i in zip(eye, interest, strict=True)], "lookat eye and interest")
    side = _unit(_cross(up, back), "lookat up and view direction")
    top = _cross(back, side)
    return _matrix([*((side[i], top[i], back[i], eye[i]) for i in range(3)), IDENTITY[3]])


def _skew(values: list[float]) -> Matrix:
    """RenderMan's skew (which COLLADA adopts): points move along the translation axis by
    tan(angle) times their distance along the rotation axis. pycollada ignores <skew>."""
    along = _unit(values[1:4], "skew rotation axis")
    shift = _unit(values[4:7], "skew translation axis")
    k = math.tan(math.radians(values[0]))
    rows = [[(1.0 if i == j else 0.0) + k * shift[i] * along[j] for j in range(3)] + [0.0] for i in range(3)]
    return _matrix([*rows, IDENTITY[3]])


def _cross(a: Sequence[float], b: Sequence[float]) -> list[float]:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _unit(vector: Sequence[float], what: str) -> list[float]:
    length = math.sqrt(sum(v * v for v in vector))
    if not length > 0:
        raise MeshReadError(f"{what} are degenerate")
    return [v / length for v in vector]


# --- per-point work: C, or numpy with the same arithmetic ----------------------------------------


def _place(positions: Floats, matrix: Matrix, unit: float) -> bytes | bytearray:
    """float64 points: each float32 position moved by ``matrix`` in float64, rounded to float32,
    widened and multiplied by ``unit`` (see ``place`` in _weld.c)."""
    flat = tuple(v for row in matrix[:3] for v in row)
    if _cweld is not None:
        return _cweld.place(positions, flat, unit)
    import numpy as np

    p = np.frombuffer(positions, dtype=np.float32).reshape(-1, 3).astype(np.float64)
    out = np.empty_like(p)
    for j in range(3):
        r0, r1, r2, t = flat[4 * j : 4 * j + 4]
        # Elementwise, in the C code's order (no BLAS, whose kernels sum and fuse differently).
        out[:, j] = (((r0 * p[:, 0] + r1 * p[:, 1]) + r2 * p[:, 2]) + t).astype(np.float32)
    if unit != 1.0:
        out *= unit
    return out.tobytes()


def _bounds(values: Ints) -> tuple[int, int]:
    """Smallest and largest of non-empty int64 values (min() and max() would box each one)."""
    if _cweld is not None:
        found = _cweld.bounds(values)
        assert found is not None  # the caller skips empty lists
        return found
    return min(values), max(values)


def _shift(values: Ints, offset: int) -> bytes | bytearray:
    if _cweld is not None:
        return _cweld.shift(values, offset)
    import numpy as np

    return (np.frombuffer(values, dtype=np.int64) + offset).tobytes()


def _columns(values: Floats, offset: int, stride: int, count: int, picks: tuple[int, int, int]) -> Floats:
    """float32 x, y, z of ``count`` points at ``offset + i * stride + pick``; NaN becomes 0."""
    out: Floats = array("f")
    if _cweld is not None:
        out.frombytes(_cweld.columns(values, offset, stride, count, picks))
        return out
    import numpy as np

    block = np.frombuffer(values, dtype=np.float64)[offset : offset + count * stride].reshape(count, stride)
    positions = np.ascontiguousarray(block[:, list(picks)], dtype=np.float32)
    positions[np.isnan(positions)] = 0
    out.frombytes(positions.tobytes())
    return out


# --- geometry ----------------------------------------------------------------------------------


def _read_mesh(doc: _Document, geometry: etree._Element) -> _Mesh | None:
    """Positions and triangle index lists of a ``<geometry>``; None for non-mesh geometry."""
    mesh = geometry.find(doc.q("mesh"))
    if mesh is None:
        return None  # convex_mesh, spline, brep: pycollada skips them as well
    gid = geometry.get("id", "")
    sources = {s.get("id", ""): s for s in mesh.iterfind(doc.q("source"))}
    vertices = mesh.find(doc.q("vertices"))
    positions: dict[str, Floats] = {}
    parts: list[tuple[Floats, Ints]] = []
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
        count = len(points) // 3
        low, high = _bounds(tri)
        if low < 0 or high >= count:
            bad = low if low < 0 else high
            raise MeshReadError(f"{where}: vertex index {bad} out of range for {count} positions")
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


def _positions(doc: _Document, source: etree._Element, where: str) -> Floats:
    """float32 x, y, z of a ``<source>``, through its accessor's offset, stride and params."""
    array_element = source.find(doc.q("float_array"))
    if array_element is None:
        raise MeshReadError(f"{where} has no float_array")
    values = _floats(array_element.text, f"float_array in {where}")
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
    if stride > max(len(values), 3) or offset > len(values):  # also keeps both within a C long
        raise MeshReadError(f"{where}: accessor stride {stride} or offset {offset} exceeds the {len(values)} values")
    if stride <= columns[-1] or offset < 0:
        raise MeshReadError(f"{where}: accessor stride {stride} and offset {offset} do not fit x, y, z")
    # The accessor's count is not trusted (pycollada does not read it either): the array length is.
    count = max(len(values) - offset, 0) // stride
    return _columns(values, offset, stride, count, (columns[0], columns[1], columns[2]))


def _corner_indices(doc: _Document, p: etree._Element | None, columns: _Columns, where: str) -> Ints:
    """The VERTEX index of each corner listed in a ``<p>``."""
    values = _ints(None if p is None else p.text, f"<p> of {where}")
    if len(values) % columns.stride:
        raise MeshReadError(f"{where}: <p> has {len(values)} indices, not a multiple of {columns.stride} inputs")
    return values if columns.stride == 1 else values[columns.vertex :: columns.stride]


def _read_triangles(doc: _Document, primitive: etree._Element, columns: _Columns, where: str) -> Ints:
    # One <p> by the spec; pycollada reads only the first, so later ones are ignored here too.
    corners = _corner_indices(doc, primitive.find(doc.q("p")), columns, where)
    if len(corners) % 3:
        raise MeshReadError(f"{where}: {len(corners)} corners do not make whole triangles")
    return corners


def _read_polylist(doc: _Document, primitive: etree._Element, columns: _Columns, where: str) -> Ints:
    vcount = primitive.find(doc.q("vcount"))
    counts = _ints(None if vcount is None else vcount.text, f"<vcount> of {where}")
    corners = _corner_indices(doc, primitive.find(doc.q("p")), columns, where)
    return _fan(corners, counts, where)


def _read_polygons(doc: _Document, primitive: etree._Element, columns: _Columns, where: str) -> Ints:
    # Only direct <p> children: a <ph> (polygon with holes) is skipped whole, as pycollada does.
    polygons = [_corner_indices(doc, p, columns, where) for p in primitive.iterfind(doc.q("p"))]
    corners: Ints = array("q")
    for polygon in polygons:
        corners.extend(polygon)
    return _fan(corners, array("q", [len(polygon) for polygon in polygons]), where)


def _read_strips(doc: _Document, primitive: etree._Element, columns: _Columns, where: str) -> Ints:
    out: Ints = array("q")
    for p in primitive.iterfind(doc.q("p")):
        strip = _corner_indices(doc, p, columns, where)
        # pycollada's order: the even triangles of a strip, then the odd ones (winding kept).
        for first in (0, 1):
            for k in range(first, len(strip) - 2, 2):
                out.extend(
                    (strip[k], strip[k + 1], strip[k + 2]) if k % 2 == 0 else (strip[k + 1], strip[k], strip[k + 2])
                )
    return out


def _read_fans(doc: _Document, primitive: etree._Element, columns: _Columns, where: str) -> Ints:
    out: Ints = array("q")
    for p in primitive.iterfind(doc.q("p")):
        fan = _corner_indices(doc, p, columns, where)
        for k in range(1, len(fan) - 1):
            out.extend((fan[0], fan[k], fan[k + 1]))
    return out


_PRIMITIVE_READERS = {
    "triangles": _read_triangles,
    "polylist": _read_polylist,
    "polygons": _read_polygons,
    "tristrips": _read_strips,
    "trifans": _read_fans,
}


def _fan(corners: Ints, counts: Ints, where: str) -> Ints:
    if len(counts) and min(counts) < 0:
        raise MeshReadError(f"{where}: negative vertex count")
    total = sum(counts)
    if total > len(corners):
        raise MeshReadError(f"{where}: vcount lists {total} corners but <p> has {len(corners)}")
    return fan_triangulate(corners, counts)


def fan_triangulate(corners: Ints, counts: Ints) -> Ints:
    """Fan triangulation of polygons of ``counts`` corners each, listed one after another in
    ``corners``: (v0, v1, v2), (v0, v2, v3) ... A polygon of fewer than three corners gives none.
    Counts must be non-negative and sum to at most ``len(corners)``."""
    if counts.count(3) == len(counts):
        return corners[: 3 * len(counts)]  # already triangles: the common case
    out: Ints = array("q")
    start = 0
    for count in counts:
        for k in range(start + 1, start + count - 1):
            out.extend((corners[start], corners[k], corners[k + 1]))
        start += count
    return out


# --- numbers -----------------------------------------------------------------------------------


def _floats(text: str | None, what: str) -> Floats:
    values = parse_floats(text)
    if values is None:
        raise MeshReadError(f"bad number in {what}: {_first_bad(text or '', float)!r}")
    return values


def _ints(text: str | None, what: str) -> Ints:
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
