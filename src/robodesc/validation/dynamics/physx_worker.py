"""The scenarios in PhysX, run by the interpreter that has ovphysx (never imported by robodesc).

ovphysx (NVIDIA's PhysX for USD stages, on CPU) cannot share robodesc's environment (it pins
``packaging<24``; :mod:`robodesc.validation.physx_python`), so robodesc starts this file there and
speaks JSON: one request on standard input ``{"usd", "root", "scenarios", "setup"}`` (setup as
:meth:`Setup.as_dict`), one answer on standard output ``{"physx": version, "runs": [Run fields]}``
or ``{"error": message}``. It imports only the stdlib, ovphysx, ovstage, pxr and numpy.

PhysX reads the USD exactly as written: the file is never edited. What a scenario needs is put
over it, in a scene layer that sublayers the file (a physics scene with gravity, the floor, the
root welded to the world or its world joint deactivated), and through ovphysx's write API (the
joints at the home pose, the drive targets, the dropped root's pose). Everything else (masses,
drive gains and limits, armature, velocity limits, colliders, materials) is the file's.

Units: ovphysx gives angular joint columns in degrees and gains per degree, as USD authors them;
linear ones in stage units. The answer is SI (rad, m, N·m).
"""
# mypy: ignore-errors

from __future__ import annotations

import contextlib
import math
import os
import tempfile

_SAMPLE = 0.01
_BOX, _BOX_H = 0.05, 0.01  # the slide block's half length and height (mujoco_run: why flat)
_PHYSX_DEFAULT_MU = 0.5  # PhysX's default material, for a collider bound to none


def _short(path):
    return str(path).rstrip("/").split("/")[-1]


# --- reading the file (pxr) -------------------------------------------------------------------


def _inspect(usd, root_name, feet, names=None):
    """What the scene layer needs from the file: units, the root body, joints by name, the joints
    that tie a body to the world, and the friction of the colliders the robot stands on. A prim's
    name is its displayName (the source's, in robodesc's USD), else ``names``' entry for it (a
    file's name -> the source's), else its own."""
    from pxr import Usd, UsdGeom, UsdPhysics

    names = names or {}

    def name_of(prim):
        return prim.GetMetadata("displayName") or names.get(prim.GetName()) or prim.GetName()

    stage = Usd.Stage.Open(usd)
    mpu = UsdGeom.GetStageMetersPerUnit(stage) or 1.0
    bodies, joints, world_joints, scenes = [], {}, [], []
    for prim in stage.Traverse():
        if prim.HasAPI(UsdPhysics.RigidBodyAPI):
            bodies.append(prim)
        if prim.IsA(UsdPhysics.Scene):
            scenes.append(str(prim.GetPath()))
        if not prim.IsA(UsdPhysics.Joint):
            continue
        joint = UsdPhysics.Joint(prim)
        ends = [joint.GetBody0Rel().GetTargets(), joint.GetBody1Rel().GetTargets()]
        linked = [t for targets in ends for t in targets if stage.GetPrimAtPath(t).HasAPI(UsdPhysics.RigidBodyAPI)]
        if len(linked) == 1:
            world_joints.append(str(prim.GetPath()))
        kind = (
            "angular"
            if prim.IsA(UsdPhysics.RevoluteJoint)
            else "linear"
            if prim.IsA(UsdPhysics.PrismaticJoint)
            else None
        )
        if kind is None:
            continue
        joints[str(prim.GetPath())] = (name_of(prim), kind)
    if not bodies:
        raise RuntimeError("PhysX reads no rigid body from the USD")
    root = _root_body(bodies, root_name, name_of)
    xf = UsdGeom.Xformable(root).ComputeLocalToWorldTransform(Usd.TimeCode.Default())
    by_name = {name_of(p): p for p in bodies}
    return {
        "mpu": mpu,
        "default_prim": stage.GetDefaultPrim().GetName() if stage.GetDefaultPrim() else "",
        "up": UsdGeom.GetStageUpAxis(stage),
        "root": str(root.GetPath()),
        "root_pos": list(xf.ExtractTranslation()),
        "root_rot": _quat_wxyz(xf),
        "joints": joints,
        "world_joints": world_joints,
        "scenes": scenes,
        "mu": _feet_mu([by_name[f] for f in feet if f in by_name] or bodies),
    }


