"""A world in SDF (emit/sdf/world_models.py): Gazebo Harmonic's world with the terrain as its mesh
(Gazebo collides the triangles), the world's physics and friction, the robot at its spawn point."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from lxml import etree

from robodesc.api import compile_to_sdf
from tests.conftest import EXAMPLES, WORLDS

QUADRUPED = EXAMPLES / "quadruped.yaml"


def test_sdf_world(tmp_path: Path) -> None:
    out = tmp_path / "quadruped.sdf"
    result = compile_to_sdf(
        str(QUADRUPED), str(out), world=str(WORLDS / "step_20cm" / "step_20cm.world"), spawn=(0.5, 0.0)
    )
    assert result.validation is not None and result.validation.ok  # Drake reads the robot in the world
    root = etree.parse(str(out)).getroot()
    world = root.find("world")
    assert world is not None
    assert world.findtext("physics/max_step_size") == "0.001" and world.findtext("gravity") == "0 0 -9.81"
    assert world.find("model[@name='ground_plane']") is None  # the world's ground, not robodesc's plane
    terrain = world.find("model[@name='mesh_terrain']")
    assert terrain is not None and terrain.findtext("static") == "true"
    assert terrain.findtext("pose") == "-1.975 -2 -0.1 0 0 0"
    uri = terrain.findtext("link/collision/geometry/mesh/uri")
    assert uri is not None and (tmp_path / uri).resolve() == (WORLDS / "step_20cm" / "step_20cm.stl").resolve()
    assert terrain.findtext("link/collision/surface/friction/ode/mu") == "100"
    robot = world.find(f"model[@name='{result.robot.name}']")
    assert robot is not None
    x, y, z, *_ = (float(v) for v in (robot.findtext("pose") or "").split())
    assert (x, y) == pytest.approx((0.5, 0.0)) and z > 0.0


def test_a_bare_world_flag_still_wraps_in_an_empty_world(tmp_path: Path) -> None:
    from robodesc.cli import main

    out = tmp_path / "arm.sdf"
    assert (
        main(["compile", str(EXAMPLES / "urdf" / "gripper_arm.urdf"), "-t", "sdf", "-o", str(out), "--world", "-q"])
        == 0
    )
    world = etree.parse(str(out)).getroot().find("world")
    assert world is not None and world.find("model[@name='ground_plane']") is not None
    assert os.path.isfile(out)
