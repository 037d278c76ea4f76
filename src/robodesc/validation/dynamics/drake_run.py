"""The scenarios in Drake, from robodesc's SDF (or the source URDF, for the source comparison).

A MultibodyPlant in discrete time (the timestep of the setup) with the SAP contact solver, the one
that runs joint actuators' implicit PD gains: one actuator per driven joint, gains from the compile
(SI), effort limit the joint's, the desired state the home pose. Drake reads both files with its
own parser, so a difference between the SDF run and the URDF run is in what robodesc wrote.
"""

from __future__ import annotations

import logging
import math
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from robodesc.ir.model import Robot
from robodesc.validation.dynamics.result import READS_DIFFERENTLY, Run, settle_time
from robodesc.validation.dynamics.scenarios import Setup, slide_angles

ENGINE = "drake"
_SAMPLE = 0.01  # s
_BOX, _BOX_H = 0.05, 0.01  # m: the slide block's half length and height (mujoco_run: why flat)


def run_file(
    robot: Robot, path: str, kind: str, setup: Setup, options: Any, scenarios: tuple[str, ...]
) -> list[Run] | str:
    try:
        import pydrake.multibody.plant  # noqa: F401
    except ImportError as exc:
        return f"not available: {exc}"
    # The parser's warnings (a Gazebo <plugin> it ignores) are the SDF check's business, not this.
    logging.getLogger("drake").setLevel(logging.ERROR)
    out: list[Run] = []
    for scenario in scenarios:
        started = time.perf_counter()
        run = Run(ENGINE, kind, scenario)
        try:
            if scenario == "slide":
                known = [r.mu for r in out if r.mu is not None]
                _slide(robot, path, options, setup, run, known[0] if known else None)
            else:
                _robot_run(robot, path, options, setup, run, floor=scenario == "drop")
        except RuntimeError as exc:  # Drake raises RuntimeError for files and states it refuses
            message = str(exc).strip().splitlines()[0][:200] if str(exc).strip() else type(exc).__name__
            if not out and scenario == scenarios[0] and "parse" in message.lower():
                return f"Drake cannot load it: {message}"
            if "greater than the given static friction" in message:
                # SDF's mu2 defaults to 1 and Drake reads mu/mu2 as static/dynamic: a source giving
                # only mu < 1 is carried as written, and Drake cannot take it (docs/contact.md).
                message = (
                    f"{READS_DIFFERENTLY} Drake reads SDF's mu and mu2 as static and dynamic friction, and the "
                    f"source gives mu below 1 without mu2 (SDF's default 1): {message}"
                )
            run.ok, run.error = False, message
        run.seconds = time.perf_counter() - started
        out.append(run)
    return out


def _plant(timestep: float) -> tuple[Any, Any, Any]:
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph, DiscreteContactApproximation
    from pydrake.systems.framework import DiagramBuilder

    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=timestep)
    plant.set_discrete_contact_approximation(DiscreteContactApproximation.kSap)
    return builder, plant, scene_graph


def _parse(
    plant: Any, robot: Robot, path: str, options: Any, *, collisions: bool = True, shapes: bool = True
) -> list[Any]:
    from pydrake.multibody.parsing import Parser

    from robodesc.validation.dynamics.drake_meshes import drake_readable

    parser = Parser(plant)
    for name, root in dict(options.package_paths).items():
        if not parser.package_map().Contains(name):
            parser.package_map().Add(name, root)
    readable = drake_readable(robot, path, options.package_paths, collisions=collisions, shapes=shapes)
    return list(parser.AddModels(Path(readable)))


def _root_body(plant: Any, robot: Robot, models: list[Any]) -> Any:
    """The tree's root: the body no joint moves. Not looked up by name: SDF cannot name a link
    ``world`` (robodesc writes ``world_link``), and a URDF's ``world`` is Drake's world body."""
    children = {plant.get_joint(i).child_body().index() for i in plant.GetJointIndices()}
    roots = robot.root_links()
    candidates = [
        plant.get_body(i)
        for model in models
        for i in plant.GetBodyIndices(model)
        if i not in children and i != plant.world_body().index()
    ]
    named = [b for b in candidates if roots and b.name() == roots[0].name]
    return (named or candidates or [plant.get_body(plant.GetBodyIndices(models[0])[0])])[0]