def _root_body(bodies, root_name, name_of):
    from pxr import UsdPhysics

    for prim in bodies:
        if root_name and root_name in (prim.GetName(), name_of(prim)):
            return prim
    rooted = [p for p in bodies if p.HasAPI(UsdPhysics.ArticulationRootAPI)]
    return rooted[0] if rooted else bodies[0]


def _quat_wxyz(xf):
    q = xf.RemoveScaleShear().ExtractRotationQuat()
    return [q.GetReal(), *q.GetImaginary()]


def _feet_mu(bodies):
    """The most common dynamic friction of the colliders under ``bodies`` (their bound physics
    material's, or PhysX's default), as the other engines' runners take the feet's."""
    from pxr import Usd, UsdPhysics, UsdShade

    values = []
    for body in bodies:
        # Into instances too: Isaac Sim 6's importer puts a mesh collider's shapes inside an
        # instance, and without this the composed stage's feet had no friction to read (solo12).
        walk = iter(Usd.PrimRange(body, Usd.TraverseInstanceProxies()))
        for prim in walk:
            if prim != body and prim.HasAPI(UsdPhysics.RigidBodyAPI):
                # Another body's colliders are its own. Skipped, not the end of the walk: the
                # importer nests child links among a link's colliders (Talos: 10 of 60 bodies had
                # their colliders read before this).
                walk.PruneChildren()
                continue
            if not prim.HasAPI(UsdPhysics.CollisionAPI):
                continue
            material, _ = UsdShade.MaterialBindingAPI(prim).ComputeBoundMaterial("physics")
            mu = None
            if material and material.GetPrim().HasAPI(UsdPhysics.MaterialAPI):
                mu = UsdPhysics.MaterialAPI(material.GetPrim()).GetDynamicFrictionAttr().Get()
            values.append(round(float(_PHYSX_DEFAULT_MU if mu is None else mu), 6))
    return max(set(values), key=values.count) if values else None


# --- the scene layer over the file ------------------------------------------------------------


