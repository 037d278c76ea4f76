"""The spawn on uneven ground (emit/common/spawn_spot.py): a legged robot whose stance would put one
foot on a bump is moved to the nearest spot where the ground under its feet is level, says so, and
stands there in MuJoCo; a --spawn given is kept, with a warning."""

from __future__ import annotations

import math
from pathlib import Path

import mujoco
import numpy as np
import pytest
import trimesh

from robodesc.api import compile_to_mjcf
from robodesc.emit.common.spawn_spot import LEVEL
from robodesc.emit.common.stance import choose_stance, lowest_collider, shape_low_point
from robodesc.emit.common.world import place_world
from robodesc.frontends.load import load_source
from robodesc.frontends.world import load_world
from robodesc.ir.diagnostics import Findings
from robodesc.ir.rigid import link_frames, pose_frame
from robodesc.meshes.data import MeshCache
from robodesc.options import build_options
from tests.conftest import EXAMPLES
from tests.worlds.test_heightfield import merged, slab

QUADRUPED = EXAMPLES / "quadruped.yaml"
BUMP = 0.1  # m


@pytest.fixture
def bumpy(tmp_path: Path) -> Path:
    """A 4 x 4 m floor (top at z = 0) with a 10 cm block under the example quadruped's front left foot
    when it stands at the origin (its feet at x 0.05 and -0.35, y ±0.18)."""
    v, f = merged(slab(-2, 2, -2, 2, 0.0, -0.2), slab(-0.05, 0.25, 0.05, 0.35, BUMP, -0.2))
    path = tmp_path / "bumpy.stl"
    trimesh.Trimesh(v, f, process=False).export(path)
    return path


def _feet_ground(placed: object, spawn: tuple[float, ...]) -> list[float]:
    robot = load_source(str(QUADRUPED), build_options({}).load, Findings())
    stance = choose_stance(robot, None)
    frames = link_frames(robot, stance.positions)
    out = []
    for leg in stance.legs:
        link = robot.link(leg.foot)
        sole = link.collisions[lowest_collider(link, frames[leg.foot], MeshCache())]
        point = shape_low_point(sole.geometry, frames[leg.foot] @ pose_frame(sole.origin))
        assert point is not None
        x, y, _ = point
        z = placed.ground_height(spawn[0] + x, spawn[1] + y)  # type: ignore[attr-defined]
        assert z is not None
        out.append(z)
    return out


def _placed(terrain: Path, spawn: tuple[float, ...] | None = None) -> tuple[object, Findings]:
    opts = build_options({"terrain": str(terrain)})
    findings = Findings()
    robot = load_source(str(QUADRUPED), opts.load, findings)
    world = load_world(opts.world, findings)
    assert world is not None
    return place_world(robot, world, findings, spawn=spawn), findings


def test_the_spawn_moves_off_the_bump(bumpy: Path) -> None:
    placed, findings = _placed(bumpy)
    spawn = placed.spawn  # type: ignore[attr-defined]
    assert max(_feet_ground(placed, (0.0, 0.0))) - min(_feet_ground(placed, (0.0, 0.0))) == pytest.approx(BUMP)
    ground = _feet_ground(placed, spawn)
    assert max(ground) - min(ground) <= LEVEL
    moved = math.hypot(spawn[0], spawn[1])
    assert 0.0 < moved < 0.4  # the nearest level spot: past the block's edge, not across the floor
    (note,) = [f for f in findings if f.code == "world-spawn-moved"]
    assert "differs by 10.0 cm" in note.message and f"({spawn[0]:.3g}, {spawn[1]:.3g})" in note.message


def test_a_given_spawn_is_kept_with_a_warning(bumpy: Path) -> None:
    placed, findings = _placed(bumpy, spawn=(0.0, 0.0))
    assert placed.spawn == (0.0, 0.0)  # type: ignore[attr-defined]
    (warning,) = [f for f in findings if f.code == "world-spawn-uneven"]
    assert "--spawn is kept" in warning.message


def test_level_ground_keeps_the_spawn(tmp_path: Path) -> None:
    v, f = slab(-2, 2, -2, 2, 0.0, -0.2)
    path = tmp_path / "flat.stl"
    trimesh.Trimesh(v, f, process=False).export(path)
    placed, findings = _placed(path)
    assert placed.spawn == (0.0, 0.0)  # type: ignore[attr-defined]
    assert not [f for f in findings if f.code.startswith("world-spawn")]


def test_it_stands_where_it_was_moved(bumpy: Path, tmp_path: Path) -> None:
    """In MuJoCo, from the home keyframe for 1 s: upright (before the move it rested on the bump)."""
    compile_to_mjcf(str(QUADRUPED), str(tmp_path / "robot.xml"), terrain=str(bumpy))
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    for _ in range(int(1.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
    up = float(data.xmat[1].reshape(3, 3)[2, 2])
    assert math.degrees(math.acos(min(1.0, up))) < 3.0
    assert np.all(np.isfinite(data.qpos))