def _robot_mu(
    plant: Any, scene_graph: Any, models: list[Any], feet: tuple[str, ...] = ()
) -> tuple[float | None, list[Any]]:
    """(the most common sliding friction of the robot's colliders, their geometry ids): the feet's
    friction when the robot stands on some (``Setup.feet``), else all colliders'."""
    inspector = scene_graph.model_inspector()
    values: list[float] = []
    on_feet: list[float] = []
    ids: list[Any] = []
    for model in models:
        for index in plant.GetBodyIndices(model):
            body = plant.get_body(index)
            for gid in plant.GetCollisionGeometriesForBody(body):
                ids.append(gid)
                props = inspector.GetProximityProperties(gid)
                if props is not None and props.HasProperty("material", "coulomb_friction"):
                    value = round(props.GetProperty("material", "coulomb_friction").dynamic_friction(), 9)
                    values.append(value)
                    if body.name() in feet:
                        on_feet.append(value)
    values = on_feet or values
    return (max(set(values), key=values.count) if values else None), ids


def _robot_run(robot: Robot, path: str, options: Any, setup: Setup, run: Run, *, floor: bool) -> None:
    from pydrake.geometry import CollisionFilterDeclaration, GeometrySet, HalfSpace
    from pydrake.math import RigidTransform
    from pydrake.multibody.plant import CoulombFriction
    from pydrake.multibody.tree import PdControllerGains
    from pydrake.systems.analysis import Simulator
    from pydrake.systems.primitives import ConstantVectorSource

    builder, plant, scene_graph = _plant(setup.timestep)
    models = _parse(plant, robot, path, options, collisions=floor)
    root = _root_body(plant, robot, models)
    if not floor and not _is_welded(plant, root):
        plant.WeldFrames(plant.world_frame(), root.body_frame())
    mu, robot_geoms = _robot_mu(plant, scene_graph, models, setup.feet)
    run.mu = mu if floor else None
    if floor:
        friction = mu if mu is not None else 1.0
        plant.RegisterCollisionGeometry(
            plant.world_body(), RigidTransform(), HalfSpace(), "dyn_floor", CoulombFriction(friction, friction)
        )
    table = _joint_table(plant, models, robot)
    actuated: list[str] = []
    for name, (kp, kd) in setup.gains.items():
        joint = table.get(name)
        if joint is None or joint.num_velocities() != 1:
            continue
        effort = _effort(robot, name)
        actuator = plant.AddJointActuator(f"drive_{name}", joint, effort)
        actuator.set_controller_gains(PdControllerGains(p=kp, d=kd))
        actuated.append(name)
    plant.Finalize()
    # Robot colliders meet the floor only (as in the other engines).
    scene_graph.collision_filter_manager().Apply(CollisionFilterDeclaration().ExcludeWithin(GeometrySet(robot_geoms)))
    for model in models:
        if plant.num_actuated_dofs(model):
            src = builder.AddSystem(ConstantVectorSource(_desired_for(plant, model, setup, table)))
            builder.Connect(src.get_output_port(), plant.get_desired_state_input_port(model))
    diagram = builder.Build()
    simulator = Simulator(diagram)
    context = plant.GetMyMutableContextFromRoot(simulator.get_mutable_context())
    run.mass = float(plant.CalcTotalMass(context, models))
    for name, value in setup.start().items():
        joint = table.get(name)
        if joint is not None and joint.num_positions() == 1:
            _set_position(joint, context, value)
    if floor and _floating(root):
        plant.SetFreeBodyPose(context, root, RigidTransform(_vec(0.0, 0.0, setup.stand_height + setup.drop_clearance)))
    where = (lambda: plant.EvalBodyPoseInWorld(context, root)) if floor else None
    peaks = _watch_efforts(simulator, plant, table)
    _advance(simulator, context, table, setup, run, where)
    if run.ok:
        run.set_peaks(peaks, setup.effort)
    if run.ok and floor:
        pose = plant.EvalBodyPoseInWorld(context, root)
        run.height = float(pose.translation()[2])
        run.tilt = math.acos(max(-1.0, min(1.0, float(pose.rotation().matrix()[2, 2]))))