def _scene_layer(folder, usd, info, weld, floor_mu, gravity=(0.0, 0.0, -9.81)):
    """A layer that sublayers the file and adds what the scenario needs, saved in ``folder``."""
    from pxr import Gf, Sdf, Usd, UsdGeom, UsdPhysics, UsdShade

    path = os.path.join(folder, "scene.usda")
    layer = Sdf.Layer.CreateNew(path)
    if usd is not None:
        layer.subLayerPaths.append(os.path.abspath(usd))
    stage = Usd.Stage.Open(layer)
    stage.SetEditTarget(layer)
    mpu = info["mpu"] if info else 1.0
    UsdGeom.SetStageMetersPerUnit(stage, mpu)
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    if info and info["default_prim"]:
        stage.SetDefaultPrim(stage.GetPrimAtPath("/" + info["default_prim"]))
    g = math.sqrt(sum(c * c for c in gravity))
    for scene_path in (info["scenes"] if info else []) or ["/DynamicsScene"]:
        scene = (
            UsdPhysics.Scene.Define(stage, scene_path)
            if scene_path == "/DynamicsScene"
            else UsdPhysics.Scene(stage.GetPrimAtPath(scene_path))
        )
        scene.CreateGravityDirectionAttr().Set(Gf.Vec3f(*(c / g for c in gravity)))
        scene.CreateGravityMagnitudeAttr().Set(g / mpu)
    if info:
        for joint in info["world_joints"]:
            stage.OverridePrim(joint).SetActive(False)
    if weld and info:
        # The root welded where the file puts it: body0 empty is the world.
        fixed = UsdPhysics.FixedJoint.Define(stage, "/DynamicsWeld")
        fixed.CreateBody1Rel().SetTargets([Sdf.Path(info["root"])])
        fixed.CreateLocalPos0Attr().Set(Gf.Vec3f(*info["root_pos"]))
        fixed.CreateLocalRot0Attr().Set(Gf.Quatf(info["root_rot"][0], *info["root_rot"][1:]))
        fixed.CreateLocalPos1Attr().Set(Gf.Vec3f(0.0, 0.0, 0.0))
        fixed.CreateLocalRot1Attr().Set(Gf.Quatf(1.0, 0.0, 0.0, 0.0))
    if floor_mu is not None:
        # Equal friction on both sides: PhysX's average, min and max all give mu.
        material = UsdShade.Material.Define(stage, "/DynamicsFloorMaterial")
        api = UsdPhysics.MaterialAPI.Apply(material.GetPrim())
        api.CreateStaticFrictionAttr().Set(float(floor_mu))
        api.CreateDynamicFrictionAttr().Set(float(floor_mu))
        api.CreateRestitutionAttr().Set(0.0)
        plane = UsdGeom.Plane.Define(stage, "/DynamicsFloor")
        plane.CreateAxisAttr().Set(UsdGeom.Tokens.z)
        UsdPhysics.CollisionAPI.Apply(plane.GetPrim())
        binding = UsdShade.MaterialBindingAPI.Apply(plane.GetPrim())
        binding.Bind(material, UsdShade.Tokens.weakerThanDescendants, "physics")
    layer.Save()
    return stage, path


# --- ovphysx ----------------------------------------------------------------------------------


_registered = False


class _Sim:
    """One PhysX instance with the scene layer attached; closed by :meth:`close`."""

    def __init__(self, path):
        global _registered
        import ovphysx
        import ovstage
        from ovphysx import PhysX
        from ovphysx.types import GlobalConfigKey

        if not _registered:
            from ovphysx.samples.python_samples.schema_support import physx_schema_paths

            roots = [str(p) for p in physx_schema_paths()]
            # Without newton-usd-schemas, newton:* attributes (velocity limits) are unknown to the stage.
            with contextlib.suppress(FileNotFoundError):
                roots.append(str(ovphysx.newton_schema_root()))
            ovstage.population.register_usd_schemas(roots)
            _registered = True
        PhysX.set_cpu_mode(True)
        # No worker threads: PhysX steps on the calling thread. A 13-link robot then steps in
        # 0.7 ms instead of 12 ms on a loaded two-core machine (the threads only contend).
        ovphysx.set_global_config(GlobalConfigKey.NUM_THREADS, 0)
        self.physx = PhysX()
        self.queries = {}
        self.stage = ovstage.Stage("robodesc-dynamics")
        ovstage.population.open_usd(self.stage, path, ordinal=1, domains=ovstage.PopulationDomain.ALL)
        self.stage.advance_write_floor(ordinal=1).wait()
        self.physx.wait_task(self.physx.attach_ovstage(self.stage, read_ordinal=1))
        self.paths = ovstage.PathDictionary(self.stage)

    def close(self):
        for query in self.queries.values():
            query.close().wait()
        self.paths.destroy()
        if self.physx.is_stage_attached(self.stage):
            self.physx.wait_task(self.physx.detach_ovstage())
        self.stage.destroy()
        self.physx.destroy()

    def read(self, kind, attributes):
        """{attribute: {prim path: numpy row(s)}}: per prim, a fixed row or the array of axes."""
        import numpy as np
        from ovphysx.types import ObjectScope

        out = {a: {} for a in attributes}
        if kind not in self.queries:  # one query per object type: a read per step then costs 1 ms, not 6
            self.queries[kind] = self.physx.query(kind, scope=ObjectScope.ALL).wait()
        with self.physx.read(self.queries[kind], attributes).wait() as result:
            paths_of = result.dictionary
            while (group := result.fetch_next().wait()) is not None:
                if group.is_delete:
                    continue
                name = attributes[_attr_index(group, attributes, paths_of)]
                paths = paths_of.get_path_strings(group.prim_list)
                if group.is_array:
                    for i in range(group.prim_count):
                        out[name][paths[group.prim_offset + i]] = np.array(group.tensors[i].numpy(), copy=True)
                else:
                    rows = group.tensors[0].numpy().reshape(group.prim_count, -1)
                    for i in range(group.prim_count):
                        out[name][paths[group.prim_offset + i]] = np.array(rows[i], copy=True)
        return out

    def write(self, kind, values):
        """``values``: {attribute: {prim path: row, or an array of axes for joints}}; a group
        publishes every prim it maps, so each must be given."""
        import numpy as np
        from ovphysx.types import SimObjectType

        names = list(values)
        with self.physx.write_sync(kind, names) as session:
            for group in session.groups:
                table = values[names[group.attribute_index]]
                paths = self.paths.get_path_strings(group.prim_list)
                fills = []
                for i in range(group.prim_count):
                    path = paths[group.prim_offset + i]
                    if path not in table:
                        raise RuntimeError(f"no value to write for {path}")
                    fills.append(np.asarray(table[path], dtype=np.float32))
                if kind == SimObjectType.ARTICULATION_JOINT:  # one tensor per joint
                    for tensor, fill in zip(group.tensors, fills, strict=True):
                        tensor.assign(fill.reshape(tuple(tensor.shape)))
                else:
                    group.tensors[0].assign(np.stack(fills).reshape(tuple(group.tensors[0].shape)))
                session.commit_sync(group)


