"""The Isaac folder's world (emit/isaac/world.py): the world stage beside the robot, the ground alone
for Isaac Lab's terrain importer, and the Isaac Lab module's TerrainImporterCfg, SimulationCfg and
init_state. Isaac Lab itself is not installed here: the module runs against stand-ins with the
fields of Isaac Lab 3's TerrainImporterCfg and SimulationCfg."""

from __future__ import annotations

import ast
import json
import math
import os
import runpy
import subprocess
import sys
import types
from pathlib import Path
from typing import Any

import pytest
from pxr import Usd, UsdGeom, UsdPhysics

import robodesc
from robodesc.validation.physx_python import physx_python
from tests.conftest import EXAMPLES, WORLDS
from tests.worlds.physx_scripts import positions

QUADRUPED = EXAMPLES / "quadruped.yaml"
STEP = WORLDS / "step_20cm" / "step_20cm.world"


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> robodesc.CompileResult:
    out = tmp_path_factory.mktemp("isaac_world") / "quadruped"
    # The folder's own validation is the Isaac tests' (tests/isaac); here, the world's files.
    return robodesc.compile_for_isaac_sim(str(QUADRUPED), out, world=str(STEP), spawn=(0.5, 0.0), validate=False)


def _run_module(path: str, monkeypatch: pytest.MonkeyPatch) -> dict[str, Any]:
    """Run the module with stand-ins for the Isaac Lab classes it builds; return what each was given."""
    made: dict[str, Any] = {}

    def recorder(name: str) -> Any:
        def make(**kw: Any) -> Any:
            made[name] = kw
            return types.SimpleNamespace(**kw)

        return make

    class ArticulationCfg:
        class InitialStateCfg:
            rot = (0.0, 0.0, 0.0, 1.0)  # Isaac Lab 3's identity (x, y, z, w)

            def __init__(self, **kw: Any) -> None:
                made["init_state"] = kw

        def __init__(self, **kw: Any) -> None:
            made["articulation"] = kw

    sim = types.SimpleNamespace(
        UsdFileCfg=lambda **kw: kw,
        ArticulationRootPropertiesCfg=lambda **kw: kw,
        SimulationCfg=recorder("sim"),
    )
    fakes = {
        "isaaclab": types.ModuleType("isaaclab"),
        "isaaclab.sim": sim,
        "isaaclab.actuators": types.SimpleNamespace(ImplicitActuatorCfg=lambda **kw: kw),
        "isaaclab.assets": types.SimpleNamespace(ArticulationCfg=ArticulationCfg),
        "isaaclab.terrains": types.SimpleNamespace(TerrainImporterCfg=recorder("terrain")),
        "isaaclab_newton": types.ModuleType("isaaclab_newton"),
        "isaaclab_newton.physics": types.SimpleNamespace(
            MJWarpSolverCfg=recorder("mjwarp"), NewtonCfg=recorder("newton")
        ),
    }
    for name, module in fakes.items():
        monkeypatch.setitem(sys.modules, name, module)
    runpy.run_path(path)
    return made


def test_isaac_folder_world_files(folder: robodesc.CompileResult) -> None:
    world = Path(folder.files["world"])
    terrain = Path(folder.files["terrain"])
    assert world.name == "quadruped_world.usda" and terrain.name == "quadruped_terrain.usda"
    stage = Usd.Stage.Open(str(world))
    # The robot's own USD, composed in at its spawn on the step's lower side (x = 0.5 m).
    robot = stage.GetPrimAtPath("/World/quadruped")
    assert robot.IsValid() and any(p.HasAPI(UsdPhysics.ArticulationRootAPI) for p in Usd.PrimRange(robot))
    spawn = UsdGeom.Xformable(robot).ComputeLocalToWorldTransform(0).ExtractTranslation()
    assert (spawn[0], spawn[1]) == pytest.approx((0.5, 0.0))
    assert UsdPhysics.Scene(stage.GetPrimAtPath("/World/PhysicsScene"))
    # The terrain file: the ground and its friction, no scene and no robot (Isaac Lab makes the scene).
    ground = Usd.Stage.Open(str(terrain))
    kinds = {p.GetTypeName() for p in ground.Traverse()}
    assert "Mesh" in kinds and "PhysicsScene" not in kinds
    assert not any(p.HasAPI(UsdPhysics.ArticulationRootAPI) for p in ground.Traverse())
    mesh = next(p for p in ground.Traverse() if p.IsA(UsdGeom.Mesh))
    assert UsdPhysics.MeshCollisionAPI(mesh).GetApproximationAttr().Get() == "none"