def _is_welded(plant: Any, body: Any) -> bool:
    """Before Finalize, a root the file joins to the world has a parent joint; a free one has none."""
    return _has_parent_joint(plant, body)


def _floating(body: Any) -> bool:
    check = getattr(body, "is_floating_base_body", None) or body.is_floating
    return bool(check())


def _set_position(joint: Any, context: Any, value: float) -> None:
    setter = getattr(joint, "set_angle", None) or joint.set_translation
    setter(context, value)


def _has_parent_joint(plant: Any, body: Any) -> bool:
    return any(plant.get_joint(i).child_body().index() == body.index() for i in plant.GetJointIndices())


def _joint_table(plant: Any, models: list[Any], robot: Robot) -> dict[str, Any]:
    """IR joint name -> Drake joint. By name, else by child link: robodesc's SDF keeps one
    namespace per model, so a joint named like a link is written ``<name>_joint``."""
    by_child = {
        plant.get_joint(i).child_body().name(): plant.get_joint(i)
        for i in plant.GetJointIndices()
        if plant.get_joint(i).model_instance() in models
    }
    out: dict[str, Any] = {}
    for joint in robot.joints:
        found = next((plant.GetJointByName(joint.name, m) for m in models if plant.HasJointNamed(joint.name, m)), None)
        out[joint.name] = found if found is not None else by_child.get(joint.child)
    return {k: v for k, v in out.items() if v is not None}


def _effort(robot: Robot, name: str) -> float:
    lim = robot.joint_map()[name].limit
    effort = lim.effort if lim is not None else None
    return float(effort) if effort is not None and effort > 0 else math.inf


def _desired_for(plant: Any, model: Any, setup: Setup, table: dict[str, Any]) -> Any:
    """[q_d, v_d] over ``model``'s actuated joints, in the plant's actuator order. Each joint by its
    IR name (``table``): the file may name it otherwise (the SDF's ``LF_HAA_joint`` for ANYmal C's
    ``LF_HAA``, a link's name too), and a Drake name looked up in the pose would target 0."""
    ir_name = {joint.index(): name for name, joint in table.items()}
    joints = [plant.get_joint_actuator(i).joint() for i in plant.GetJointActuatorIndices(model)]
    q = [setup.pose.get(ir_name.get(j.index(), j.name()), 0.0) for j in joints]
    return np.array(q + [0.0] * len(q))


def _advance(
    simulator: Any,
    context: Any,
    table: dict[str, Any],
    setup: Setup,
    run: Run,
    where: Callable[[], Any] | None = None,
) -> None:
    """Step to the end in samples of ``_SAMPLE``; ``where`` gives the free root's pose (a
    ``RigidTransform``) when the robot was dropped."""
    joints = {n: j for n in setup.pose if (j := table.get(n)) is not None and j.num_positions() == 1}
    if setup.pose and not joints:
        run.ok, run.error = False, "none of the robot's driven joints is in the file"
        return
    steps = max(1, round(setup.duration / _SAMPLE))
    q: dict[str, float] = {}
    heights: list[tuple[float, float]] = []
    for k in range(1, steps + 1):
        simulator.AdvanceTo(k * _SAMPLE)
        if where is not None:
            pose = where()
            heights.append((k * _SAMPLE, float(pose.translation()[2])))
            if setup.record:
                quat = pose.rotation().ToQuaternion()
                xyz_wxyz = (*pose.translation(), quat.w(), quat.x(), quat.y(), quat.z())
                run.root.append((k * _SAMPLE, tuple(float(c) for c in xyz_wxyz)))
        q = {n: float(j.GetOnePosition(context)) for n, j in joints.items()}
        if not all(math.isfinite(v) for v in q.values()):
            run.ok, run.error = False, f"state not finite after {k * _SAMPLE:.3g} s"
            return
        run.trajectory.append((k * _SAMPLE, q))
    run.final_q = q
    run.drift, run.worst_joint = max(((abs(v - setup.pose[n]), n) for n, v in q.items()), default=(0.0, ""))
    run.settle = settle_time(heights) if where is not None else None