def _attr_index(group, attributes, dictionary):
    """Which requested attribute a read group holds (groups come in no promised order)."""
    name = dictionary.token_to_string(group.attribute)
    if name not in attributes:
        raise RuntimeError(f"read group for an attribute not asked for ({name})")
    return attributes.index(name)


# --- the scenarios ----------------------------------------------------------------------------


def _robot_run(req, scenario, folder):
    setup = req["setup"]
    floor = scenario == "drop"
    info = _inspect(req["usd"], req["root"], setup.get("feet") or (), setup.get("names"))
    mu = info["mu"]
    _, path = _scene_layer(
        folder,
        req["usd"],
        info,
        weld=not floor,
        floor_mu=(mu if mu is not None else _PHYSX_DEFAULT_MU) if floor else None,
    )
    sim = _Sim(path)
    try:
        return _simulate(sim, req, info, scenario, floor, mu)
    finally:
        sim.close()


def _home(sim, info, setup):
    """The joints at the home pose, still, their drives targeting it: (the joints' properties as
    PhysX read them, driven joint path -> (name, scale to PhysX units), the targets written), or
    why not."""
    import numpy as np
    from ovphysx.types import SimObjectType as T

    mpu = info["mpu"]
    props = sim.read(T.ARTICULATION_JOINT, ["jointStiffness", "jointDamping", "jointMaxForce", "jointPosition"])
    # Joint prim -> (name, scale from SI to PhysX units): degrees for angular axes, stage units for linear.
    driven = {}
    for path, q in props["jointPosition"].items():
        if path not in info["joints"] or q.size != 1:
            continue
        name, kind = info["joints"][path]
        if name in setup["pose"]:
            driven[path] = (name, math.degrees(1.0) if kind == "angular" else 1.0 / mpu)
    if setup["pose"] and not driven:
        return "none of the robot's driven joints is in the file"
    every_joint = props["jointPosition"]
    # Driven joints at the home pose, and mimic followers where their leader puts them
    # (Setup.start): a follower left at the file's 0 starts its mimic constraint violated.
    start = setup.get("start", setup["pose"])
    target = {}
    for p, v in every_joint.items():
        name, kind = info["joints"].get(p, ("", ""))
        scale = math.degrees(1.0) if kind == "angular" else 1.0 / mpu
        target[p] = np.array([start[name] * scale]) if v.size == 1 and name in start else np.array(v, copy=True)
    zeros = {p: np.zeros_like(v) for p, v in every_joint.items()}
    sim.write(T.ARTICULATION_JOINT, {"jointPosition": target, "jointVelocity": zeros, "jointPositionTarget": target})
    return props, driven, target


