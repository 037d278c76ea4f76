"""A world file as the only input (``robodesc compile W.world -t mjcf|usd|sdf -o OUT``): its static
models, cords and physics with no robot, chosen by content (an ``<sdf>`` holding a ``<world>``), each
output loaded in its consumer."""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pytest
from pxr import Usd, UsdGeom, UsdPhysics

from robodesc.api import compile_to
from robodesc.cli import main
from tests.conftest import ROOT, WORLDS

STEP = WORLDS / "step_20cm" / "step_20cm.world"
CORDS = ROOT / "examples" / "worlds" / "underbrush.yaml"


def _ray_down(model: mujoco.MjModel, data: mujoco.MjData, x: float, y: float) -> float:
    geomid = np.array([-1], dtype=np.int32)
    dist = mujoco.mj_ray(model, data, np.array([x, y, 10.0]), np.array([0.0, 0.0, -1.0]), None, 1, -1, geomid)
    assert dist >= 0, (x, y)
    return 10.0 - dist


def test_mjcf_world_alone(tmp_path: Path) -> None:
    out = tmp_path / "world.xml"
    result = compile_to(str(STEP), "mjcf", str(out))
    assert result.world == "default" and result.files == {"mjcf": str(out)}
    assert result.validation is not None and result.validation.ok
    model = mujoco.MjModel.from_xml_path(str(out))
    assert model.nbody == 1 and model.nq == 0  # the world body alone: no robot
    assert model.nhfield == 1 and model.opt.timestep == pytest.approx(0.001)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    # The step rises 20 cm between x = 3 and 3.5 m (the heightfield of the terrain's mesh).
    assert _ray_down(model, data, 1.0, 0.0) == pytest.approx(0.0, abs=1e-6)
    assert _ray_down(model, data, 5.0, 0.0) == pytest.approx(0.2, abs=1e-6)
    assert not list(tmp_path.glob("robot*.xml"))


def test_mjcf_world_alone_with_cords(tmp_path: Path) -> None:
    out = tmp_path / "world.xml"
    compile_to(str(STEP), "mjcf", str(out), cords=str(CORDS))
    model = mujoco.MjModel.from_xml_path(str(out))
    assert model.nbody > 1 and all(model.jnt_type == mujoco.mjtJoint.mjJNT_BALL)


def test_usd_world_alone(tmp_path: Path) -> None:
    out = tmp_path / "world.usda"
    result = compile_to(str(STEP), "usd", str(out))
    assert result.validation is not None and result.validation.ok
    stage = Usd.Stage.Open(str(out))
    assert not any(p.HasAPI(UsdPhysics.ArticulationRootAPI) for p in stage.Traverse())
    assert stage.GetPrimAtPath("/World/PhysicsScene").GetAttribute("physxScene:timeStepsPerSecond").Get() == 1000
    terrain = stage.GetPrimAtPath("/World/mesh_terrain/collision")
    assert terrain.IsA(UsdGeom.Mesh) and UsdPhysics.MeshCollisionAPI(terrain).GetApproximationAttr().Get() == "none"
    assert not (tmp_path / "world_world.usda").exists()


def test_sdf_world_alone(tmp_path: Path) -> None:
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    out = tmp_path / "world.sdf"
    result = compile_to(str(STEP), "sdf", str(out))
    assert result.validation is not None and result.validation.ok
    text = out.read_text()
    assert "<max_step_size>0.001</max_step_size>" in text and "step_20cm.stl" in text
    plant = MultibodyPlant(0.0)
    (instance,) = Parser(plant).AddModels(str(out))
    assert plant.GetModelInstanceName(instance) == "mesh_terrain"


def test_world_alone_cli(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["compile", str(STEP), "-t", "mjcf", "-o", str(tmp_path / "world.xml")]) == 0
    assert "the world 'default' alone (no robot)" in capsys.readouterr().err
    # URDF holds no world; a world as the input is not also given with --world.
    assert main(["compile", str(STEP), "-t", "urdf", "-o", str(tmp_path / "w.urdf")]) == 2
    assert "cannot hold a world without a robot" in capsys.readouterr().err
    assert main(["compile", str(STEP), "-t", "mjcf", "-o", str(tmp_path / "w.xml"), "--spawn", "1,0"]) == 2
    assert "the input is a world" in capsys.readouterr().err
    assert not (tmp_path / "w.urdf").exists() and not (tmp_path / "w.xml").exists()