def _watch_efforts(simulator: Any, plant: Any, table: dict[str, Any]) -> dict[str, float]:
    """Each driven joint's peak |actuation| (the PD drives' output, effort-limited), filled by a
    monitor the simulator calls after every discrete step: the 10 ms samples would miss an impact."""
    from pydrake.systems.framework import EventStatus

    by_joint = {j.index(): n for n, j in table.items()}
    drives = []
    for i in plant.GetJointActuatorIndices():
        actuator = plant.get_joint_actuator(i)
        name = by_joint.get(actuator.joint().index())
        if name is not None:
            drives.append((actuator.input_start(), name))
    peaks = {name: 0.0 for _, name in drives}
    if not drives:
        return peaks
    port = plant.get_net_actuation_output_port()

    def monitor(root: Any) -> Any:
        u = port.Eval(plant.GetMyContextFromRoot(root))
        for start, name in drives:
            peaks[name] = max(peaks[name], abs(float(u[start])))
        return EventStatus.Succeeded()

    simulator.set_monitor(monitor)
    return peaks


def _slide(robot: Robot, path: str, options: Any, setup: Setup, run: Run, mu: float | None) -> None:
    """The robot's friction as Drake reads it from the file (``mu`` when the drop already read
    it), on a block on two tilted planes."""
    if mu is None:
        _, plant, scene_graph = _plant(setup.timestep)
        models = _parse(plant, robot, path, options, shapes=False)
        mu, _ = _robot_mu(plant, scene_graph, models, setup.feet)
    if mu is None:
        run.ok, run.error = False, "Drake reads no collider from the file"
        return
    run.mu = mu
    stick, slide = slide_angles(run.mu)
    run.stick = _block_travel(run.mu, stick, setup)
    run.slide = _block_travel(run.mu, slide, setup)


def _block_travel(mu: float, angle: float, setup: Setup) -> float:
    from pydrake.geometry import Box, HalfSpace
    from pydrake.math import RigidTransform, RotationMatrix
    from pydrake.multibody.plant import CoulombFriction
    from pydrake.multibody.tree import SpatialInertia, UnitInertia
    from pydrake.systems.analysis import Simulator

    builder, plant, _ = _plant(setup.timestep)
    tilt = RotationMatrix.MakeYRotation(angle)
    friction = CoulombFriction(mu, mu)
    plant.RegisterCollisionGeometry(
        plant.world_body(), RigidTransform(tilt, _vec(0.0, 0.0, 0.0)), HalfSpace(), "plane", friction
    )
    inertia = SpatialInertia(1.0, _vec(0.0, 0.0, 0.0), UnitInertia.SolidBox(2 * _BOX, 2 * _BOX, 2 * _BOX_H))
    block = plant.AddRigidBody("block", inertia)
    plant.RegisterCollisionGeometry(block, RigidTransform(), Box(2 * _BOX, 2 * _BOX, 2 * _BOX_H), "block", friction)
    plant.Finalize()
    simulator = Simulator(builder.Build())
    context = plant.GetMyMutableContextFromRoot(simulator.get_mutable_context())
    normal = tilt.col(2)
    start = _vec(*(np.asarray(normal) * (_BOX_H + 1e-4)))
    plant.SetFreeBodyPose(context, block, RigidTransform(tilt, start))
    simulator.AdvanceTo(setup.duration)
    return float(np.linalg.norm(plant.EvalBodyPoseInWorld(context, block).translation() - start))


def _vec(*values: float) -> Any:
    """A float64 vector, typed loosely: pydrake's stubs want ndarray[float64] spelled their way."""
    return np.array(values, dtype=np.float64)
