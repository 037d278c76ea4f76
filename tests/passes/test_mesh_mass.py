"""robodesc.meshes.mass against trimesh, which it replaces for the inertia passes (docs/passes.md).

On the same triangles the integrals and the hull agree with trimesh's to rounding (1e-9 relative).
Reading and merging agree exactly for STL and OBJ; trimesh reads COLLADA through pycollada's float32
arrays, robodesc in float64, so DAE files agree to float32 precision. Where trimesh keeps vertices
apart by their normals or texture coordinates (a closed mesh it calls open), robodesc merges them.
"""

from __future__ import annotations

import glob
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh

from robodesc.meshes.mass import is_watertight, merge_vertices, read_merged, solid
from robodesc.validation.corpora import example_robot_data_root

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
EXAMPLE_MESHES = sorted(
    glob.glob(os.path.join(ROOT, "examples", "urdf", "meshes", "*"))
    + glob.glob(os.path.join(ROOT, "tests", "usd", "data", "wedge.*"))
)
ERD = example_robot_data_root()
# A few corpus meshes of each reader: closed and open STL, OBJ and COLLADA (skipped when absent).
CORPUS_MESHES = [
    "robots/bolt_description/meshes/stl/bolt_body.stl",
    "robots/z1_description/meshes/collision/z1_Link04.STL",
    "robots/ur_description/meshes/ur5/collision/forearm.stl",
    "robots/solo_description/meshes/obj/without_foot/solo_lower_leg_right_side.obj",
    "robots/alex_description/meshes/cycloidal_arm/RightShoulderYawLink.obj",
    "robots/panda_description/meshes/visual/link2.dae",
    "robots/romeo_description/meshes/V1/visual/Torso.dae",
    "robots/icub_description/meshes/upmc/collision/icub_simple_collision_neck_1.dae",
]


def _corpus(rel: str) -> str:
    path = os.path.join(ERD or "", rel)
    if ERD is None or not os.path.isfile(path):
        pytest.skip(f"{rel} is not installed (example-robot-data)")
    return path


def _trimesh_props(mesh: trimesh.Trimesh) -> tuple[bool, float, np.ndarray, np.ndarray]:
    """What robodesc did before meshes.mass: trimesh's watertight test, hull, invert and integrals."""
    closed = bool(mesh.is_watertight)
    if not closed:
        mesh = mesh.convex_hull
    if mesh.volume < 0:
        mesh.invert()
    return closed, float(mesh.volume), np.asarray(mesh.center_mass), np.asarray(mesh.moment_inertia)


def _assert_same(path: str, found: object, expected: tuple[bool, float, np.ndarray, np.ndarray], rel: float) -> None:
    closed, volume, com, tensor = expected
    assert found.watertight == closed, path  # type: ignore[attr-defined]
    assert found.volume == pytest.approx(volume, rel=rel), path  # type: ignore[attr-defined]
    size = volume ** (1 / 3)  # the centre's error relative to the body's size
    assert np.abs(found.com - com).max() <= rel * size, path  # type: ignore[attr-defined]
    assert np.abs(found.tensor - tensor).max() <= rel * np.abs(tensor).max(), path  # type: ignore[attr-defined]


def _paths() -> list[str]:
    return EXAMPLE_MESHES + [os.path.join(ERD or "", rel) for rel in CORPUS_MESHES]


@pytest.mark.parametrize("path", _paths(), ids=os.path.basename)
def test_same_triangles_same_numbers_as_trimesh(path: str) -> None:
    """The integrals, the watertight test and the hull, on robodesc's merged triangles."""
    if not os.path.isfile(path):
        pytest.skip(f"{path} is not installed")
    vertices, faces = read_merged(path)
    # A URDF scale, applied after the merge as trimesh does. Not a millimetre one: trimesh's hull drops
    # triangles whose cross product is under 1e-13 (util.unitize), opening the hull; robodesc keeps
    # them (docs/passes.md).
    scale = np.array([1.0, 1.5, 0.5])
    mesh = trimesh.Trimesh(vertices * scale, faces, process=False)
    _assert_same(path, solid(vertices * scale, faces), _trimesh_props(mesh), rel=1e-9)


@pytest.mark.parametrize(
    "path",
    EXAMPLE_MESHES + [os.path.join(ERD or "", rel) for rel in CORPUS_MESHES if not rel.endswith(".dae")],
    ids=os.path.basename,
)
def test_stl_and_obj_files_same_numbers_as_trimesh_load(path: str) -> None:
    """From the file: robodesc's readers and merge give trimesh.load's numbers."""
    if not os.path.isfile(path):
        pytest.skip(f"{path} is not installed")
    vertices, faces = read_merged(path)
    expected = _trimesh_props(trimesh.load(path, force="mesh"))
    if path.endswith(".dae"):  # tests/usd/data has no DAE; kept for a reader change
        return
    _assert_same(path, solid(vertices, faces), expected, rel=1e-9)