def _stand(req):
    """The stand on a world: the world stage as written (its terrain, gravity and step), the robot's
    joints at the home pose and its root at the spawn (``setup.world.spawn``: x, y, z, yaw); the
    feet's link poses at the start and the end, and the contact sensors' net normal force (the
    ``PhysxContactReportAPI`` links), averaged over the last quarter second."""
    import numpy as np
    from ovphysx.types import SimObjectType as T

    setup = req["setup"]
    world = setup["world"]
    info = _inspect(req["usd"], req["root"], world["feet"])
    mpu = info["mpu"]
    sim = _Sim(req["usd"])
    binding = None
    try:
        posed = _home(sim, info, setup)
        if isinstance(posed, str):
            return {"scenario": "stand", "ok": False, "error": posed}
        x, y, z, yaw = world["spawn"]
        roots = sim.read(T.ARTICULATION, ["rootPosition"])["rootPosition"]
        mine = [p for p in roots if p == info["root"]] or list(roots)[:1]
        sim.write(
            T.ARTICULATION,
            {
                "rootPosition": {p: ([x / mpu, y / mpu, z / mpu] if p in mine else roots[p]) for p in roots},
                "rootOrientation": {
                    p: ([0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)] if p in mine else [0.0, 0.0, 0.0, 1.0])
                    for p in roots
                },
            },
        )
        feet = _link_paths(req["usd"], world["feet"])
        sensors = list(_link_paths(req["usd"], world["sensors"]).values())
        if sensors:
            binding = sim.physx.create_contact_binding(sensor_patterns=sensors)
        start = _link_poses(sim, feet, mpu)
        dt = setup["timestep"]
        steps = max(1, round(world["duration"] / dt))
        window = max(1, round(0.25 / dt))
        total = np.zeros(3)
        out = np.zeros((len(sensors), 3), dtype=np.float32)
        for step in range(steps):
            sim.physx.step_sync(dt)
            if binding is not None and step >= steps - window:
                sim.physx.wait_all()
                binding.read_net_normal_forces(out)
                total += out.sum(axis=0)
        end = _link_poses(sim, feet, mpu)
        root = sim.read(T.ARTICULATION, ["rootPosition", "rootOrientation"])
        pos = root["rootPosition"][mine[0]] * mpu
        qx, qy = (float(c) for c in root["rootOrientation"][mine[0]][:2])
        if not np.all(np.isfinite(pos)):
            return {"scenario": "stand", "ok": False, "error": "state not finite at the end"}
        masses = sim.read(T.ARTICULATION_LINK, ["mass"])["mass"]
        robot_mass = sum(float(m[0]) for p, m in masses.items() if p.startswith(info["root"].rsplit("/", 1)[0]))
        return {
            "scenario": "stand",
            "ok": True,
            "error": "",
            "height": float(pos[2]),
            "tilt": math.acos(max(-1.0, min(1.0, 1.0 - 2.0 * (qx * qx + qy * qy)))),
            "feet_start": start,
            "feet_end": end,
            "mass": robot_mass,
            "contact_sum": float(total[2] / window) * mpu if binding is not None else None,
        }
    finally:
        if binding is not None:
            binding.destroy()
        sim.close()


def _link_paths(usd, names):
    """Link name -> its rigid body's prim path in the stage (by displayName, else prim name)."""
    from pxr import Usd, UsdPhysics

    stage = Usd.Stage.Open(usd)
    out = {}
    for prim in stage.Traverse():
        if prim.HasAPI(UsdPhysics.RigidBodyAPI):
            label = prim.GetMetadata("displayName") or prim.GetName()
            if label in names and label not in out:
                out[label] = str(prim.GetPath())
    return out


