"""An SDF file in Drake (libsdformat's frame semantics) against robodesc's IR of it.

Compared where the choice of link frame cannot change the answer: each body's mass, its centre of
mass and its inertia about that centre in the root body's frame, at random joint values. (The IR
puts a link's frame on its joint, SDF lets the link sit elsewhere: frames differ, bodies must not.)
Drake names a nested model's body ``link`` in the instance ``top::nested``; the IR, ``nested::link``.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from robodesc.ir.inertia import tensor
from robodesc.ir.model import JointType, Robot
from robodesc.ir.transforms import forward_kinematics, pose_matrix, resolve_mimic

TOL = 1e-9


@dataclass
class DrakeComparison:
    problems: list[str] = field(default_factory=list)
    bodies: int = 0
    max_com_error: float = 0.0
    max_inertia_error: float = 0.0


def _scoped(plant: Any, top: str, name: str, kind: str) -> Any:
    scope, _, local = name.rpartition("::")
    instance = plant.GetModelInstanceByName(f"{top}::{scope}" if scope else top)
    if kind == "body":
        return plant.GetBodyByName(local, instance)
    # Drake files a joint between models under its child's model: look it up by name alone then.
    return (
        plant.GetJointByName(local, instance) if plant.HasJointNamed(local, instance) else plant.GetJointByName(local)
    )


def compare_in_drake(
    sdf_path: str, robot: Robot, *, packages: dict[str, str] | None = None, samples: int = 4, seed: int = 0
) -> DrakeComparison:
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    out = DrakeComparison()
    plant = MultibodyPlant(0.0)
    parser = Parser(plant)
    for name, path in (packages or {}).items():
        parser.package_map().Add(name, path)
    parser.AddModels(sdf_path)
    plant.Finalize()
    top = robot.name
    bodies = {}
    for link in robot.links:
        try:
            bodies[link.name] = _scoped(plant, top, link.name, "body")
        except RuntimeError:
            if link.inertial is None:  # robodesc's own massless links (a universal joint's cross)
                continue
            out.problems.append(f"link {link.name!r} is not a body in Drake")
    out.bodies = len(bodies)
    rng = random.Random(seed)
    context = plant.CreateDefaultContext()
    for _ in range(samples):
        q: dict[str, float] = {}
        for joint in robot.joints:
            if joint.type.dof != 1 or joint.mimic is not None:
                continue
            lim = joint.limit
            lo = lim.lower if lim is not None and lim.lower is not None else -math.pi
            hi = lim.upper if lim is not None and lim.upper is not None else math.pi
            q[joint.name] = rng.uniform(lo, hi)
        q = resolve_mimic(robot, q)
        _set(plant, context, robot, top, q)
        fk = forward_kinematics(robot, q)
        root = robot.root.name
        x_wr = plant.EvalBodyPoseInWorld(context, bodies[root]).GetAsMatrix4()
        inv_r = np.linalg.inv(x_wr)
        for link in robot.links:
            body = bodies.get(link.name)
            if body is None:
                continue
            mass, com, inertia = _ir_body(link.inertial, inv_fk_root=np.linalg.inv(fk[root]) @ fk[link.name])
            spatial = body.CalcSpatialInertiaInBodyFrame(context)
            d_mass = float(spatial.get_mass())
            if abs(d_mass - mass) > TOL * max(1.0, mass):
                out.problems.append(f"link {link.name!r}: Drake mass {d_mass}, IR {mass}")
                continue
            if mass == 0:  # a massless body has no centre to compare
                continue
            x_rb = inv_r @ plant.EvalBodyPoseInWorld(context, body).GetAsMatrix4()
            d_com_b = np.asarray(spatial.get_com())
            d_com = (x_rb @ np.append(d_com_b, 1.0))[:3]
            d_i = spatial.Shift(d_com_b).CalcRotationalInertia().CopyToFullMatrix3()
            d_i = x_rb[:3, :3] @ d_i @ x_rb[:3, :3].T
            com_err = float(np.max(np.abs(d_com - com)))
            i_err = float(np.max(np.abs(d_i - inertia)))
            out.max_com_error = max(out.max_com_error, com_err)
            out.max_inertia_error = max(out.max_inertia_error, i_err)
            if com_err > TOL or i_err > TOL * max(1.0, float(np.max(np.abs(inertia)))):
                out.problems.append(f"link {link.name!r}: COM differs by {com_err:.3g}, inertia by {i_err:.3g}")
    return out


def _set(plant: Any, context: Any, robot: Robot, top: str, q: dict[str, float]) -> None:
    universal: dict[str, list[float]] = {}
    for joint in robot.joints:
        if joint.name not in q:
            continue
        if joint.child.endswith("_cross") or joint.parent.endswith("_cross"):
            universal.setdefault(joint.name.rsplit("_", 1)[0], []).append(q[joint.name])
            continue
        dj = _scoped(plant, top, joint.name, "joint")
        if joint.type is JointType.PRISMATIC:
            dj.set_translation(context, q[joint.name])
        else:
            dj.set_angle(context, q[joint.name])
    for name, angles in universal.items():
        _scoped(plant, top, name, "joint").set_angles(context, np.array(angles))


def _ir_body(inertial: object, inv_fk_root: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    from robodesc.ir.geometry import Inertial

    if not isinstance(inertial, Inertial) or not inertial.mass:
        return 0.0, np.zeros(3), np.zeros((3, 3))
    frame = inv_fk_root @ pose_matrix(inertial.origin)
    rot = frame[:3, :3]
    inertia = rot @ tensor(inertial.inertia) @ rot.T if inertial.inertia is not None else np.zeros((3, 3))
    return inertial.mass, frame[:3, 3], inertia
