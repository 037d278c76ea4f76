"""Drop one robot's USD onto flat ground in PhysX (ovphysx, CPU) and report how it stands.

Run by the interpreter that has ovphysx (``robodesc.validation.physx_python.physx_python()``; it
cannot live in robodesc's environment), by ``benchmarks/physx_causes.py``: one JSON request on
standard input, one JSON answer on standard output. A benchmark's own minimal runner, written
before PhysX became a ``validate --dynamics`` engine on main.

Request: ``{"usd", "spawn": [x, y, z], "duration", "timestep", "floor_mu"}``, optionally
``"terrain"``: a world stage ``-t usd --world`` wrote (``<stem>_world.usda``). The USD is read as
written (its drives, targets, initial joint state, masses, colliders, materials, PhysX attributes);
a scene layer that sublayers it adds only gravity, a floor plane with friction ``floor_mu`` and the
spawn translation of the robot prim; with ``terrain``, the world stage's scene, terrain and
materials instead of the gravity and plane (its own robot switched off).

Answer: ``{"height", "xy", "tilt", "joint_error", "worst_joint", "peak_torque", "peak_share", "peak_joint",
"steps_per_second"}`` in SI: the root's final height (m; z, not over a terrain), its x and y, and tilt from upright (rad); the largest
final |q - target| (rad or m); the largest drive torque over the run, |kp (target - q) - kd qd|
clamped to the drive's maxForce (PhysX's drive is implicit: this is the force of each step's end
state), and the same as a share of maxForce (the effort limit), with the joint it occurs at.
"""
# mypy: ignore-errors

from __future__ import annotations

import json
import math
import os
import sys
import tempfile
import time


def _scene(folder, usd, spawn, floor_mu, terrain=None):
    from pxr import Gf, Sdf, Usd, UsdGeom, UsdPhysics, UsdShade

    robot = Usd.Stage.Open(usd)
    prim = robot.GetDefaultPrim()
    path = os.path.join(folder, "scene.usda")
    layer = Sdf.Layer.CreateNew(path)
    layer.subLayerPaths.append(os.path.abspath(usd))
    if terrain:
        layer.subLayerPaths.append(os.path.abspath(terrain))
    stage = Usd.Stage.Open(layer)
    stage.SetEditTarget(layer)
    stage.SetDefaultPrim(stage.GetPrimAtPath(prim.GetPath()))
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    UsdGeom.SetStageMetersPerUnit(stage, UsdGeom.GetStageMetersPerUnit(robot) or 1.0)
    # The robot prim has no transform ops of its own: one translate moves every link to the spawn.
    UsdGeom.Xformable(stage.GetPrimAtPath(prim.GetPath())).AddTranslateOp().Set(Gf.Vec3d(*spawn))
    if terrain:
        # The world stage robodesc writes (-t usd --world): its physics scene, terrain and materials
        # as written; its own robot (a payload) is switched off, the request's robot stands in.
        world = Usd.Stage.Open(os.path.abspath(terrain), load=Usd.Stage.LoadNone)
        top = world.GetDefaultPrim() or world.GetPseudoRoot()
        for child in top.GetAllChildren():  # GetChildren skips the unloaded payload: the robot itself
            if child.HasAuthoredPayloads():
                stage.OverridePrim(child.GetPath()).SetActive(False)
        layer.Save()
        return path
    scene = UsdPhysics.Scene.Define(stage, "/PhysicsScene")
    scene.CreateGravityDirectionAttr().Set(Gf.Vec3f(0.0, 0.0, -1.0))
    scene.CreateGravityMagnitudeAttr().Set(9.81)
    material = UsdShade.Material.Define(stage, "/FloorMaterial")
    api = UsdPhysics.MaterialAPI.Apply(material.GetPrim())
    api.CreateStaticFrictionAttr().Set(float(floor_mu))
    api.CreateDynamicFrictionAttr().Set(float(floor_mu))
    api.CreateRestitutionAttr().Set(0.0)
    plane = UsdGeom.Plane.Define(stage, "/Floor")
    plane.CreateAxisAttr().Set(UsdGeom.Tokens.z)
    UsdPhysics.CollisionAPI.Apply(plane.GetPrim())
    UsdShade.MaterialBindingAPI.Apply(plane.GetPrim()).Bind(material, UsdShade.Tokens.weakerThanDescendants, "physics")
    layer.Save()
    return path


