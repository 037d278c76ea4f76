"""The scenarios in MuJoCo, from a URDF (robodesc's output, or the source itself) or an MJCF file.

A URDF carries no actuators: a position actuator per driven joint is added with ``MjSpec`` from the
compile's gains (kp, kv in SI per rad or m), as a URDF consumer configures them. An MJCF file
brings its own actuators: they are used as written, targets set to the home pose, so a wrong gain
in the MJCF shows up as a hold the other engines do not share.
"""

from __future__ import annotations

import math
import os
import time
from typing import Any

import mujoco
import numpy as np

from robodesc.ir.model import Robot
from robodesc.validation.dynamics.result import Run, settle_time
from robodesc.validation.dynamics.scenarios import Setup, slide_angles
from robodesc.validation.dynamics.verdict import SOURCE
from robodesc.validation.mujoco_load import add_floating_base, captured_warnings, load_urdf_in_mujoco
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import ValidationReport

ENGINE = "mujoco"
_SAMPLE = 0.01  # s between trajectory samples
_BOX = 0.05  # m: half length and width of the slide block
# Half its height: a flat block tips only past tan = _BOX / _BOX_H = 5, so it slides, not rolls, at
# tan = 1.3 mu up to mu 3.8 (a cube tipped over from mu 0.77 on: rolling, not friction, set its travel).
_BOX_H = 0.01  # m
# Implicit in the drives' velocity terms: MuJoCo's default Euler is explicit in an actuator's kv,
# and kv = 1 N·m·s/rad on a 10 g fingertip is unstable at any usable time step (Drake's PD and
# Newton's MuJoCo solver are implicit too). A URDF names no integrator; an MJCF's own is kept.
_INTEGRATOR = mujoco.mjtIntegrator.mjINT_IMPLICITFAST


def load_spec(robot: Robot, path: str, kind: str, package_paths: dict[str, str]) -> tuple[Any, str]:
    """(MjSpec, why not) for a URDF or MJCF file; the spec is None when MuJoCo refuses it."""
    if kind == "mjcf":
        try:
            return mujoco.MjSpec.from_file(path), ""
        except ValueError as exc:
            return None, str(exc).strip()
    with open(path, encoding="utf-8") as fh:
        text = fh.read()
    scratch = ValidationReport(robot=robot.name, target=kind, consumer=ENGINE)
    loaded = load_urdf_in_mujoco(
        robot, text, os.path.dirname(os.path.abspath(path)), ValidateOptions(package_paths=package_paths), scratch
    )
    if loaded is None:
        failed = [c.message for c in scratch.checks if c.status.value == "fail"]
        return None, (failed[0] if failed else "MuJoCo refused the file")
    return loaded.spec, ""


def run_all(robot: Robot, spec: Any, kind: str, setup: Setup, scenarios: tuple[str, ...]) -> list[Run]:
    out: list[Run] = []
    for scenario in scenarios:
        started = time.perf_counter()
        run = Run(ENGINE, kind, scenario)
        try:
            if scenario == "hold-fixed":
                _hold(robot, spec, kind, setup, run)
            elif scenario == "drop":
                _drop(robot, spec, kind, setup, run)
            elif scenario == "slide":
                _slide(spec, setup, run)
        except (ValueError, RuntimeError) as exc:  # MuJoCo raises ValueError for what it refuses
            run.ok, run.error = False, str(exc).strip().splitlines()[0][:200]
        run.seconds = time.perf_counter() - started
        out.append(run)
    return out


def _actuate(spec: Any, kind: str, setup: Setup) -> None:
    if kind == "mjcf" and len(spec.actuators):
        return  # the file's own drives
    for name, (kp, kd) in setup.gains.items():
        if spec.joint(name) is None:
            continue
        act = spec.add_actuator(name=f"drive_{name}", target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.set_to_position(kp=kp, kv=kd)


def _joint_addresses(model: Any, setup: Setup) -> dict[str, int]:
    out = {}
    for name in setup.pose:
        jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if jid >= 0:
            out[name] = int(model.jnt_qposadr[jid])
    return out


def _start(model: Any, data: Any, setup: Setup) -> dict[str, int]:
    addr = _joint_addresses(model, setup)
    for name, value in setup.start().items():
        jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if jid >= 0:
            data.qpos[int(model.jnt_qposadr[jid])] = value
    for i in range(model.nu):
        jid = int(model.actuator_trnid[i, 0])
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, jid)
        if name in setup.pose:
            data.ctrl[i] = setup.pose[name]
    return addr


