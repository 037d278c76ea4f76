"""Convex decomposition computed by robodesc (CoACD, cached by content) for MJCF and SDF, and the
exact-triangle modes for static links (issue 25).

The mesh is an L-shaped prism (20 triangles): concave, so CoACD gives two parts in well under a
second. CoACD is never imported here: its library breaks Drake's parser in the same process
(meshes/decompose.py), so it is looked up by its package metadata.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

import robodesc
from robodesc.ir.diagnostics import ConfigError, Severity
from robodesc.meshes import decompose as dec
from robodesc.pipeline import CompileResult

ELL = Path(__file__).resolve().parent / "data" / "ell.obj"
# The L's outline in x-y (m), extruded 0.03 m along z: what the parts must cover together.
ELL_EXTENT = ((0.0, 0.0, 0.0), (0.1, 0.1, 0.03))

needs_coacd = pytest.mark.skipif(dec.coacd_version() is None, reason="CoACD is not installed (robodesc[decompose])")

INERTIA = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'


def _robot(tmp_path: Path) -> Path:
    """world -(fixed)- table -(revolute)- arm; every link collides with the L."""
    shutil.copy(ELL, tmp_path / "ell.obj")
    mesh = '<collision><origin xyz="0 0 0.1"/><geometry><mesh filename="ell.obj"/></geometry></collision>'
    path = tmp_path / "r.urdf"
    path.write_text(
        f"""<robot name="r">
  <link name="world"/>
  <link name="table">{INERTIA}{mesh}</link>
  <link name="arm">{INERTIA}{mesh}</link>
  <joint name="weld" type="fixed"><parent link="world"/><child link="table"/></joint>
  <joint name="hinge" type="revolute"><parent link="table"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""
    )
    return path


def _compile(tmp_path: Path, target: str, out: str, **options: object) -> CompileResult:
    options.setdefault("collision_approximation", "convexDecomposition")
    if target != "usd":  # USD leaves the decomposition to PhysX
        options.setdefault("decomposition_cache", str(tmp_path / "cache"))
    return robodesc.compile_to(str(_robot(tmp_path)), target, str(tmp_path / out), **options)


def _codes(result: CompileResult) -> dict[str, str]:
    return {f.code: f.message for f in result.findings}


@needs_coacd
def test_mjcf_writes_each_part_as_a_geom_mujoco_loads(tmp_path: Path) -> None:
    import mujoco

    # The welded table kept as its own body (MJCF fuses fixed links by default): its parts are counted there.
    result = _compile(tmp_path, "mjcf", "mj/robot.xml", merge_fixed=False)
    assert result.validation is not None  # validated (a failure raises)
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "mj" / "robot.xml"))
    arm = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "arm")
    geoms = [g for g in range(model.ngeom) if model.geom_bodyid[g] == arm and model.geom_group[g] == 3]
    assert len(geoms) == 2
    assert all(model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH for g in geoms)
    # The parts cover the L: together they span its extent (in the geom frame, 0.1 m up).
    points = np.concatenate([_part_points(model, g) for g in geoms])
    np.testing.assert_allclose(points.min(axis=0), np.add(ELL_EXTENT[0], (0, 0, 0.1)), atol=1e-3)
    np.testing.assert_allclose(points.max(axis=0), np.add(ELL_EXTENT[1], (0, 0, 0.1)), atol=1e-3)
    # The table (static: a body without a joint under the world) gets its parts too.
    table = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "table")
    assert sum(1 for g in range(model.ngeom) if model.geom_bodyid[g] == table and model.geom_group[g] == 3) == 2


def _part_points(model: object, geom: int) -> np.ndarray:
    """A mesh geom's vertices in its body's frame."""
    m = model  # type: ignore[assignment]
    mesh = m.geom_dataid[geom]  # type: ignore[attr-defined]
    start, count = m.mesh_vertadr[mesh], m.mesh_vertnum[mesh]  # type: ignore[attr-defined]
    local = m.mesh_vert[start : start + count]  # type: ignore[attr-defined]
    import mujoco

    rot = np.zeros(9)
    mujoco.mju_quat2Mat(rot, m.geom_quat[geom])  # type: ignore[attr-defined]
    return np.asarray(local @ rot.reshape(3, 3).T + m.geom_pos[geom])  # type: ignore[attr-defined]