def test_isaac_lab_module_world(folder: robodesc.CompileResult, monkeypatch: pytest.MonkeyPatch) -> None:
    path = folder.files["isaaclab"]
    ast.parse(Path(path).read_text())  # valid Python
    plain = runpy.run_path(path)  # without Isaac Lab: plain data, no configs
    assert plain["TERRAIN_CFG"] is None and plain["SIM_CFG"] is None
    assert Path(plain["TERRAIN_USD_PATH"]).is_file() and Path(plain["WORLD_USD_PATH"]).is_file()
    made = _run_module(path, monkeypatch)
    assert made["terrain"] == {
        "prim_path": "/World/ground",
        "terrain_type": "usd",
        "usd_path": plain["TERRAIN_USD_PATH"],
    }
    # The world's physics: Quad-SDK's 1 ms step and Earth's gravity.
    assert made["sim"]["dt"] == pytest.approx(0.001)
    assert made["sim"]["gravity"] == pytest.approx((0.0, 0.0, -9.81))
    # ... on the robot's recommended solver settings (issue 35: the elliptic cone that stands it still).
    assert made["mjwarp"]["cone"] == "elliptic" and made["newton"]["num_substeps"] == 2
    # The robot's init_state is its spawn on the terrain, as the world stage places it.
    pos = made["init_state"]["pos"]
    assert pos == pytest.approx(plain["WORLD"]["spawns"][0])
    assert (pos[0], pos[1]) == (0.5, 0.0)
    stage = Usd.Stage.Open(folder.files["world"])
    placed = UsdGeom.Xformable(stage.GetPrimAtPath("/World/quadruped")).ComputeLocalToWorldTransform(0)
    assert placed.ExtractTranslation()[2] == pytest.approx(pos[2], abs=1e-6)


def test_isaac_world_spawn_height_follows_the_terrain(tmp_path: Path) -> None:
    """The same robot spawned on the 20 cm step's top (x = 5 m) stands 0.2 m higher than below it (x = 1 m)."""
    low = robodesc.compile_for_isaac_sim(
        str(QUADRUPED), tmp_path / "low", world=str(STEP), spawn=(1.0, 0.0), validate=False
    )
    high = robodesc.compile_for_isaac_sim(
        str(QUADRUPED), tmp_path / "high", world=str(STEP), spawn=(5.0, 0.0), validate=False
    )
    z_low = runpy.run_path(low.files["isaaclab"])["ROBOT"]["init_state"]["pos"][2]
    z_high = runpy.run_path(high.files["isaaclab"])["ROBOT"]["init_state"]["pos"][2]
    assert z_high - z_low == pytest.approx(0.2, abs=1e-6)


def test_isaac_flat_plane_world_is_isaac_labs_plane(tmp_path: Path) -> None:
    world = tmp_path / "plane.world"
    world.write_text(
        '<sdf version="1.6"><world name="w"><physics type="ode"><max_step_size>0.005</max_step_size></physics>'
        '<model name="ground"><static>true</static><link name="l"><collision name="c"><geometry><plane>'
        "<normal>0 0 1</normal></plane></geometry></collision></link></model></world></sdf>"
    )
    result = robodesc.compile_for_isaac_sim(str(QUADRUPED), tmp_path / "out", world=str(world), validate=False)
    module = runpy.run_path(result.files["isaaclab"])
    assert module["WORLD"]["terrain_type"] == "plane" and module["TERRAIN_USD_PATH"] is None
    assert "terrain" not in result.files and module["WORLD"]["dt"] == pytest.approx(0.005)
    assert math.isclose(module["ROBOT"]["init_state"]["pos"][0], 0.0)


@pytest.mark.skipif(physx_python() is None, reason="no PhysX interpreter (tests/consumers/run.sh builds one)")
def test_physx_stands_two_copies_on_the_isaac_world_stage(tmp_path: Path) -> None:
    """The folder's world stage in PhysX: two copies in the folder's stance, one on the step's top,
    stand 1 s where they were put (each settles a few millimetres onto its feet)."""
    out = tmp_path / "quadruped"
    robodesc.compile_for_isaac_sim(str(QUADRUPED), out, world=str(STEP), spawn=[(5.0, 0.0), (1.0, 0.0)], validate=False)
    spawns = runpy.run_path(str(out / "quadruped_isaaclab.py"))["WORLD"]["spawns"]
    python = physx_python()
    assert python is not None
    done = subprocess.run(
        [python, "-c", positions("ARTICULATION", "rootPosition"), str(out / "quadruped_world.usda"), "1.0"],
        capture_output=True, text=True, timeout=600, check=False, env={**os.environ},
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    roots = sorted(json.loads(done.stdout.strip().splitlines()[-1]))
    for spawn, root in zip(sorted(spawns), roots, strict=True):
        assert root[0] == pytest.approx(spawn[0], abs=0.02) and root[1] == pytest.approx(spawn[1], abs=0.02)
        assert root[2] == pytest.approx(spawn[2], abs=0.02)  # standing: neither fallen nor sunk
    assert roots[1][2] - roots[0][2] == pytest.approx(0.2, abs=0.005)