def _simulate(model: Any, data: Any, setup: Setup, run: Run, addr: dict[str, int], root: int | None = None) -> bool:
    if setup.pose and not addr:
        run.ok, run.error = False, "none of the robot's driven joints is in the file"
        return False
    steps = max(1, round(setup.duration / setup.timestep))
    every = max(1, round(_SAMPLE / setup.timestep))
    heights: list[tuple[float, float]] = []
    drives = _drive_joints(model)
    dofs = np.array(list(drives), dtype=int)
    peak = np.zeros(len(dofs))
    # MuJoCo's warnings (a bad acceleration) are collected, not appended to MUJOCO_LOG.TXT in the
    # user's working folder; the run's numbers say what went wrong.
    with captured_warnings([]):
        for step in range(steps):
            mujoco.mj_step(model, data)
            if not np.all(np.isfinite(data.qpos)):
                run.ok, run.error = False, f"state not finite after {(step + 1) * setup.timestep:.3g} s"
                return False
            np.maximum(peak, np.abs(data.qfrc_actuator[dofs]), out=peak)
            if (step + 1) % every == 0:
                q = {n: float(data.qpos[a]) for n, a in addr.items()}
                run.trajectory.append(((step + 1) * setup.timestep, q))
                if root is not None:
                    heights.append(((step + 1) * setup.timestep, float(data.xpos[root][2])))
                    if setup.record:
                        pose = (*data.xpos[root], *data.xquat[root])  # MuJoCo's quaternions are w, x, y, z
                        run.root.append(((step + 1) * setup.timestep, tuple(float(c) for c in pose)))
    run.settle = settle_time(heights) if root is not None else None
    run.final_q = {n: float(data.qpos[a]) for n, a in addr.items()}
    worst = max(((abs(q - setup.pose[n]), n) for n, q in run.final_q.items()), default=(0.0, ""))
    run.drift, run.worst_joint = worst
    run.set_peaks({name: float(peak[i]) for i, name in enumerate(drives.values())}, setup.effort)
    return True


def _drive_joints(model: Any) -> dict[int, str]:
    """DOF address -> name of each joint an actuator drives (the runner's drives, or an MJCF's own).
    Its effort is read from ``qfrc_actuator``: what the joint receives, after the joint's own
    ``actuatorfrcrange`` (the URDF's effort limit) clamps it; ``actuator_force`` is not clamped."""
    out = {}
    for i in range(model.nu):
        if int(model.actuator_trntype[i]) == int(mujoco.mjtTrn.mjTRN_JOINT):
            jid = int(model.actuator_trnid[i, 0])
            name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, jid)
            if name:
                out[int(model.jnt_dofadr[jid])] = name
    return out


def _colliders(spec: Any) -> list[Any]:
    """The geoms that collide: an MJCF's visual geoms (contype and conaffinity 0, robodesc's
    ``visual`` class) touch nothing and must stay so."""
    return [g for g in spec.geoms if int(g.contype) or int(g.conaffinity)]


def _no_self_contact(spec: Any) -> None:
    """Robot colliders touch the floor only: convex hulls of meshes overlap on most robots and
    their pushes are not what these scenarios measure. Visual geoms stay out of contact."""
    for geom in _colliders(spec):
        geom.contype, geom.conaffinity = 1, 0


def _hold(robot: Robot, spec: Any, kind: str, setup: Setup, run: Run) -> None:
    s = spec.copy()
    for body in s.bodies:  # weld the root (an MJCF or a prior step may have freed it)
        for joint in list(body.joints):
            if joint.type == mujoco.mjtJoint.mjJNT_FREE:
                s.delete(joint)
    for key in list(s.keys):  # a keyframe's qpos counts the free joint just removed
        s.delete(key)
    _actuate(s, kind, setup)
    for name, armature in setup.source_armature.items() if kind == SOURCE else ():
        joint = s.joint(name)
        if joint is not None and not joint.armature:
            joint.armature = armature
    s.option.timestep = setup.timestep
    if kind != "mjcf":
        s.option.integrator = _INTEGRATOR
    s.option.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONTACT)
    model = s.compile()
    run.mass = _weighed(robot, model)
    if kind == "mjcf":
        run.armature = {j.name: float(j.armature) for j in s.joints if j.name and j.armature}
    data = mujoco.MjData(model)
    addr = _start(model, data, setup)
    _simulate(model, data, setup, run, addr)