def test_collada_agrees_to_float32() -> None:
    """pycollada (trimesh's COLLADA reader) keeps float32 coordinates; robodesc reads float64."""
    path = _corpus("robots/romeo_description/meshes/V1/visual/Torso.dae")
    vertices, faces = read_merged(path)
    _assert_same(path, solid(vertices, faces), _trimesh_props(trimesh.load(path, force="mesh")), rel=1e-6)


def test_closed_mesh_trimesh_calls_open_is_closed() -> None:
    """panda's link2.dae is closed, but trimesh keeps vertices apart by their normals (merge_norm
    is off by default), so it sees open seams and takes the hull. robodesc merges by position."""
    path = _corpus("robots/panda_description/meshes/visual/link2.dae")
    assert trimesh.load(path, force="mesh").is_watertight is False
    vertices, faces = read_merged(path)
    found = solid(vertices, faces)
    assert found.watertight
    hull = trimesh.Trimesh(vertices, faces, process=False).convex_hull
    assert found.volume < hull.volume  # a concave link: its own volume, not the hull's


def test_merge_rounds_to_1e8_as_trimesh() -> None:
    # Two triangles sharing an edge whose ends differ by less than 5e-9 (and by the sign of zero).
    vertices = np.array(
        [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-0.0, 1e-10, 0.0],
            [1.0 + 3e-9, 0.0, 0.0],
            [1.0, 1.0, 2e-8],
        ]
    )
    faces = np.array([[0, 1, 2], [3, 5, 4]])
    merged, new_faces = merge_vertices(vertices, faces)
    mesh = trimesh.Trimesh(vertices, faces, process=True)
    assert len(merged) == len(mesh.vertices) == 4
    assert np.array_equal(merged, mesh.vertices) and np.array_equal(new_faces, mesh.faces)


def test_merge_drops_non_finite_faces_and_unused_vertices() -> None:
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [np.nan, 0, 0], [5, 5, 5]], dtype=float)
    merged, faces = merge_vertices(vertices, np.array([[0, 1, 2], [0, 1, 3]]))
    assert merged.tolist() == [[0, 0, 0], [1, 0, 0], [0, 1, 0]] and faces.tolist() == [[0, 1, 2]]


def test_watertight_means_every_edge_in_two_faces() -> None:
    box = trimesh.creation.box()
    faces = np.asarray(box.faces, dtype=np.int64)
    assert is_watertight(faces)
    assert not is_watertight(faces[1:])  # one triangle gone
    assert not is_watertight(np.vstack([faces, faces[:2]]))  # an edge in four faces
    assert not is_watertight(np.zeros((0, 3), dtype=np.int64))


def test_inside_out_and_mirrored_give_positive_volume() -> None:
    box = trimesh.creation.box(extents=(1.0, 2.0, 3.0))
    v, f = np.asarray(box.vertices), np.asarray(box.faces, dtype=np.int64)
    for found in (solid(v, f[:, ::-1]), solid(v * np.array([-1.0, 1.0, 1.0]), f)):
        assert found.volume == pytest.approx(6.0, rel=1e-12)
        assert np.diag(found.tensor) == pytest.approx([6 * 13 / 12, 6 * 10 / 12, 6 * 5 / 12], rel=1e-12)


def test_mjcf_compile_imports_neither_trimesh_nor_scipy(tmp_path: Path) -> None:
    """Mesh-derived inertia on a closed STL robot costs no trimesh (over a second) nor scipy."""
    urdf = tmp_path / "r.urdf"
    mesh = os.path.join(ROOT, "examples", "urdf", "meshes", "finger.stl")
    urdf.write_text(
        f'<robot name="r"><link name="a"><inertial><mass value="1"/></inertial>'
        f'<collision><geometry><mesh filename="{mesh}"/></geometry></collision></link></robot>'
    )
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    # The CLI leaves through os._exit: -X importtime's report is what tells which modules it loaded.
    cmd = [sys.executable, "-X", "importtime", "-m", "robodesc", "compile", str(urdf), "-t", "mjcf"]
    out = subprocess.run(
        [*cmd, "-o", str(tmp_path / "o" / "robot.xml"), "--no-validate", "-q"], env=env, capture_output=True, text=True
    )
    assert out.returncode == 0, out.stderr[-2000:]
    loaded = {line.rsplit("|", 1)[1].strip() for line in out.stderr.splitlines() if line.startswith("import time:")}
    assert "robodesc.meshes.mass" in loaded
    assert not {m for m in loaded if m.split(".")[0] in ("trimesh", "scipy")}
    assert "fullinertia" in (tmp_path / "o" / "robot.xml").read_text()
