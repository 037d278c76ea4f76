"""The mesh readers against the implementations they replaced.

``robodesc.meshes.collada`` must give pycollada's triangles, to float32 rounding (pycollada
rounds node transforms to float32 after every operation, mesh_collada once at the end),
``usd_meshio._weld`` the np.unique weld's points and indices, and the vectorised OBJ reader
the line-by-line one's. The references are kept here (:func:`pycollada_triangles`,
:func:`weld_reference`); ``benchmarks/mesh_read_speed.py`` times against them. Hand-written files
cover what the corpora do not; the whole-corpus comparisons are in the slow tier.
"""

from __future__ import annotations

import hashlib
import math
import os
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
from numpy.typing import NDArray

from robodesc.meshes import readers as usd_meshio
from robodesc.meshes.collada import MeshReadError, read_collada
from robodesc.validation.corpora import example_robot_data_root, icub_root, stretch_root

SHARED_CORPUS = Path(__file__).resolve().parents[2] / ".." / "shared" / "corpus"

# pycollada drops a whole geometry instance when one of its bound materials fails to load; this
# foot's carbon-fibre material refers to a texture surface that is missing, so pycollada sees no
# triangles at all. The new reader ignores materials and reads the foot.
PYCOLLADA_DROPS = {"anymal_foot.dae"}


# --- the references ----------------------------------------------------------------------------


def pycollada_triangles(path: str) -> NDArray[np.float64]:
    """The COLLADA reader robodesc used before mesh_collada (pycollada), unchanged. Tests that
    compare with it skip when pycollada is not installed (it is no longer a runtime dependency)."""
    collada = pytest.importorskip("collada")

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


def weld_reference(tri: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.int32]]:
    """The weld robodesc used before (np.unique over 24-byte rows), unchanged."""
    flat = np.ascontiguousarray(tri.reshape(-1, 3))
    if len(flat) == 0:
        return flat, np.zeros(0, dtype=np.int32)
    keys = flat.view(np.dtype((np.void, flat.dtype.itemsize * 3))).ravel()
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    return flat[first[order]], rank[inverse.ravel()].astype(np.int32)


# --- corpora -----------------------------------------------------------------------------------


def corpus_files(suffix: str) -> list[str]:
    """Every file with ``suffix`` in the installed corpora, one per distinct content."""
    roots = [example_robot_data_root(), icub_root(), stretch_root(), str(SHARED_CORPUS)]
    seen: dict[str, str] = {}
    for root in roots:
        if root is None or not os.path.isdir(root):
            continue
        for path in sorted(_walk(root, suffix)):
            with open(path, "rb") as handle:
                seen.setdefault(hashlib.sha1(handle.read()).hexdigest(), path)
    return sorted(seen.values())


def _walk(root: str, suffix: str) -> Iterator[str]:
    for folder, _, names in os.walk(root):
        for name in names:
            if name.lower().endswith(suffix):
                yield os.path.join(folder, name)


# --- hand-written COLLADA ----------------------------------------------------------------------

NS14 = "http://www.collada.org/2005/11/COLLADASchema"
NS15 = "http://www.collada.org/2008/03/COLLADASchema"

POSITIONS = [0.0, 0.0, 0.0, 1.5, 0.0, 0.0, 1.5, 2.25, 0.0, 0.0, 2.25, 0.125, -0.5, 1.0, 3.0, 0.1, 0.2, 0.3]


def dae(
    geometries: str,
    scene: str,
    *,
    asset: str = "",
    library_nodes: str = "",
    ns: str = NS14,
    scene_url: str = "#Scene",
) -> str:
    nodes = f"<library_nodes>{library_nodes}</library_nodes>" if library_nodes else ""
    return f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="{ns}" version="1.4.1">
  <asset>{asset}</asset>
  <library_geometries>{geometries}</library_geometries>
  {nodes}
  <library_visual_scenes><visual_scene id="Scene">{scene}</visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="{scene_url}"/></scene>
