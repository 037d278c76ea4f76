"""Every bundled example (URDF, YAML, HoloScript, Python builder) compiled to every target, and each
result checked by an independent consumer (MuJoCo for URDF, Drake for SDF, usd-core's physics
parser for USD)."""

from __future__ import annotations

import importlib.util
import os
from pathlib import Path
from typing import Any

import pytest
from pxr import Usd, UsdPhysics

import robodesc
from robodesc.ir.model import Robot
from tests.conftest import EXAMPLES, HOLO_ARM


def _four_bar() -> Robot:
    spec = importlib.util.spec_from_file_location("four_bar_example", EXAMPLES / "four_bar.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    robot: Robot = module.build()
    return robot


SOURCES: dict[str, tuple[Any, dict[str, Any]]] = {
    "gripper_arm.urdf": (str(EXAMPLES / "urdf" / "gripper_arm.urdf"), {}),
    "arm6_gripper.yaml": (str(EXAMPLES / "arm6_gripper.yaml"), {}),
    "quadruped.yaml": (str(EXAMPLES / "quadruped.yaml"), {}),
    "four_bar.yaml": (str(EXAMPLES / "four_bar.yaml"), {}),
    "four_bar.py": (_four_bar, {}),
    "mobile_base.yaml": (str(EXAMPLES / "mobile_base.yaml"), {}),
    "isaac_arm.yaml": (str(EXAMPLES / "isaac_arm.yaml"), {"missing_mesh": "primitive"}),
    "isaac-sim-robot-arm.holo": (str(HOLO_ARM), {"missing_mesh": "primitive"}),
    "pan_tilt (SDF model folder)": (str(EXAMPLES / "sdf" / "pan_tilt"), {}),
}


def _load_physics(stage: Usd.Stage, root: str) -> Any:
    """usd-core 26 renamed the parser; both spellings return the same per-type table."""
    load = getattr(UsdPhysics, "LoadUsdPhysicsFromRange", None)
    if hasattr(UsdPhysics, "UsdPhysicsLoadStageFromPrimRange"):
        load = UsdPhysics.UsdPhysicsLoadStageFromPrimRange
    assert load is not None
    return load(stage, [root])


def _source(name: str) -> Any:
    src, _ = SOURCES[name]
    return src() if callable(src) else src


@pytest.mark.parametrize("name", sorted(SOURCES))
def test_urdf_validates_in_mujoco(name: str, tmp_path: Path) -> None:
    result = robodesc.compile_to_urdf(_source(name), tmp_path / "robot.urdf", **SOURCES[name][1])
    assert result.validation is not None
    assert result.validation.ok, result.validation.to_text()


@pytest.mark.parametrize("name", sorted(SOURCES))
def test_sdf_validates_in_drake(name: str, tmp_path: Path) -> None:
    result = robodesc.compile_to_sdf(_source(name), tmp_path / "robot.sdf", **SOURCES[name][1])
    assert result.validation is not None
    assert result.validation.ok, result.validation.to_text()


@pytest.mark.parametrize("name", sorted(SOURCES))
def test_usd_parses_as_the_ir(name: str, tmp_path: Path) -> None:
    out = tmp_path / "robot.usda"
    result = robodesc.compile_to_usd(_source(name), out, **SOURCES[name][1])
    robot = result.robot
    stage = Usd.Stage.Open(str(out))
    root = stage.GetDefaultPrim()
    parsed = _load_physics(stage, str(root.GetPath()))
    bodies = joints = 0
    for kind, (paths, _descs) in parsed.items():
        if kind == UsdPhysics.ObjectType.RigidBody:
            bodies = len(paths)
        elif kind in (
            UsdPhysics.ObjectType.RevoluteJoint,
            UsdPhysics.ObjectType.PrismaticJoint,
            UsdPhysics.ObjectType.FixedJoint,
            UsdPhysics.ObjectType.SphericalJoint,
            UsdPhysics.ObjectType.D6Joint,
        ):
            joints += len(paths)
    assert bodies == len(robot.links)
    # Tree joints + loop closures (+ the root_joint of a fixed base).
    fixed_root = 1 if root.GetChild("joints").GetChild("root_joint") else 0
    assert joints == len(robot.joints) + len(robot.loop_joints) + fixed_root
    total = sum(
        UsdPhysics.MassAPI(p).GetMassAttr().Get() or 0.0 for p in stage.Traverse() if p.HasAPI(UsdPhysics.MassAPI)
    )
    assert total == pytest.approx(robot.total_mass(), rel=1e-6)


@pytest.mark.parametrize("name", sorted(SOURCES))
def test_isaac_folder(name: str, tmp_path: Path) -> None:
    result = robodesc.compile_for_isaac_sim(_source(name), tmp_path / "isaac", **SOURCES[name][1])
    assert {"usd", "urdf", "importer_settings", "isaaclab", "validation", "findings"} <= set(result.files)
    assert all(os.path.exists(p) for p in result.files.values())
    assert result.validation is not None and result.validation.ok, result.validation.to_text()


def test_four_bar_loop_closure_is_outside_the_articulation(tmp_path: Path) -> None:
    out = tmp_path / "four_bar.usda"
    robodesc.compile_to_usd(_four_bar(), out)
    stage = Usd.Stage.Open(str(out))
    loops = [
        p
        for p in stage.Traverse()
        if p.HasAttribute("physics:excludeFromArticulation") and p.GetAttribute("physics:excludeFromArticulation").Get()
    ]
    assert len(loops) == 1