def _weighed(robot: Robot, model: Any) -> float:
    """The robot's mass as MuJoCo holds it: every body's, plus the links fused into the world body.
    An MJCF welds a fixed base by writing it (and the links fixed to it: merge_fixed) into
    ``<worldbody>``, where MuJoCo weighs nothing, since it never moves; the structural check leaves
    those links out the same way (validation/compare.py). Without this, ur5's held MJCF read 4 kg
    light and `validate --dynamics` failed a file that carries every gram."""
    total = float(model.body_mass.sum())
    try:
        root = robot.root
    except ValueError:
        return total
    if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, root.name) > 0:
        return total  # the root is a body of its own: nothing was fused into the world
    children = robot.child_joints()
    fused: list[str] = []
    stack = [root.name]
    while stack:
        name = stack.pop()
        fused.append(name)
        stack.extend(
            j.child
            for j in children.get(name, [])
            if j.type.dof == 0 and mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, j.child) <= 0
        )
    links = robot.link_map()
    for name in fused:
        inertial = links[name].inertial if name in links else None
        if inertial is not None and inertial.mass is not None:
            total += float(inertial.mass)
    return total


def _robot_mu(spec: Any, feet: tuple[str, ...] = ()) -> float:
    """The sliding friction MuJoCo gives the robot's colliders (the most common one): its feet's
    when it stands on some (``Setup.feet``), else all of them."""
    geoms = _colliders(spec)
    on_feet = [g for g in geoms if _body_name(g) in feet]
    values = [round(float(g.friction[0]), 9) for g in on_feet or geoms]
    return max(set(values), key=values.count) if values else 1.0


def _body_name(geom: Any) -> str:
    parent = geom.parent
    return str(parent.name) if parent is not None else ""


def _drop(robot: Robot, spec: Any, kind: str, setup: Setup, run: Run) -> None:
    s = spec.copy()
    add_floating_base(s, robot)
    _actuate(s, kind, setup)
    mu = _robot_mu(s, setup.feet)
    _no_self_contact(s)
    run.mu = mu
    # Equal friction on both sides: MuJoCo takes the larger, Drake a harmonic mean, Newton its own
    # rule; all of them give mu when the two are equal.
    s.worldbody.add_geom(
        name="dyn_floor",
        type=mujoco.mjtGeom.mjGEOM_PLANE,
        size=[0, 0, 1],
        contype=0,
        conaffinity=1,
        friction=[mu, 0.005, 0.0001],
    )
    s.option.timestep = setup.timestep
    if kind != "mjcf":
        s.option.integrator = _INTEGRATOR
    model = s.compile()
    run.mass = _weighed(robot, model)
    data = mujoco.MjData(model)
    addr = _start(model, data, setup)
    root = _free_root(model)
    if root is None:
        run.ok, run.error = False, "no free root body"
        return
    qadr = int(model.jnt_qposadr[root])
    data.qpos[qadr + 2] = setup.stand_height + setup.drop_clearance
    body = int(model.jnt_bodyid[root])
    if _simulate(model, data, setup, run, addr, body):
        run.height = float(data.xpos[body][2])
        run.tilt = math.acos(max(-1.0, min(1.0, float(data.xmat[body][8]))))


def _free_root(model: Any) -> int | None:
    for j in range(model.njnt):
        if int(model.jnt_type[j]) == int(mujoco.mjtJoint.mjJNT_FREE):
            return j
    return None


def _slide(spec: Any, setup: Setup, run: Run) -> None:
    mu = _robot_mu(spec, setup.feet)
    run.mu = mu
    stick, slide = slide_angles(mu)
    run.stick = _block_travel(mu, stick, setup)
    run.slide = _block_travel(mu, slide, setup)


def _block_travel(mu: float, angle: float, setup: Setup) -> float:
    """A 1 kg block, friction mu on both sides, on a plane tilted by ``angle``: distance moved."""
    s = mujoco.MjSpec()
    s.option.timestep = setup.timestep
    s.option.integrator = _INTEGRATOR
    s.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC  # the Coulomb cone, as Drake's and Newton's
    c, sn = math.cos(angle / 2), math.sin(angle / 2)
    s.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 1], quat=[c, 0, sn, 0], friction=[mu, 0, 0])
    normal = np.array([math.sin(angle), 0.0, math.cos(angle)])
    body = s.worldbody.add_body(pos=list(normal * (_BOX_H + 1e-4)), quat=[c, 0, sn, 0])
    body.add_freejoint()
    body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[_BOX, _BOX, _BOX_H], mass=1.0, friction=[mu, 0, 0], condim=3)
    model = s.compile()
    data = mujoco.MjData(model)
    with captured_warnings([]):  # see _simulate
        mujoco.mj_forward(model, data)
        start = data.qpos[:3].copy()
        for _ in range(max(1, round(setup.duration / setup.timestep))):
            mujoco.mj_step(model, data)
    return float(np.linalg.norm(data.qpos[:3] - start))


