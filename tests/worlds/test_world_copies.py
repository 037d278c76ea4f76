"""Several copies of one robot in one world (``--spawn`` given more than once): each copy on the
ground under its own feet, N copies weighing N times the robot, in MuJoCo (MJCF's <attach>), usd-core
and PhysX (a payload per copy) and Drake (a model per copy). PhysX stands copies on the Isaac folder's world stage
(test_isaac_world.py), the same payloads."""

from __future__ import annotations

from pathlib import Path

import mujoco
import pytest
from pxr import Usd, UsdPhysics

from robodesc.api import compile_to_mjcf, compile_to_sdf, compile_to_usd
from robodesc.cli import main
from tests.conftest import EXAMPLES, WORLDS

QUADRUPED = EXAMPLES / "quadruped.yaml"
STEP = WORLDS / "step_20cm" / "step_20cm.world"
# The third copy stands on the step's top, 0.2 m above the others (the step rises at x = 3.0-3.5 m).
SPAWNS = [(0.0, 0.0), (1.0, 0.5), (5.0, 0.0)]
MASS = 15.4  # kg, the example quadruped


def test_mjcf_copies_stand_at_their_spawns(tmp_path: Path) -> None:
    # Validated by MuJoCo in test_spawn_repeated_on_the_command_line; here the numbers.
    compile_to_mjcf(str(QUADRUPED), str(tmp_path / "robot.xml"), world=str(STEP), spawn=SPAWNS, validate=False)
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml"))
    assert float(model.body_mass.sum()) == pytest.approx(3 * MASS)
    assert model.nu == 3 * 12 and model.nq == 3 * 19
    # The robot's options reach every copy (an attached model's <option> does not carry over).
    assert model.opt.cone == mujoco.mjtCone.mjCONE_ELLIPTIC and model.opt.impratio == 100.0
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home"))
    for _ in range(int(0.5 / model.opt.timestep)):
        mujoco.mj_step(model, data)
    roots = [data.xpos[model.body(f"robot_{i}/trunk").id].copy() for i in range(3)]
    for (x, y), root in zip(SPAWNS, roots, strict=True):
        assert root[:2] == pytest.approx((x, y), abs=0.02)  # standing where it was put
    # Same stance, same height over the ground under it: the step's copy 0.2 m higher.
    assert roots[1][2] == pytest.approx(roots[0][2], abs=2e-3)
    assert roots[2][2] - roots[0][2] == pytest.approx(0.2, abs=2e-3)
    assert 0.3 < roots[0][2] < 0.4


def test_usd_copies_are_payloads(tmp_path: Path) -> None:
    out = tmp_path / "quadruped.usda"
    compile_to_usd(str(QUADRUPED), str(out), world=str(STEP), spawn=SPAWNS)
    stage = Usd.Stage.Open(str(tmp_path / "quadruped_world.usda"))
    roots = [p for p in stage.Traverse() if p.HasAPI(UsdPhysics.ArticulationRootAPI)]
    assert [str(p.GetPath()) for p in roots] == [f"/World/quadruped_{i}/trunk" for i in range(3)]
    mass = sum(UsdPhysics.MassAPI(p).GetMassAttr().Get() for p in stage.Traverse() if p.HasAPI(UsdPhysics.MassAPI))
    assert mass == pytest.approx(3 * MASS, rel=1e-6)


def test_sdf_copies_are_models(tmp_path: Path) -> None:
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    out = tmp_path / "quadruped.sdf"
    compile_to_sdf(str(QUADRUPED), str(out), world=str(STEP), spawn=SPAWNS)
    plant = MultibodyPlant(0.0)
    Parser(plant).AddModels(str(out))
    plant.Finalize()
    copies = [plant.GetModelInstanceByName(f"quadruped_{i}") for i in range(3)]
    context = plant.CreateDefaultContext()
    # The copies only: Drake gives the static terrain's link a mass of its own.
    assert plant.CalcTotalMass(context, copies) == pytest.approx(3 * MASS)
    trunks = [plant.GetBodyByName("trunk", m).EvalPoseInWorld(context).translation() for m in copies]
    assert [tuple(t[:2]) for t in trunks] == pytest.approx(SPAWNS)
    assert trunks[2][2] - trunks[0][2] == pytest.approx(0.2, abs=1e-6)


def test_spawn_repeated_on_the_command_line(tmp_path: Path) -> None:
    out = tmp_path / "robot.xml"
    argv = ["compile", str(QUADRUPED), "-t", "mjcf", "-o", str(out), "--world", str(STEP), "-q"]
    assert main([*argv, "--spawn", "0,0", "--spawn", "1,0.5"]) == 0
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml"))
    assert float(model.body_mass.sum()) == pytest.approx(2 * MASS)


def test_spawn_without_a_world_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["compile", str(QUADRUPED), "-t", "mjcf", "-o", str(tmp_path / "robot.xml")]
    assert main([*argv, "--spawn", "0,0", "--spawn", "1,0"]) == 2
    assert "--spawn places the robot in a world" in capsys.readouterr().err
    assert not (tmp_path / "robot.xml").exists()
