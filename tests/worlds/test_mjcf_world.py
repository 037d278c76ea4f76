"""A world in MJCF (emit/mjcf/world.py): the terrain as an hfield MuJoCo reads at the mesh's heights,
the world's physics, the robot spawned on the ground under its feet, standing there."""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pytest

from robodesc.api import compile_to_mjcf
from robodesc.cli import main
from robodesc.frontends.world import load_world
from robodesc.frontends.world.options import WorldOptions
from robodesc.ir.diagnostics import Findings
from robodesc.meshes.data import build_mesh
from tests.conftest import EXAMPLES, SPIRIT_XACRO, WORLDS
from tests.mjcf.helpers import stand_from_home

QUADRUPED = EXAMPLES / "quadruped.yaml"


def _stand(scene: Path, seconds: float) -> tuple[float, np.ndarray]:
    return stand_from_home(scene, seconds)


def _ground(model: mujoco.MjModel, data: mujoco.MjData, x: float, y: float) -> float:
    """The world's surface under (x, y) as MuJoCo collides it: a ray against the world body's geoms."""
    geomid = np.array([-1], dtype=np.int32)
    # Group 0 only: the terrain (the robot's colliders are group 3, its visuals 2).
    groups = np.array([1, 0, 0, 0, 0, 0], dtype=np.uint8)
    dist = mujoco.mj_ray(model, data, np.array([x, y, 10.0]), np.array([0.0, 0.0, -1.0]), groups, 1, -1, geomid)
    assert dist >= 0, (x, y)
    return 10.0 - dist


@pytest.mark.parametrize("name", ["step_20cm", "slope_20", "rough_25cm"])
def test_hfield_heights_are_the_mesh_heights(name: str, tmp_path: Path) -> None:
    out = tmp_path / "robot.xml"
    result = compile_to_mjcf(str(QUADRUPED), str(out), world=str(WORLDS / name / f"{name}.world"))
    (note,) = [f for f in result.findings if f.code == "world-heightfield"]
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert model.opt.timestep == 0.001 and model.nhfield == 1
    # The mesh's top vertices (the top of a wall where two share x, y), placed as the world places
    # the terrain model, nudged 1 mm inside the terrain's edge (a ray on the very edge may miss it).
    world = load_world(WorldOptions(file=str(WORLDS / name / f"{name}.world")), Findings())
    assert world is not None
    offset = np.array(world.bodies[0].pose.xyz)
    mesh = build_mesh(str(WORLDS / name / f"{name}.stl"), None)
    points = np.frombuffer(mesh.points, dtype=np.float32).reshape(-1, 3).astype(np.float64)
    tops: dict[tuple[float, float], float] = {}
    for x, y, z in points:
        key = (round(x, 6), round(y, 6))
        tops[key] = max(tops.get(key, -np.inf), z)
    low, high = points[:, :2].min(axis=0) + 1e-3, points[:, :2].max(axis=0) - 1e-3
    keys = sorted(tops)
    rng = np.random.default_rng(0)
    worst = 0.0
    for i in rng.choice(len(keys), size=min(60, len(keys)), replace=False):
        x, y = np.clip(keys[i], low, high)
        worst = max(worst, abs(_ground(model, data, x + offset[0], y + offset[1]) - (tops[keys[i]] + offset[2])))
    # rough_25cm's vertices sit between grid points: the reported error bounds what MuJoCo sees.
    bound = max(2e-3, 1.05 * float(note.message.split("error at the mesh's vertices ")[1].split(" mm")[0]) / 1000)
    assert worst <= bound


@pytest.mark.parametrize("name", ["flat", "step_20cm", "slope_20"])
def test_the_quadruped_stands_on_the_world(name: str, tmp_path: Path) -> None:
    out = tmp_path / "robot.xml"
    compile_to_mjcf(str(QUADRUPED), str(out), world=str(WORLDS / name / f"{name}.world"), spawn=(0.5, 0.0))
    upright, position = _stand(tmp_path / "scene.xml", 2.0)
    assert upright > 0.99
    assert position[:2] == pytest.approx((0.5, 0.0), abs=0.05)
    assert 0.25 < position[2] < 0.45  # on the terrain's top at z = 0 (Quad-SDK's -0.1 pose + 0.1 slab)


def test_spirit_stands_on_the_step_world_by_the_cli(tmp_path: Path) -> None:
    if not SPIRIT_XACRO.exists():
        pytest.skip("corpus not present")
    out = tmp_path / "robot.xml"
    world = WORLDS / "step_20cm" / "step_20cm.world"
    code = main(["compile", str(SPIRIT_XACRO), "-t", "mjcf", "-o", str(out), "--world", str(world), "-q"])
    assert code == 0
    upright, position = _stand(tmp_path / "scene.xml", 2.0)
    assert upright > 0.99 and position[2] > 0.25


def test_a_height_image_terrain(tmp_path: Path) -> None:
    from PIL import Image

    # A 16-bit ramp: black at -x, white at +x, 2 m by 1 m, white 0.5 m high.
    ramp = np.tile(np.linspace(0, 65535, 21).round().astype(np.uint16), (11, 1))
    image = tmp_path / "ramp.png"
    Image.fromarray(ramp).save(image)
    out = tmp_path / "robot.xml"
    compile_to_mjcf(str(QUADRUPED), str(out), terrain=str(image), terrain_size=(2.0, 1.0, 0.5), spawn=(0.0, 0.0, 1.0))
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    for x in (-0.8, -0.25, 0.3, 0.9):
        assert _ground(model, data, x, 0.2) == pytest.approx((x + 1.0) / 2.0 * 0.5, abs=1e-4)


def test_a_robot_only_target_refuses_a_world(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    world = WORLDS / "flat" / "flat.world"
    out = tmp_path / "robot.urdf"
    code = main(["compile", str(QUADRUPED), "-t", "urdf", "-o", str(out), "--world", str(world)])
    assert code == 2 and not out.exists()
    assert "cannot hold a world" in capsys.readouterr().err


def test_bad_spawn_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    world = WORLDS / "flat" / "flat.world"
    code = main(
        [
            "compile",
            str(QUADRUPED),
            "-t",
            "mjcf",
            "-o",
            str(tmp_path / "r.xml"),
            "--world",
            str(world),
            "--spawn",
            "1,nan",
        ]
    )
    assert code == 2 and "--spawn" in capsys.readouterr().err