def run_file(
    robot: Robot, path: str, kind: str, setup: Setup, options: Any, scenarios: tuple[str, ...]
) -> list[Run] | str:
    """The runner contract of :mod:`.run`: the runs, or why the file could not be loaded."""
    if scenarios == ("stand",):
        return [stand_scene(path, kind, setup)]
    spec, why = load_spec(robot, path, "mjcf" if kind == "mjcf" else "urdf", dict(options.package_paths))
    if spec is None:
        return f"MuJoCo cannot load it: {why}"
    return run_all(robot, spec, kind, setup, scenarios)


# s: the contact sensors are averaged over the stand's last quarter second (a robot on drives sways).
SENSOR_WINDOW = 0.25


def stand_scene(path: str, kind: str, setup: Setup) -> Run:
    """The stand on a world: MJCF's scene.xml (the terrain's hfield, the robot included) from its
    ``home`` keyframe (the stance at the spawn point, drive targets at the stance), run for the
    world's duration; the feet's poses at the start and the end, and the touch sensors, summed."""
    started = time.perf_counter()
    run = Run(ENGINE, kind, "stand")
    world = setup.world
    assert world is not None
    try:
        model = mujoco.MjModel.from_xml_path(path)
    except ValueError as exc:
        run.ok, run.error = False, f"MuJoCo cannot load {os.path.basename(path)}: {str(exc).strip()[:200]}"
        return run
    data = mujoco.MjData(model)
    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    mujoco.mj_resetDataKeyframe(model, data, max(key, 0))
    mujoco.mj_forward(model, data)
    root = _free_root(model)
    if root is None:
        run.ok, run.error = False, "no free root body in the scene"
        return run
    body = int(model.jnt_bodyid[root])
    feet = _foot_frames(model, world.soles)
    touch = [
        int(model.sensor_adr[i]) for i in range(model.nsensor) if model.sensor_type[i] == mujoco.mjtSensor.mjSENS_TOUCH
    ]
    run.feet_start = {n: _pose(data, f) for n, f in feet.items()}
    steps = max(1, round(world.duration / model.opt.timestep))
    window = max(1, round(SENSOR_WINDOW / model.opt.timestep))
    sensed = 0.0
    with captured_warnings([]):
        for step in range(steps):
            mujoco.mj_step(model, data)
            if not np.all(np.isfinite(data.qpos)):
                run.ok, run.error = False, f"state not finite after {(step + 1) * model.opt.timestep:.3g} s"
                return run
            if step >= steps - window and touch:
                sensed += float(sum(data.sensordata[a] for a in touch))
    run.feet_end = {n: _pose(data, f) for n, f in feet.items()}
    run.height = float(data.xpos[body][2])
    run.tilt = math.acos(max(-1.0, min(1.0, float(data.xmat[body][8]))))
    run.mass = float(model.body_mass.sum())
    run.weight = run.mass * float(np.linalg.norm(model.opt.gravity))
    run.contact_sum = sensed / window if touch else None
    run.seconds = time.perf_counter() - started
    return run


def _foot_frames(model: Any, names: Any) -> dict[str, tuple[str, int]]:
    """Each foot link's frame in the scene: its body, or the site a merged fixed link became
    (``--merge-fixed``, on for MJCF: Spirit's toes are sites of its lower legs)."""
    out = {}
    for name in names:
        body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name)
        site = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, name)
        if body >= 0:
            out[name] = ("body", body)
        elif site >= 0:
            out[name] = ("site", site)
    return out


def _pose(data: Any, frame: tuple[str, int]) -> list[float]:
    kind, i = frame
    if kind == "body":
        return [*(float(v) for v in data.xpos[i]), *(float(v) for v in data.xquat[i])]
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, data.site_xmat[i])
    return [*(float(v) for v in data.site_xpos[i]), *(float(v) for v in quat)]
