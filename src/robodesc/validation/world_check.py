"""The world an output carries, read back by its consumer (``--world``, ``--terrain``; docs/worlds.md).

MJCF: MuJoCo loads ``scene.xml`` (its hfields) and casts rays down at points of each terrain; the
ground it collides with must be where the placement put it (the heightfield's heights, to float32's
precision). USD: usd-core composes the world stage: the physics scene's gravity, each terrain a
static triangle-mesh collider with every triangle and ``approximation = "none"``, and the robot's
bodies composed in at the spawn point. The expectations come from the emitter as plain numbers, so
this module needs nothing of the emitters.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from typing import Any

from robodesc.validation.report import Status, ValidationReport

GROUND_TOL = 1e-4  # m: MuJoCo keeps an hfield's heights as float32 fractions of its height range
POSITION_TOL = 1e-6  # m


def check_mjcf_ground(scene: str, probes: Sequence[tuple[float, float, float]], report: ValidationReport) -> None:
    """Rays from 10 m above each probe (x, y, expected ground z) down onto the scene's world geoms
    (group 0: the robot's colliders and visuals are groups 3 and 2)."""
    import mujoco
    import numpy as np

    try:
        model = mujoco.MjModel.from_xml_path(scene)
    except ValueError as exc:
        report.add("world-ground", Status.FAIL, os.path.basename(scene), f"MuJoCo cannot load the scene: {exc}")
        return
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    groups = np.array([1, 0, 0, 0, 0, 0], dtype=np.uint8)
    geom = np.array([-1], dtype=np.int32)
    worst, where = 0.0, (0.0, 0.0)
    for x, y, z in probes:
        dist = mujoco.mj_ray(model, data, np.array([x, y, 10.0]), np.array([0.0, 0.0, -1.0]), groups, 1, -1, geom)
        got = 10.0 - dist if dist >= 0 else -math.inf
        if abs(got - z) > worst:
            worst, where = abs(got - z), (x, y)
    report.note_error("world-ground", worst)
    element = f"{os.path.basename(scene)} ({model.nhfield} hfield(s))"
    if worst <= GROUND_TOL:
        report.add(
            "world-ground",
            Status.PASS,
            element,
            f"MuJoCo's ground at {len(probes)} points equals the placed terrain's",
            error=worst,
            tolerance=GROUND_TOL,
        )
    else:
        report.add(
            "world-ground",
            Status.FAIL,
            element,
            f"MuJoCo's ground at ({where[0]:.3f}, {where[1]:.3f}) is {worst:.4g} m from the placed terrain's",
            error=worst,
            tolerance=GROUND_TOL,
        )


def check_usd_world(path: str, robot_file: str, expect: Mapping[str, Any], report: ValidationReport) -> None:
    """``expect``: ``gravity`` (m/s²), ``terrains`` (prim path -> triangle count), ``robot`` (prim
    path), ``payload_prim`` (the prim its payload names) and ``root`` (its translation). ``robot_file``: the robot as staged, which the stage's
    payload (naming the final file) is pointed at for the check, in memory."""
    from pxr import Sdf, Usd, UsdGeom, UsdPhysics

    name = os.path.basename(path)
    layer = Sdf.Layer.OpenAsAnonymous(path)
    if layer is None:
        report.add("world-stage", Status.FAIL, name, "usd-core cannot open the world stage")
        return
    spec = layer.GetPrimAtPath(str(expect["robot"]))
    if spec is not None:
        spec.payloadList.ClearEditsAndMakeExplicit()
        spec.payloadList.explicitItems = [Sdf.Payload(os.path.abspath(robot_file), str(expect["payload_prim"]))]
    stage = Usd.Stage.Open(layer)
    problems: list[str] = []
    scene = stage.GetPrimAtPath("/World/PhysicsScene")
    gravity = UsdPhysics.Scene(scene).GetGravityMagnitudeAttr().Get() if scene.IsValid() else None
    if gravity is None or abs(float(gravity) - float(expect["gravity"])) > 1e-4:
        problems.append(f"gravity {gravity} where the world says {expect['gravity']:g}")
    for prim_path, count in dict(expect["terrains"]).items():
        prim = stage.GetPrimAtPath(prim_path)
        if not prim.IsValid() or not prim.IsA(UsdGeom.Mesh):
            problems.append(f"no terrain mesh at {prim_path}")
            continue
        got = len(UsdGeom.Mesh(prim).GetFaceVertexCountsAttr().Get() or [])
        approximation = UsdPhysics.MeshCollisionAPI(prim).GetApproximationAttr().Get()
        if not prim.HasAPI(UsdPhysics.CollisionAPI) or prim.HasAPI(UsdPhysics.RigidBodyAPI):
            problems.append(f"{prim_path} is not a static collider")
        if approximation != "none" or got != count:
            problems.append(f"{prim_path}: {got} triangles, approximation {approximation!r} (expected {count}, 'none')")
    robot = stage.GetPrimAtPath(str(expect["robot"]))
    bodies = [p for p in Usd.PrimRange(robot) if p.HasAPI(UsdPhysics.RigidBodyAPI)] if robot.IsValid() else []
    if not bodies:
        problems.append(f"the robot's payload composes no rigid body at {expect['robot']}")
    else:
        at = UsdGeom.Xformable(robot).ComputeLocalToWorldTransform(Usd.TimeCode.Default()).ExtractTranslation()
        off = max(abs(a - b) for a, b in zip(at, expect["root"], strict=True))
        if off > POSITION_TOL:
            problems.append(f"the robot stands at {tuple(round(v, 4) for v in at)}, not {tuple(expect['root'])}")
    terrains = len(expect["terrains"])
    if problems:
        report.add("world-stage", Status.FAIL, name, "; ".join(problems))
    else:
        report.add(
            "world-stage",
            Status.PASS,
            name,
            f"usd-core composes it: gravity, {terrains} static triangle-mesh terrain(s) with every triangle, "
            f"the robot's {len(bodies)} bodies at the spawn point",
        )