def _link_poses(sim, paths, mpu):
    """Link name -> [x, y, z, qw, qx, qy, qz] (m) of the links at ``paths`` (name -> prim path)."""
    from ovphysx.types import SimObjectType as T

    rows = sim.read(T.ARTICULATION_LINK, ["position", "orientation"])
    out = {}
    for name, path in paths.items():
        if path in rows["position"]:
            p, q = rows["position"][path] * mpu, rows["orientation"][path]
            out[name] = [float(p[0]), float(p[1]), float(p[2]), float(q[3]), float(q[0]), float(q[1]), float(q[2])]
    return out


def _simulate(sim, req, info, scenario, floor, mu):
    from ovphysx.types import SimObjectType as T

    setup = req["setup"]
    mpu = info["mpu"]
    posed = _home(sim, info, setup)
    if isinstance(posed, str):
        return {"scenario": scenario, "ok": False, "error": posed}
    props, driven, target = posed
    roots = sim.read(T.ARTICULATION, ["rootPosition"])["rootPosition"]
    if floor:
        spawn = [info["root_pos"][0], info["root_pos"][1], (setup["stand_height"] + setup["drop_clearance"]) / mpu]
        sim.write(
            T.ARTICULATION,
            {"rootPosition": {p: spawn for p in roots}, "rootOrientation": {p: [0.0, 0.0, 0.0, 1.0] for p in roots}},
        )
    # Each drive's torque, from its gains as PhysX read them: PhysX's drive is implicit, so the
    # force it applied over a step is kp (target - q) - kd qd at the step's end, clamped to maxForce.
    gains = {
        p: (
            float(props["jointStiffness"][p][0]),
            float(props["jointDamping"][p][0]),
            float(props["jointMaxForce"][p][0]),
        )
        for p in driven
    }
    dt = setup["timestep"]
    steps = max(1, round(setup["duration"] / dt))
    every = max(1, round(_SAMPLE / dt))
    run = {"scenario": scenario, "ok": True, "error": "", "mu": mu, "trajectory": []}
    if floor:  # the total mass PhysX read: a drop that settles apart may weigh apart
        masses = sim.read(T.ARTICULATION_LINK, ["mass"])["mass"]
        run["mass"] = float(sum(float(m[0]) for m in masses.values()))
    peak = {driven[p][0]: 0.0 for p in driven}
    heights = []
    for step in range(steps):
        sim.physx.step_sync(dt)
        state = sim.read(T.ARTICULATION_JOINT, ["jointPosition", "jointVelocity"])
        q = {p: float(state["jointPosition"][p][0]) for p in driven}
        if not all(math.isfinite(v) for v in q.values()):
            return {**run, "ok": False, "error": f"state not finite after {(step + 1) * dt:.3g} s"}
        for p, (kp, kd, fmax) in gains.items():
            tau = kp * (float(target[p][0]) - q[p]) - kd * float(state["jointVelocity"][p][0])
            tau = min(abs(tau), fmax) if fmax > 0 else abs(tau)
            # Effort per degree converts back through the same scale: N·m for angular, N for linear.
            name = driven[p][0]
            peak[name] = max(peak[name], tau)
        if (step + 1) % every == 0:
            run["trajectory"].append([(step + 1) * dt, {driven[p][0]: v / driven[p][1] for p, v in q.items()}])
            if floor:
                record = bool(setup.get("record"))
                names = ["rootPosition", "rootOrientation"] if record else ["rootPosition"]
                now = sim.read(T.ARTICULATION, names)
                xyz = [float(c) * mpu for c in next(iter(now["rootPosition"].values()))]
                heights.append([(step + 1) * dt, xyz[2]])
                if record:  # ovphysx's quaternions are x, y, z, w; the answer's w, x, y, z
                    qx, qy, qz, qw = (float(c) for c in next(iter(now["rootOrientation"].values())))
                    run.setdefault("root", []).append([(step + 1) * dt, [*xyz, qw, qx, qy, qz]])
    final = {driven[p][0]: v / driven[p][1] for p, v in q.items()}
    pose = setup["pose"]
    worst = max(((abs(v - pose[n]), n) for n, v in final.items()), default=(0.0, ""))
    run.update(final_q=final, drift=worst[0], worst_joint=worst[1], peak_effort=peak)
    if floor:
        root = sim.read(T.ARTICULATION, ["rootPosition", "rootOrientation"])
        z = float(next(iter(root["rootPosition"].values()))[2]) * mpu
        qx, qy = (float(c) for c in next(iter(root["rootOrientation"].values()))[:2])
        run.update(height=z, heights=heights, tilt=math.acos(max(-1.0, min(1.0, 1.0 - 2.0 * (qx * qx + qy * qy)))))
    return run