@needs_coacd
def test_sdf_writes_each_part_as_a_collision_drake_reads(tmp_path: Path) -> None:
    pytest.importorskip("pydrake")
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.systems.framework import DiagramBuilder

    result = _compile(tmp_path, "sdf", "sd/robot.sdf", version="1.11")
    assert result.validation is not None  # Drake's parser read it and the numbers matched (else it raises)
    text = (tmp_path / "sd" / "robot.sdf").read_text()
    assert text.count('<mesh optimization="convex_hull">') == 4  # two parts on each of two links
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlantSceneGraph(builder, 0.0)
    Parser(plant).AddModels(str(tmp_path / "sd" / "robot.sdf"))
    plant.Finalize()
    assert len(plant.GetCollisionGeometriesForBody(plant.GetBodyByName("arm"))) == 2
    parts = sorted((tmp_path / "sd" / "meshes").glob("ell_part*.obj"))
    assert len(parts) == 2


@needs_coacd
def test_the_second_compile_reads_the_cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    first = _compile(tmp_path, "mjcf", "a/robot.xml")
    assert "CoACD" in _codes(first)["decomposition"]

    def no_coacd(*args: object) -> object:
        raise AssertionError("CoACD ran although the cache holds the parts")

    monkeypatch.setattr(dec, "_run_coacd", no_coacd)
    second = _compile(tmp_path, "mjcf", "b/robot.xml")
    assert "from the cache" in _codes(second)["decomposition"]
    a = sorted(p.read_bytes() for p in (tmp_path / "a" / "meshes").glob("*.obj"))
    b = sorted(p.read_bytes() for p in (tmp_path / "b" / "meshes").glob("*.obj"))
    assert a == b and len(a) == 2
    # The cache is also read without CoACD installed.
    monkeypatch.setattr(dec, "coacd_version", lambda: None)
    third = _compile(tmp_path, "sdf", "c/robot.sdf")
    assert "from the cache" in _codes(third)["decomposition"]


@needs_coacd
def test_the_parts_are_the_same_every_time(tmp_path: Path) -> None:
    data = robodesc_mesh()
    # A small search budget: the same seed must give the same parts whatever the budget.
    settings = dec.DecompositionSettings(resolution=500, preprocess_resolution=20, mcts_iterations=10, mcts_nodes=5)
    one = dec.decompose(*data, settings, str(tmp_path / "one"))
    two = dec.decompose(*data, settings, str(tmp_path / "two"))
    assert not one.cached and not two.cached and one.key == two.key
    assert len(one.parts) == len(two.parts) == 2
    for (v1, f1), (v2, f2) in zip(one.parts, two.parts, strict=True):
        assert np.array_equal(v1, v2) and np.array_equal(f1, f2)


def robodesc_mesh() -> tuple[np.ndarray, np.ndarray]:
    from robodesc.meshes.data import build_mesh

    m = build_mesh(str(ELL), None)
    points = np.frombuffer(m.points, dtype=np.float32).reshape(-1, 3).astype(np.float64)
    return points, np.frombuffer(m.face_vertex_indices, dtype=np.int32).reshape(-1, 3)


