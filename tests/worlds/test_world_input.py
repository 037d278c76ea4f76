"""Worlds read once (frontends/world): Quad-SDK's five SDF worlds, bare terrains, and bad input named
at its file and line."""

from __future__ import annotations

from pathlib import Path

import pytest

from robodesc.frontends.world import load_world
from robodesc.frontends.world.options import WorldOptions
from robodesc.ir.diagnostics import ConfigError, Findings, ParseError, UnsupportedError
from robodesc.ir.geometry import Mesh
from tests.conftest import WORLDS

NAMES = ["flat", "step_20cm", "gap_40cm", "slope_20", "rough_25cm"]


@pytest.mark.parametrize("name", NAMES)
def test_quadsdk_worlds(name: str) -> None:
    findings = Findings()
    world = load_world(WorldOptions(file=str(WORLDS / name / f"{name}.world")), findings)
    assert world is not None
    assert world.physics.step == 0.001 and world.physics.iterations == 300 and world.physics.engine == "ode"
    assert world.physics.gravity == (0.0, 0.0, -9.81)
    (terrain,) = world.bodies
    assert terrain.name == "mesh_terrain" and terrain.pose.xyz[2] == -0.1
    (collider,) = terrain.colliders
    assert isinstance(collider.shape, Mesh) and collider.shape.path is not None
    assert Path(collider.shape.path).name == f"{name}.stl"  # model:///name/name.stl beside the world
    assert collider.surface is not None and collider.surface.mu == 100 and collider.surface.mu2 == 100
    # The sun is a model Quad-SDK does not ship: a warning at the include's line, never a failure.
    (missing,) = [f for f in findings if f.code == "world-include-missing"]
    assert missing.loc is not None and missing.loc.line == 17 and "custom_sun" in missing.message


def _world(tmp_path: Path, body: str) -> Path:
    path = tmp_path / "w.world"
    path.write_text(f"<sdf version='1.9'>\n<world name='w'>\n{body}\n</world>\n</sdf>\n")
    return path


def test_static_primitives_and_dynamic_models(tmp_path: Path) -> None:
    path = _world(
        tmp_path,
        """<model name='ground'><static>true</static><link name='l'><collision name='c'><geometry>
        <plane><normal>0 0 1</normal><size>10 10</size></plane></geometry></collision></link></model>
        <model name='block'><static>1</static><pose>1 0 0.1 0 0 0.5</pose><link name='l'><pose>0 0 0.05 0 0 0</pose>
        <collision name='c'><geometry><box><size>0.4 0.4 0.1</size></box></geometry>
        <surface><friction><ode><mu>0.3</mu></ode></friction></surface></collision></link></model>
        <model name='ball'><link name='l'/></model>""",
    )
    findings = Findings()
    world = load_world(WorldOptions(file=str(path)), findings)
    assert world is not None
    assert [b.name for b in world.bodies] == ["ground", "block"]
    block = world.bodies[1].colliders[0]
    assert block.origin.xyz == pytest.approx((0, 0, 0.05)) and block.surface is not None and block.surface.mu == 0.3
    (dynamic,) = [f for f in findings if f.code == "world-dynamic-model"]
    assert dynamic.element == "model 'ball'" and dynamic.loc is not None and dynamic.loc.line == 8


@pytest.mark.parametrize(
    ("body", "error", "line"),
    [
        ("<model name='m'><static>true</static><pose>0 0 nan 0 0 0</pose></model>", ParseError, 3),
        ("<model name='m'><static>true</static><pose>0 0 0</pose></model>", ParseError, 3),
        ("<model name='m'><static>true</static><pose relative_to='x'>0 0 0 0 0 0</pose></model>", UnsupportedError, 3),
    ],
)
def test_bad_worlds_name_the_line(tmp_path: Path, body: str, error: type[Exception], line: int) -> None:
    path = _world(tmp_path, body)
    with pytest.raises(error) as caught:
        load_world(WorldOptions(file=str(path)), Findings())
    assert f"w.world:{line}" in str(caught.value)


def test_a_robot_is_not_a_world(tmp_path: Path) -> None:
    robot = tmp_path / "r.sdf"
    robot.write_text("<sdf version='1.9'><model name='r'/></sdf>")
    with pytest.raises(ParseError, match="is not an SDF world"):
        load_world(WorldOptions(file=str(robot)), Findings())


def test_terrain_options(tmp_path: Path) -> None:
    image = tmp_path / "h.png"
    image.write_bytes(b"")
    with pytest.raises(ConfigError, match="--terrain-size"):
        load_world(WorldOptions(terrain=str(image)), Findings())
    with pytest.raises(ConfigError, match="give one"):
        load_world(WorldOptions(file=str(image), terrain=str(image)), Findings())
    with pytest.raises(ParseError, match="file not found"):
        load_world(WorldOptions(terrain=str(tmp_path / "none.stl")), Findings())