</COLLADA>
"""


def source(
    sid: str, values: list[float] | str, params: str = "XYZ", *, stride: int | None = None, extra: str = ""
) -> str:
    text = values if isinstance(values, str) else " ".join(repr(v) for v in values)
    count = len(text.split())
    params_xml = "".join(f'<param name="{p}" type="float"/>' for p in params)
    stride = stride or len(params)
    return (
        f'<source id="{sid}"><float_array id="{sid}-array" count="{count}">{text}</float_array>'
        f'<technique_common><accessor source="#{sid}-array" count="{count // stride}" stride="{stride}" {extra}>'
        f"{params_xml}</accessor></technique_common></source>"
    )


def geometry(gid: str, primitives: str, positions: list[float] | str = POSITIONS, sources: str = "") -> str:
    return (
        f'<geometry id="{gid}"><mesh>{source(gid + "-pos", positions)}{sources}'
        f'<vertices id="{gid}-vtx"><input semantic="POSITION" source="#{gid}-pos"/></vertices>'
        f"{primitives}</mesh></geometry>"
    )


def triangles(gid: str, p: str, *, count: int = 0) -> str:
    return f'<triangles count="{count}"><input semantic="VERTEX" source="#{gid}-vtx" offset="0"/><p>{p}</p></triangles>'


def node(body: str, *, nid: str = "") -> str:
    return f'<node id="{nid}">{body}</node>' if nid else f"<node>{body}</node>"


def instance(gid: str) -> str:
    return f'<instance_geometry url="#{gid}"/>'


def write(tmp_path: Path, text: str, name: str = "mesh.dae") -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def like_pycollada(got: NDArray[np.float64], expected: NDArray[np.float64]) -> bool:
    """Equal up to float32 rounding steps: pycollada rounds each operation of a node transform to
    float32, mesh_collada computes in float64 and rounds once."""
    scale = float(np.max(np.abs(expected))) if expected.size else 0.0
    return got.shape == expected.shape and bool(np.allclose(got, expected, rtol=4e-7, atol=4e-7 * scale))


def assert_like_pycollada(path: str) -> NDArray[np.float64]:
    expected = pycollada_triangles(path)
    got = read_collada(path)
    assert like_pycollada(got, expected), np.max(np.abs(got - expected)) if got.shape == expected.shape else got.shape
    return got


def test_triangles_in_a_node(tmp_path: Path) -> None:
    text = dae(geometry("g", triangles("g", "0 1 2 0 2 3 3 4 5")), node(instance("g")))
    got = assert_like_pycollada(write(tmp_path, text))
    np.testing.assert_array_equal(got[2], np.float32(POSITIONS).reshape(-1, 3)[[3, 4, 5]])


def test_nested_transforms(tmp_path: Path) -> None:
    matrix = "0 -1 0 0.5  1 0 0 -0.25  0 0 1 2  0 0 0 1"
    scene = node(
        "<translate>0.1 0.2 0.3</translate><rotate>0 0 1 30</rotate>"
        + node(
            f"<scale>2 0.5 1.5</scale><matrix>{matrix}</matrix>" + node("<rotate>1 0 0 -90</rotate>" + instance("g"))
        )
        + instance("g")
    ) + node("<translate>-1 0 0</translate>" + instance("g"))
    text = dae(geometry("g", triangles("g", "0 1 2 1 2 4")), scene)
    got = assert_like_pycollada(write(tmp_path, text))
    assert len(got) == 6


def test_polylist_is_fanned(tmp_path: Path) -> None:
    normals = source("g-nrm", [0.0, 0.0, 1.0] * 3)
    inputs = (
        '<input semantic="VERTEX" source="#g-vtx" offset="0"/><input semantic="NORMAL" source="#g-nrm" offset="1"/>'
    )
    # A triangle, a quad, a pentagon and a triangle; each corner is (vertex, normal).
    corners = [*(0, 1, 2), *(0, 1, 2, 3), *(1, 2, 3, 4, 5), *(3, 4, 5)]
    p = " ".join(f"{v} {v % 3}" for v in corners)
    poly = f'<polylist count="4">{inputs}<vcount>3 4 5 3</vcount><p>{p}</p></polylist>'
    text = dae(geometry("g", poly, sources=normals), node(instance("g")))
    got = assert_like_pycollada(write(tmp_path, text))
    points = np.float32(POSITIONS).reshape(-1, 3).astype(np.float64)
    fans = [[0, 1, 2], [0, 1, 2], [0, 2, 3], [1, 2, 3], [1, 3, 4], [1, 4, 5], [3, 4, 5]]
    np.testing.assert_array_equal(got, points[fans])


def test_polygons_skip_holes(tmp_path: Path) -> None:
    inputs = '<input semantic="VERTEX" source="#g-vtx" offset="0"/>'
    hole = "<ph><p>0 1 2 3</p><h>4 5 0</h></ph>"
    poly = f'<polygons count="3">{inputs}<p>0 1 2 3</p>{hole}<p>3 4 5</p></polygons>'
    text = dae(geometry("g", poly), node(instance("g")))
    got = assert_like_pycollada(write(tmp_path, text))
    assert len(got) == 3  # the quad's two, the triangle; the polygon with a hole is skipped


def test_strips_and_fans(tmp_path: Path) -> None:
    inputs = '<input semantic="VERTEX" source="#g-vtx" offset="0"/>'
    strips = f'<tristrips count="2">{inputs}<p>0 1 2 3 4 5</p><p>5 4 3 2</p></tristrips>'
    fans = f'<trifans count="1">{inputs}<p>0 1 2 3 4</p><p>1 2</p></trifans>'
    text = dae(geometry("g", strips + fans), node(instance("g")))
    got = assert_like_pycollada(write(tmp_path, text))
    assert len(got) == 4 + 2 + 3


def test_input_offsets(tmp_path: Path) -> None:
    normals = source("g-nrm", [0.0, 0.0, 1.0, 0.0, 1.0, 0.0])
    uv = source("g-uv", [0.0, 0.0, 1.0, 1.0], "ST")
    inputs = (
        '<input semantic="NORMAL" source="#g-nrm" offset="0"/><input semantic="VERTEX" source="#g-vtx" offset="1"/>'
        '<input semantic="TEXCOORD" source="#g-uv" offset="2" set="0"/>'
    )
    p = "0 3 1  1 4 0  0 5 1  1 0 1  0 1 0  1 2 1"
    tris = f'<triangles count="2">{inputs}<p>{p}</p></triangles>'
    text = dae(geometry("g", tris, sources=normals + uv), node(instance("g")))
    got = assert_like_pycollada(write(tmp_path, text))
    points = np.float32(POSITIONS).reshape(-1, 3).astype(np.float64)
    np.testing.assert_array_equal(got, points[[[3, 4, 5], [0, 1, 2]]])


def test_instance_node_from_library(tmp_path: Path) -> None:
    library = node("<translate>0 0 1</translate>" + instance("g"), nid="part")
    scene = node("<rotate>0 1 0 45</rotate><instance_node url='#part'/>") + node(
        "<translate>2 0 0</translate><instance_node url='#part'/>"
    )
    text = dae(geometry("g", triangles("g", "0 1 2")), scene, library_nodes=library)
    got = assert_like_pycollada(write(tmp_path, text))
    assert len(got) == 2


def test_unit_meter_scales(tmp_path: Path) -> None:
    text = dae(geometry("g", triangles("g", "0 1 2")), node(instance("g")), asset='<unit meter="0.001" name="mm"/>')
    got = assert_like_pycollada(write(tmp_path, text))
    np.testing.assert_allclose(got[0, 1], [0.0015, 0.0, 0.0])


def test_up_axis_is_ignored(tmp_path: Path) -> None:
    body = geometry("g", triangles("g", "0 1 2 2 3 4")), node("<translate>1 2 3</translate>" + instance("g"))
    y_up = assert_like_pycollada(write(tmp_path, dae(*body, asset="<up_axis>Y_UP</up_axis>"), "y.dae"))
    z_up = assert_like_pycollada(write(tmp_path, dae(*body, asset="<up_axis>Z_UP</up_axis>"), "z.dae"))
    np.testing.assert_array_equal(y_up, z_up)


def test_nan_positions_become_zero(tmp_path: Path) -> None:
    positions = "0 0 0 1 NaN 0 0 1 nan"
    text = dae(geometry("g", triangles("g", "0 1 2"), positions), node(instance("g")))
    got = assert_like_pycollada(write(tmp_path, text))
    assert not np.isnan(got).any()


def test_collada_15_namespace(tmp_path: Path) -> None:
    text = dae(geometry("g", triangles("g", "0 1 2")), node(instance("g")), ns=NS15)
    assert read_collada(write(tmp_path, text)).shape == (1, 3, 3)


def test_accessor_stride_offset_and_unnamed_params(tmp_path: Path) -> None:
    # pycollada ignores stride and offset, so this one is checked by hand: values start at offset 2,
    # come four to a vertex, and the unnamed second param is a value to skip.
    values = [9.0, 9.0, *(1.0, 7.0, 2.0, 3.0), *(4.0, 7.0, 5.0, 6.0), *(7.0, 7.0, 8.0, 9.0)]
    params = '<param name="X" type="float"/><param type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>'
    text_values = " ".join(repr(v) for v in values)
    src = (
        f'<source id="g-pos"><float_array id="a" count="{len(values)}">{text_values}</float_array>'
        f'<technique_common><accessor source="#a" count="3" stride="4" offset="2">{params}</accessor>'
        "</technique_common></source>"
    )
    mesh = (
        f'<geometry id="g"><mesh>{src}<vertices id="g-vtx"><input semantic="POSITION" source="#g-pos"/></vertices>'
        f"{triangles('g', '0 1 2')}</mesh></geometry>"
    )
    got = read_collada(write(tmp_path, dae(mesh, node(instance("g")))))
    np.testing.assert_array_equal(got[0], [[1, 2, 3], [4, 5, 6], [7, 8, 9]])


def test_lookat_and_skew(tmp_path: Path) -> None:
    # pycollada ignores <skew> and builds a non-rigid <lookat>: these follow the COLLADA spec.
    look = node("<lookat>1 2 3  1 2 0  0 1 0</lookat>" + instance("g"))
    skew = node("<skew>45 0 1 0 1 0 0</skew>" + instance("g"))
    got = read_collada(write(tmp_path, dae(geometry("g", triangles("g", "0 1 3")), look + skew)))
    # Looking down -Z from (1, 2, 3): the camera frame is the world frame moved to the eye.
    points = np.float32(POSITIONS).reshape(-1, 3).astype(np.float64)[[0, 1, 3]]
    np.testing.assert_allclose(got[0], points + np.array([1.0, 2.0, 3.0]), atol=1e-6)
    # Skew by 45° of y along x: x += tan(45°) * y.
    np.testing.assert_allclose(
        got[1], points + np.outer(points[:, 1] * math.tan(math.radians(45)), [1, 0, 0]), atol=1e-6
    )


def test_geometry_instanced_twice_is_read_once(tmp_path: Path) -> None:
    scene = node(instance("g")) + node("<scale>2 2 2</scale>" + instance("g"))
    got = assert_like_pycollada(write(tmp_path, dae(geometry("g", triangles("g", "0 1 2")), scene)))
    np.testing.assert_array_equal(got[1], got[0] * 2)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (dae(geometry("g", triangles("g", "0 1 9")), node(instance("g"))), "vertex index 9 out of range"),
        (dae(geometry("g", triangles("g", "0 -1 2")), node(instance("g"))), "vertex index -1 out of range"),
        (dae(geometry("g", triangles("g", "0 1 x")), node(instance("g"))), "bad integer in <p>"),
        (dae(geometry("g", triangles("g", "0 1 2 3")), node(instance("g"))), "do not make whole triangles"),
        (
            dae(geometry("g", triangles("g", "0 1 2"), "0 0 0 1 0 0 0 1 oops"), node(instance("g"))),
            "bad number in float_array",
        ),
        (dae(geometry("g", triangles("g", "0 1 2")), node(instance("missing"))), "missing geometry '#missing'"),
        (dae(geometry("g", triangles("g", "0 1 2")), node("<instance_node url='#nowhere'/>")), "missing node"),
        (dae(geometry("g", triangles("g", "0 1 2")), node(instance("g")), scene_url="#Other"), "missing visual_scene"),
        (dae(geometry("g", triangles("g", "0 1 2")), ""), "has no triangles"),
        (dae(geometry("g", triangles("g", "")), node(instance("g"))), "has no triangles"),
        (
            dae(geometry("g", triangles("g", "0 1 2")), node("<matrix>1 0 0</matrix>" + instance("g"))),
            "needs 16 numbers",
        ),
        (
            dae(geometry("g", triangles("g", "0 1 2")), node("<rotate>0 0 1 x</rotate>" + instance("g"))),
            "bad number in <rotate>",
        ),
        (
            dae(
                geometry("g", '<triangles><input semantic="NORMAL" source="#n" offset="0"/><p>0 1 2</p></triangles>'),
                node(instance("g")),
            ),
            "has no VERTEX input",
        ),
        (
            dae(
                geometry(
                    "g",
                    '<polylist><input semantic="VERTEX" source="#g-vtx" offset="0"/><vcount>3 4</vcount><p>0 1 2 3 4</p></polylist>',
                ),
                node(instance("g")),
            ),
            "vcount lists 7 corners",
        ),
        (
            dae(
                '<geometry id="g"><mesh><vertices id="v"><input semantic="POSITION" source="#nope"/></vertices>'
                + triangles("g", "0 1 2").replace("#g-vtx", "#v")
                + "</mesh></geometry>",
                node(instance("g")),
            ),
            "position source '#nope' is missing",
        ),
        (
            dae(
                geometry("g", triangles("g", "0 1 2")),
                node("<instance_node url='#loop'/>"),
                library_nodes=node("<instance_node url='#loop'/>", nid="loop"),
            ),
            "too deep",
        ),
        ("<COLLADA><unclosed></COLLADA>", "not valid XML"),
    ],
)
def test_malformed_files_raise(tmp_path: Path, text: str, message: str) -> None:
    with pytest.raises(MeshReadError, match=message):
        read_collada(write(tmp_path, text))


def test_external_entities_are_not_read(tmp_path: Path) -> None:
    secret = tmp_path / "secret.txt"
    secret.write_text("0 0 0 1 0 0 0 1 0")
    text = dae(geometry("g", triangles("g", "0 1 2"), "&secret;"), node(instance("g")))
    text = text.replace("<COLLADA", f'<!DOCTYPE COLLADA [<!ENTITY secret SYSTEM "{secret.as_uri()}">]>\n<COLLADA', 1)
    with pytest.raises(MeshReadError, match="out of range for 0 positions"):
        read_collada(write(tmp_path, text))


def test_meshio_uses_the_new_reader(tmp_path: Path) -> None:
    path = write(tmp_path, dae(geometry("g", triangles("g", "0 1 2 0 2 3")), node(instance("g"))))
    points, indices, uv = usd_meshio.read_triangles(path)
    assert uv is None and len(points) == 4
    np.testing.assert_array_equal(indices, [0, 1, 2, 0, 2, 3])
    assert usd_meshio.MeshReadError is MeshReadError


# --- weld --------------------------------------------------------------------------------------


def assert_weld_like_reference(tri: NDArray[np.float64]) -> None:
    points, indices = usd_meshio._weld(tri)
    expected_points, expected_indices = weld_reference(tri)
    assert points.dtype == np.float64 and indices.dtype == np.int32
    # Bitwise, so -0.0/0.0 and NaN payloads count.
    assert points.tobytes() == expected_points.tobytes()
    np.testing.assert_array_equal(indices, expected_indices)


@pytest.mark.parametrize("seed", range(5))
def test_weld_random(seed: int) -> None:
    rng = np.random.default_rng(seed)
    base = rng.normal(size=(300, 3))
    base[:10] = 0.0
    base[5:10, 1] = -0.0  # equal to 0.0 but not bitwise: kept apart, as np.unique on bytes did
    base[10:12] = np.nan
    base[20:40] = base[20:40].astype(np.float32)  # float32-widened, like STL and COLLADA data
    tri = base[rng.integers(0, len(base), size=(2000, 3))]
    assert_weld_like_reference(tri)


def test_weld_edge_cases() -> None:
    assert_weld_like_reference(np.zeros((0, 3, 3)))
    assert_weld_like_reference(np.ones((1, 3, 3)))
    assert_weld_like_reference(np.arange(27, dtype=np.float64).reshape(3, 3, 3))


def test_weld_survives_hash_collisions(monkeypatch: pytest.MonkeyPatch) -> None:
    # Every corner gets the same hash: the exact sort must take over.
    def colliding(rows: NDArray[np.uint64]) -> tuple[NDArray[np.intp], NDArray[np.bool_]]:
        return np.arange(len(rows)), np.ones(max(len(rows) - 1, 0), dtype=bool)

    monkeypatch.setattr(usd_meshio, "_hash_order", colliding)
    rng = np.random.default_rng(7)
    base = rng.normal(size=(50, 3))
    assert_weld_like_reference(base[rng.integers(0, 50, size=(400, 3))])


@pytest.mark.parametrize("seed", range(3))
def test_weld_indexed_like_welding_the_corners(seed: int) -> None:
    # COLLADA corners index moved position sources: welding those first must change nothing.
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(400, 3)).astype(np.float32).astype(np.float64)
    points[50:80] = points[:30]  # the same point twice in the sources
    points[80:90] = 0.0
    points[85:90, 2] = -0.0
    points[90:95] = np.nan
    for count in (3000, 300):  # more corners than points, and fewer (welds the corners instead)
        corners = rng.integers(0, len(points), size=count)
        got_points, got_indices = usd_meshio._weld_indexed(points, corners)
        expected_points, expected_indices = weld_reference(points[corners])
        assert got_points.tobytes() == expected_points.tobytes()
        assert got_indices.dtype == np.int32
        np.testing.assert_array_equal(got_indices, expected_indices)


def test_weld_real_stl() -> None:
    files = [p for p in corpus_files(".stl") if os.path.getsize(p) > 200_000][:3]
    if not files:
        pytest.skip("no STL corpus installed")
    for path in files:
        assert_weld_like_reference(usd_meshio._read_stl(path))


# --- OBJ ---------------------------------------------------------------------------------------


def assert_obj_like_lines(tmp_path: Path, data: bytes, *, fast: bool = True) -> None:
    path = tmp_path / "mesh.obj"
    path.write_bytes(data)
    got = usd_meshio._read_obj(str(path))
    expected = usd_meshio._read_obj_lines(data)
    assert (usd_meshio._read_obj_fast(data) is not None) == fast
    assert got[0].tobytes() == expected[0].tobytes()
    assert got[1].dtype == expected[1].dtype == np.int32
    np.testing.assert_array_equal(got[1], expected[1])


OBJ = b"""# a comment
mtllib x.mtl
o first
v 0 0 0
v 1.5 0 0
v 1.5 2.25 0
v 0 2.25 0.125
vn 0 0 1
vt 0.5 0.5
f 1 2 3
f 1/1/1 2/1/1 3/1/1 4/1/1
o second
v -0.5 1e-3 3
v 0.1 0.2 0.3
f 3//1 4//1 5//1 6//1 1//1
f 5 6
"""


@pytest.mark.parametrize(
    ("data", "fast"),
    [
        (OBJ, True),
        (OBJ.replace(b"\n", b"\r\n"), True),
        (OBJ.replace(b"\n", b"\r"), True),
        (OBJ.replace(b"v 0 0 0", b"v 0\t 0  0\t"), True),
        (OBJ.replace(b"v 0 0 0", b"v 0 0 0 0.2 0.3 0.4"), True),  # vertex colours
        (OBJ.replace(b"# a comment", "# café, 東京".encode()), True),
        (OBJ.replace(b"vt 0.5 0.5", b"v 9 9 9"), True),  # a forward reference stays absolute
        (OBJ.replace(b"f 1 2 3", b"f -4 -3 -2"), False),  # relative indices
        (OBJ.replace(b"v 0 0 0", "v 0\u00a00 0".encode()), False),  # a non-ASCII space
        (OBJ.replace(b"# a comment", b"# form\x0cfeed"), False),
        (b"", True),
    ],
)
def test_obj_like_line_reader(tmp_path: Path, data: bytes, fast: bool) -> None:
    assert_obj_like_lines(tmp_path, data, fast=fast)


@pytest.mark.parametrize(
    ("data", "message"),
    [
        (OBJ.replace(b"f 1 2 3", b"f 1 x 3"), "bad face line"),
        (OBJ.replace(b"f 1 2 3", b"f 1 /2 3"), "bad face line"),
        (OBJ.replace(b"v 0 0 0", b"v 0 0"), "bad vertex line"),
        (OBJ.replace(b"v 0 0 0", b"v 0 0 zero"), "bad vertex line"),
        (OBJ.replace(b"f 1 2 3", b"f 1 2 30"), "does not exist"),
    ],
)
def test_obj_errors(tmp_path: Path, data: bytes, message: str) -> None:
    path = tmp_path / "bad.obj"
    path.write_bytes(data)
    with pytest.raises(MeshReadError, match=message):
        usd_meshio._read_obj(str(path))


# --- whole corpora (slow) ----------------------------------------------------------------------


@pytest.mark.slow
def test_collada_corpus_like_pycollada() -> None:
    files = corpus_files(".dae")
    if not files:
        pytest.skip("no COLLADA corpus installed")
    differences = []
    for path in files:
        got = read_collada(path)
        try:
            expected = pycollada_triangles(path)
        except MeshReadError:
            assert os.path.basename(path) in PYCOLLADA_DROPS, path
            continue
        if not like_pycollada(got, expected):
            differences.append(path)
    assert not differences


@pytest.mark.slow
def test_collada_corpus_welds_like_before() -> None:
    # The whole DAE path of read_triangles against the old weld of its triangles, bit for bit, and
    # against pycollada's triangles, on the largest files.
    files = sorted(corpus_files(".dae"), key=os.path.getsize)[-20:]
    for path in files:
        if os.path.basename(path) in PYCOLLADA_DROPS:
            continue
        points, indices, _ = usd_meshio.read_triangles(path)
        triangles = read_collada(path)
        expected_points, expected_indices = weld_reference(triangles)
        assert points.tobytes() == expected_points.tobytes(), path
        np.testing.assert_array_equal(indices, expected_indices)
        assert like_pycollada(triangles, pycollada_triangles(path)), path


@pytest.mark.slow
def test_obj_corpus_like_line_reader(tmp_path: Path) -> None:
    files = corpus_files(".obj")
    if not files:
        pytest.skip("no OBJ corpus installed")
    for path in files:
        with open(path, "rb") as handle:
            assert_obj_like_lines(tmp_path, handle.read())


@pytest.mark.slow
def test_stl_corpus_welds_like_before() -> None:
    files = corpus_files(".stl")
    if not files:
        pytest.skip("no STL corpus installed")
    for path in files:
        assert_weld_like_reference(usd_meshio._read_stl(path))