def _block_travel(mu, angle, setup, folder):
    """A block of friction mu on a horizontal plane with gravity tilted by ``angle``: the same as a
    tilted plane. Distance moved in the run."""
    import numpy as np
    from ovphysx.types import SimObjectType as T
    from pxr import Gf, UsdGeom, UsdPhysics, UsdShade

    g = 9.81
    gravity = (g * math.sin(angle), 0.0, -g * math.cos(angle))
    stage, path = _scene_layer(folder, None, None, weld=False, floor_mu=mu, gravity=gravity)
    cube = UsdGeom.Cube.Define(stage, "/Block")
    cube.CreateSizeAttr().Set(1.0)
    cube.AddTranslateOp().Set(Gf.Vec3d(0.0, 0.0, _BOX_H + 1e-4))
    cube.AddScaleOp().Set(Gf.Vec3f(2 * _BOX, 2 * _BOX, 2 * _BOX_H))
    UsdPhysics.RigidBodyAPI.Apply(cube.GetPrim())
    UsdPhysics.CollisionAPI.Apply(cube.GetPrim())
    UsdPhysics.MassAPI.Apply(cube.GetPrim()).CreateMassAttr().Set(1.0)
    material = UsdShade.Material(stage.GetPrimAtPath("/DynamicsFloorMaterial"))
    UsdShade.MaterialBindingAPI.Apply(cube.GetPrim()).Bind(material, UsdShade.Tokens.weakerThanDescendants, "physics")
    stage.GetRootLayer().Save()
    sim = _Sim(path)
    try:
        start = next(iter(sim.read(T.RIGID_BODY, ["position"])["position"].values()))
        for _ in range(max(1, round(setup["duration"] / setup["timestep"]))):
            sim.physx.step_sync(setup["timestep"])
        end = next(iter(sim.read(T.RIGID_BODY, ["position"])["position"].values()))
    finally:
        sim.close()
    return float(np.linalg.norm(np.asarray(end) - np.asarray(start)))


def _slide(req, mu, folder):
    from worker_loop import slide_run

    setup = req["setup"]
    if mu is None:
        mu = _inspect(req["usd"], req["root"], setup.get("feet") or (), setup.get("names"))["mu"]
    return slide_run("PhysX", mu, lambda angle: _block_travel(mu, angle, setup, _sub(folder, f"{angle:.6f}")))


def _sub(folder, name):
    path = os.path.join(folder, name)
    os.makedirs(path, exist_ok=True)
    return path


def _version():
    import ovphysx

    return ovphysx.__version__


if __name__ == "__main__":
    from worker_loop import serve

    with tempfile.TemporaryDirectory(prefix="robodesc-physx-") as scratch:

        def _scenario(req, name, mu):
            folder = _sub(scratch, name)
            if name == "stand":
                return _stand(req)
            return _slide(req, mu, folder) if name == "slide" else _robot_run(req, name, folder)

        serve("physx", _version, _scenario)
