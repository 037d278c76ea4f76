"""A world compiled alone (a world file as the input, no robot): each output loaded in its
consumer, and the world's physics read back (docs/worlds.md, "A world alone")."""

from __future__ import annotations

import math

from robodesc.ir.world import WorldPhysics
from robodesc.validation.report import Status, ValidationReport

GRAVITY = (0.0, 0.0, -9.81)


def check_mjcf_world(path: str, name: str, physics: WorldPhysics, colliders: int) -> ValidationReport:
    """MuJoCo loads the scene (any warning fails it); its step, gravity and world geoms are the world's."""
    import mujoco

    from robodesc.validation.mujoco_load import captured_warnings

    report = ValidationReport(robot=name, target="mjcf", consumer="mujoco")
    sink: list[str] = []
    try:
        with captured_warnings(sink):
            model = mujoco.MjModel.from_xml_path(path)
    except ValueError as exc:
        report.add("world-load", Status.FAIL, "scene", f"MuJoCo refuses {path}: {exc}")
        return report
    if sink:
        report.add("world-load", Status.FAIL, "scene", "MuJoCo warns: " + "; ".join(sink)[:400])
        return report
    geoms = int((model.geom_bodyid == 0).sum())
    report.add("world-load", Status.PASS, "scene", f"{geoms} world geoms, {model.nhfield} heightfields")
    _physics(report, physics, model.opt.timestep, tuple(float(g) for g in model.opt.gravity))
    _count(report, "world-geoms", geoms, colliders)
    return report


def check_usd_world(path: str, name: str, physics: WorldPhysics, colliders: int) -> ValidationReport:
    """usd-core opens the stage; its physics scene and static colliders are the world's."""
    from pxr import Usd, UsdPhysics

    report = ValidationReport(robot=name, target="usd", consumer="usd-core")
    stage = Usd.Stage.Open(path)
    if stage is None:
        report.add("world-load", Status.FAIL, "stage", f"usd-core cannot open {path}")
        return report
    scenes = [p for p in stage.Traverse() if p.IsA(UsdPhysics.Scene)]
    found = [p for p in stage.Traverse() if p.HasAPI(UsdPhysics.CollisionAPI) and not _in_body(p)]
    report.add("world-load", Status.PASS, "stage", f"{len(scenes)} physics scene(s), {len(found)} static colliders")
    if len(scenes) != 1:
        report.add("world-physics", Status.FAIL, "PhysicsScene", f"{len(scenes)} physics scenes, expected 1")
        return report
    scene = UsdPhysics.Scene(scenes[0])
    direction = scene.GetGravityDirectionAttr().Get() or (0.0, 0.0, -1.0)
    magnitude = scene.GetGravityMagnitudeAttr().Get()
    gravity = tuple(float(d) * float(magnitude) for d in direction)
    steps = scenes[0].GetAttribute("physxScene:timeStepsPerSecond").Get()
    _physics(report, physics, 1.0 / steps if steps else None, gravity)
    _count(report, "world-colliders", len(found), colliders)
    return report


def check_sdf_world(text: str, name: str, models: int) -> ValidationReport:
    """Drake parses the world (libsdformat underneath) into one model per static body."""
    from robodesc.validation.drake_sdf import _drake_warnings, drake_available

    report = ValidationReport(robot=name, target="sdf", consumer="drake")
    if not drake_available():
        report.add("world-load", Status.SKIP, "world", "skipped: pydrake is not installed (pip install drake)")
        return report
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    plant = MultibodyPlant(0.0)  # held: a Parser outlived by its plant crashes Drake
    # Drake's notes on what it ignores (physics, plugins, lights: Gazebo's) go to the report, not the terminal.
    ignored: list[str] = []
    try:
        with _drake_warnings(ignored):
            instances = Parser(plant).AddModelsFromString(text, "sdf")
    except Exception as exc:  # Drake raises RuntimeError/ValueError with libsdformat's messages
        report.add("world-load", Status.FAIL, "world", f"Drake refuses the SDF: {str(exc).strip()}")
        return report
    report.add("world-load", Status.PASS, "world", f"parsed by Drake into {len(instances)} model(s)")
    _count(report, "world-models", len(instances), models)
    return report


def _in_body(prim: object) -> bool:
    """A collider of a moving body (a cord's capsule), not of the static ground."""
    from pxr import UsdPhysics

    at = prim
    while at is not None and at.IsValid():  # type: ignore[attr-defined]
        if at.HasAPI(UsdPhysics.RigidBodyAPI):  # type: ignore[attr-defined]
            return True
        at = at.GetParent()  # type: ignore[attr-defined]
    return False


def _physics(report: ValidationReport, physics: WorldPhysics, step: float | None, gravity: tuple[float, ...]) -> None:
    if physics.step is not None:
        error = abs((step or 0.0) - physics.step)
        status = Status.PASS if step is not None and error <= 1e-9 else Status.FAIL
        report.add("world-step", status, "physics", f"step {step} s, the world's {physics.step:g} s", error=error)
    expected = physics.gravity or GRAVITY
    error = math.dist(gravity, expected)
    status = Status.PASS if error <= 1e-6 else Status.FAIL
    report.add("world-gravity", status, "physics", f"gravity {gravity}, the world's {expected}", error=error)


def _count(report: ValidationReport, name: str, found: int, expected: int) -> None:
    status = Status.PASS if found == expected else Status.FAIL
    report.add(name, status, "world", f"{found}, expected {expected}")