def test_without_coacd_the_mesh_is_written_whole_with_a_warning(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(dec, "coacd_version", lambda: None)
    result = _compile(tmp_path, "mjcf", "mj/robot.xml")
    assert result.validation is not None  # validated (a failure raises)
    warnings = [f for f in result.findings if f.code == "decomposition-unavailable"]
    assert len(warnings) == 1 and warnings[0].severity is Severity.WARNING  # once, not per mesh
    assert "pip install 'robodesc[decompose]'" in warnings[0].message
    text = (tmp_path / "mj" / "robot.xml").read_text()
    assert text.count('<geom type="mesh"') == 2 and "ell_part" not in text  # the whole L, hulled by MuJoCo


@needs_coacd
def test_the_time_limit_falls_back_to_the_hull(tmp_path: Path) -> None:
    result = _compile(tmp_path, "mjcf", "mj/robot.xml", decomposition_timeout=0.001)
    assert result.validation is not None  # validated (a failure raises)
    assert "longer than 0.001 s" in _codes(result)["decomposition-failed"]
    assert "ell_part" not in (tmp_path / "mj" / "robot.xml").read_text()


@needs_coacd
def test_the_parts_cap_is_said(tmp_path: Path) -> None:
    result = _compile(tmp_path, "mjcf", "mj/robot.xml", decomposition_max_parts=1)
    assert "cap of 1 convex parts" in _codes(result)["decomposition-capped"]
    assert (tmp_path / "mj" / "robot.xml").read_text().count('<geom type="mesh"') == 2  # one part per link


def test_sdf_to_standard_output_keeps_the_mesh(tmp_path: Path) -> None:
    result = robodesc.compile_to(str(_robot(tmp_path)), "sdf", None, collision_approximation="convexDecomposition")
    assert "sdf-decomposition-no-folder" in _codes(result)


def test_bad_decomposition_settings_are_refused(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="decomposition_max_parts"):
        _compile(tmp_path, "mjcf", "mj/robot.xml", decomposition_max_parts=0)


# ---- exact triangles for static links -------------------------------------------------------------


def test_usd_triangle_mesh_and_sdf_modes(tmp_path: Path) -> None:
    pytest.importorskip("pxr")
    from pxr import Usd, UsdPhysics

    result = _compile(
        tmp_path, "usd", "r.usda", collision_approximation={"table": "none", "arm": "sdf", ".*": "convexHull"}
    )
    stage = Usd.Stage.Open(str(tmp_path / "r.usda"))
    modes = {}
    for prim in stage.Traverse():
        if prim.HasAPI(UsdPhysics.MeshCollisionAPI):
            modes[str(prim.GetPath()).split("/")[2]] = UsdPhysics.MeshCollisionAPI(prim).GetApproximationAttr().Get()
            if modes[str(prim.GetPath()).split("/")[2]] == "sdf":
                assert prim.GetAttribute("physxSDFMeshCollision:sdfResolution").Get() == 256
    assert modes == {"table": "none", "arm": "sdf"}
    codes = _codes(result)
    # The table is welded to the world but still an articulation body: PhysX hulls it; it does not move.
    assert "table" in codes["usd-triangle-mesh"] and "move" not in codes["usd-triangle-mesh"]
    assert "GPU dynamics" in codes["usd-sdf-collider"] and "arm" in codes["usd-sdf-collider"]


def test_usd_triangle_mesh_on_a_moving_link_says_so(tmp_path: Path) -> None:
    pytest.importorskip("pxr")
    result = _compile(tmp_path, "usd", "r.usda", collision_approximation={"arm": "none", ".*": "convexHull"})
    assert "arm moves" in _codes(result)["usd-triangle-mesh"]


def test_mjcf_says_meshes_collide_as_hulls(tmp_path: Path) -> None:
    result = _compile(tmp_path, "mjcf", "mj/robot.xml", collision_approximation="none", merge_fixed=False)
    assert result.validation is not None  # validated (a failure raises)
    message = _codes(result)["mjcf-triangle-mesh"]
    assert "convex hull" in message and "table, arm" in message


def test_sdf_writes_the_triangle_mesh_as_given(tmp_path: Path) -> None:
    result = _compile(tmp_path, "sdf", "sd/robot.sdf", collision_approximation="none", version="1.11")
    assert result.validation is not None  # validated (a failure raises)
    text = (tmp_path / "sd" / "robot.sdf").read_text()
    assert "optimization" not in text and text.count("<uri>../ell.obj</uri>") == 2
    assert not [f for f in result.findings if "approximation" in f.code]


def test_static_links() -> None:
    from robodesc.emit.common.approximation import static_links
    from robodesc.frontends.load import load_string

    arm = load_string(
        '<robot name="a"><link name="base"/><link name="plate"/><link name="upper"/><link name="tool"/>'
        '<joint name="w" type="fixed"><parent link="base"/><child link="plate"/></joint>'
        '<joint name="j" type="revolute"><parent link="plate"/><child link="upper"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        '<joint name="t" type="fixed"><parent link="upper"/><child link="tool"/></joint></robot>'
    ).robot
    assert static_links(arm, fix_base=True) == {"base", "plate"}
    assert static_links(arm, fix_base=False) == set()


def test_gazebo_parity_leaves_the_sdf_meshes_to_gazebo(tmp_path: Path) -> None:
    result = robodesc.compile_to(str(_robot(tmp_path)), "sdf", str(tmp_path / "r.sdf"), preset="gazebo_parity")
    assert not [f for f in result.findings if "approximation" in f.code]
    assert "optimization" not in (tmp_path / "r.sdf").read_text()


def test_the_command_line_takes_snake_case_modes(tmp_path: Path) -> None:
    from robodesc.cli import main

    out = tmp_path / "r.usda"
    argv = ["compile", str(_robot(tmp_path)), "-t", "usd", "-o", str(out), "-q"]
    assert main([*argv, "--collision-approximation", "arm=convex_decomposition"]) == 0
    assert out.read_text().count('physics:approximation = "convexDecomposition"') == 1