class _Sim:
    def __init__(self, path):
        import ovphysx
        import ovstage
        from ovphysx import PhysX
        from ovphysx.samples.python_samples.schema_support import physx_schema_paths

        ovstage.population.register_usd_schemas(
            [*[str(p) for p in physx_schema_paths()], str(ovphysx.newton_schema_root())]
        )
        PhysX.set_cpu_mode(True)
        self.physx = PhysX()
        self.stage = ovstage.Stage("physx-causes")
        ovstage.population.open_usd(self.stage, path, ordinal=1, domains=ovstage.PopulationDomain.ALL)
        self.stage.advance_write_floor(ordinal=1).wait()
        self.physx.wait_task(self.physx.attach_ovstage(self.stage, read_ordinal=1))
        self.physx.warmup()
        self.physx.wait_all()
        self.paths = ovstage.PathDictionary(self.stage)

    def read(self, kind, attributes):
        """{attribute: {prim path: list of floats}} (a joint's one axis, a root's 3 or 4 numbers)."""
        from ovphysx.types import ObjectScope

        out = {a: {} for a in attributes}
        with self.physx.read_sync(kind, attributes, scope=ObjectScope.ALL) as result:
            for group in result.groups:
                if group.is_delete:
                    continue
                name = self.paths.token_to_string(group.attribute)
                paths = self.paths.get_path_strings(group.prim_list)
                if group.is_array:
                    for i in range(group.prim_count):
                        out[name][paths[group.prim_offset + i]] = [float(v) for v in group.tensors[i].numpy().ravel()]
                else:
                    rows = group.tensors[0].numpy().reshape(group.prim_count, -1)
                    for i in range(group.prim_count):
                        out[name][paths[group.prim_offset + i]] = [float(v) for v in rows[i]]
        return out

    def close(self):
        if self.physx.is_stage_attached(self.stage):
            self.physx.wait_task(self.physx.detach_ovstage())
        self.stage.destroy()
        self.physx.destroy()


def _angular(usd):
    """Joint prim path -> True for angular axes (PhysX reports them in degrees)."""
    from pxr import Usd, UsdPhysics

    stage = Usd.Stage.Open(usd)  # held: prims of a collected stage expire
    return {
        str(p.GetPath()): p.IsA(UsdPhysics.RevoluteJoint)
        for p in stage.Traverse()
        if p.IsA(UsdPhysics.RevoluteJoint) or p.IsA(UsdPhysics.PrismaticJoint)
    }


def run(req):
    from ovphysx.types import SimObjectType as T

    with tempfile.TemporaryDirectory(prefix="physx-causes-") as folder:
        sim = _Sim(_scene(folder, req["usd"], req["spawn"], req["floor_mu"], req.get("terrain")))
        try:
            angular = _angular(req["usd"])
            fixed = sim.read(
                T.ARTICULATION_JOINT, ["jointPositionTarget", "jointStiffness", "jointDamping", "jointMaxForce"]
            )
            driven = [p for p, v in fixed["jointStiffness"].items() if len(v) == 1 and p in angular and v[0] > 0]
            scale = {p: math.radians(1.0) if angular[p] else 1.0 for p in driven}  # PhysX units -> SI
            peak, share, at = 0.0, 0.0, ""
            dt = req["timestep"]
            steps = round(req["duration"] / dt)
            started = time.perf_counter()
            for _ in range(steps):
                sim.physx.step_sync(dt)
                state = sim.read(T.ARTICULATION_JOINT, ["jointPosition", "jointVelocity"])
                for p in driven:
                    kp, kd, fmax = (
                        fixed["jointStiffness"][p][0],
                        fixed["jointDamping"][p][0],
                        fixed["jointMaxForce"][p][0],
                    )
                    tau = abs(
                        kp * (fixed["jointPositionTarget"][p][0] - state["jointPosition"][p][0])
                        - kd * state["jointVelocity"][p][0]
                    )
                    tau = min(tau, fmax) if fmax > 0 else tau
                    if not math.isfinite(tau):
                        return {"error": f"state not finite at {p}"}
                    if tau > peak:
                        peak, at = tau, p
                    if fmax > 0 and tau / fmax > share:
                        share = tau / fmax
            elapsed = time.perf_counter() - started
            errors = {
                p: abs(state["jointPosition"][p][0] - fixed["jointPositionTarget"][p][0]) * scale[p] for p in driven
            }
            worst = max(errors, key=errors.get)
            root = sim.read(T.ARTICULATION, ["rootPosition", "rootOrientation"])
            x, y, z = next(iter(root["rootPosition"].values()))[:3]
            qx, qy = next(iter(root["rootOrientation"].values()))[:2]  # x y z w
            return {
                "height": z,
                "xy": [x, y],
                "tilt": math.acos(max(-1.0, min(1.0, 1.0 - 2.0 * (qx * qx + qy * qy)))),
                "joint_error": errors[worst],
                "worst_joint": worst.rsplit("/", 1)[-1],
                "peak_torque": peak,
                "peak_share": share,
                "peak_joint": at.rsplit("/", 1)[-1],
                "steps_per_second": steps / elapsed,
            }
        finally:
            sim.close()


if __name__ == "__main__":
    print(json.dumps(run(json.loads(sys.stdin.read()))))
