"""A world in USD (emit/usd/world.py): a stage beside the robot with the terrain as a static
triangle-mesh collider, the world's physics, and the robot composed in at its spawn point."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest
from pxr import Usd, UsdGeom, UsdPhysics

from robodesc.api import compile_to_usd
from robodesc.cli import main
from robodesc.validation.physx_python import physx_python
from tests.conftest import EXAMPLES, WORLDS
from tests.worlds.physx_scripts import positions

QUADRUPED = EXAMPLES / "quadruped.yaml"


def test_world_stage(tmp_path: Path) -> None:
    out = tmp_path / "quadruped.usda"
    result = compile_to_usd(
        str(QUADRUPED), str(out), world=str(WORLDS / "step_20cm" / "step_20cm.world"), spawn=(0.5, 0.0)
    )
    world_file = tmp_path / "quadruped_world.usda"
    assert result.files["world"] == str(world_file)
    stage = Usd.Stage.Open(str(world_file))
    assert stage.GetDefaultPrim().GetPath() == "/World"
    scene = UsdPhysics.Scene(stage.GetPrimAtPath("/World/PhysicsScene"))
    assert scene.GetGravityMagnitudeAttr().Get() == pytest.approx(9.81)
    assert stage.GetPrimAtPath("/World/PhysicsScene").GetAttribute("physxScene:timeStepsPerSecond").Get() == 1000
    terrain = stage.GetPrimAtPath("/World/mesh_terrain/collision")
    assert terrain.IsA(UsdGeom.Mesh) and terrain.HasAPI(UsdPhysics.CollisionAPI)
    assert UsdPhysics.MeshCollisionAPI(terrain).GetApproximationAttr().Get() == "none"
    assert not terrain.HasAPI(UsdPhysics.RigidBodyAPI)  # static: no body of its own
    assert len(UsdGeom.Mesh(terrain).GetFaceVertexCountsAttr().Get()) == 20  # every triangle of the STL
    # One flat normal per triangle, as the robot's meshes get (emit/usd/geometry.author_mesh).
    normals = UsdGeom.Mesh(terrain).GetNormalsAttr().Get()
    assert len(normals) == 20 and UsdGeom.Mesh(terrain).GetNormalsInterpolation() == "uniform"
    assert max(n[2] for n in normals) == pytest.approx(1.0)  # the tops face up
    # The robot is composed in under /World, placed at the spawn point.
    robot = stage.GetDefaultPrim().GetChild(result.robot.name)
    assert robot.IsValid() and any(p.HasAPI(UsdPhysics.RigidBodyAPI) for p in Usd.PrimRange(robot))
    translate = UsdGeom.Xformable(robot).ComputeLocalToWorldTransform(Usd.TimeCode.Default()).ExtractTranslation()
    assert (translate[0], translate[1]) == pytest.approx((0.5, 0.0))


@pytest.mark.skipif(physx_python() is None, reason="no PhysX interpreter (tests/consumers/run.sh builds one)")
def test_physx_rests_the_robot_on_the_terrain(tmp_path: Path) -> None:
    out = tmp_path / "quadruped.usda"
    world = WORLDS / "step_20cm" / "step_20cm.world"
    code = main(["compile", str(QUADRUPED), "-t", "usd", "-o", str(out), "--no-fix-base", "--world", str(world), "-q"])
    assert code == 0
    python = physx_python()
    assert python is not None
    done = subprocess.run(
        [python, "-c", positions("ARTICULATION", "rootPosition"), str(tmp_path / "quadruped_world.usda"), "1.0"],
        capture_output=True, text=True, timeout=600, check=False, env={**os.environ},
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    root = json.loads(done.stdout.strip().splitlines()[-1])[0]
    # It lands on the terrain's top (z = 0 at the origin: Quad-SDK's pose -0.1 and a 0.1 slab),
    # neither through it nor floating above it.
    assert 0.0 < root[2] < 0.6 and abs(root[0]) < 0.05, root


def test_a_concave_terrain_warns_of_newtons_hull(tmp_path: Path) -> None:
    """examples/worlds/steps.world's step is concave: Newton's MuJoCo solver would collide its hull
    (docs/worlds.md, "Newton and the USD terrain"); the warning names the terrain. Its friction (1) is
    the robot's highest, so it is written as given."""
    steps = EXAMPLES / "worlds" / "steps.world"
    result = compile_to_usd(str(QUADRUPED), str(tmp_path / "q.usda"), world=str(steps), validate=False)
    (hull,) = [f for f in result.findings if f.code == "usd-world-newton-hull"]
    assert hull.element == "collision 'collision' of 'terrain'"
    assert not [f for f in result.findings if f.code == "usd-world-friction"]


def test_a_world_friction_of_100_is_written_as_the_robots(tmp_path: Path) -> None:
    world = WORLDS / "flat" / "flat.world"
    result = compile_to_usd(str(QUADRUPED), str(tmp_path / "q.usda"), world=str(world), validate=False)
    assert [f.code for f in result.findings if f.code == "usd-world-newton-hull"] == []  # a box: convex
    stage = Usd.Stage.Open(str(tmp_path / "q_world.usda"))
    material = UsdPhysics.MaterialAPI(stage.GetPrimAtPath("/World/PhysicsMaterials/surface_0"))
    assert material.GetDynamicFrictionAttr().Get() == pytest.approx(1.0)  # Quad-SDK's 100, for PhysX's min
    assert [f.code for f in result.findings if f.code == "usd-world-friction"] == ["usd-world-friction"]
