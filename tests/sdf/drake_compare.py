"""Load an emitted SDF with Drake (libsdformat's strict parser) and compare it with the IR.

Compared: bodies, joints (type, limits), masses, inertia tensors about the COM in the body frame,
COM positions, and forward kinematics of every link relative to the root at random joint values.
"""

from __future__ import annotations

import logging
import math
import random
from dataclasses import dataclass, field

import numpy as np

from robodesc.emit.sdf import SdfResult
from robodesc.emit.sdf.model import UNLIMITED
from robodesc.ir.inertia import tensor
from robodesc.ir.model import JointType, Robot
from robodesc.ir.transforms import forward_kinematics, pose_matrix, resolve_mimic

TOL = 1e-9
# Drake ignores Gazebo-only elements with a warning; any other warning is a failure.
ALLOWED_WARNINGS = ("Ignoring unsupported SDFormat element in link: sensor",)
ALLOWED_PREFIXES = (
    "Ignoring unsupported SDFormat element in joint: sensor",
    "Ignoring unsupported SDFormat element in model: plugin",
    # The world wrapper's Gazebo settings.
    "Ignoring unsupported SDFormat element in world: physics",
    "Ignoring unsupported SDFormat element in world: gravity",
    "Ignoring unsupported SDFormat element in world: plugin",
    "Ignoring unsupported SDFormat element in world: spherical_coordinates",
    "Ignoring unsupported SDFormat element in world: light",
)
_DRAKE_TYPE = {
    JointType.FIXED: "weld",
    JointType.REVOLUTE: "revolute",
    JointType.CONTINUOUS: "revolute",
    JointType.PRISMATIC: "prismatic",
    JointType.SPHERICAL: "ball_rpy",
}


class _Capture(logging.Handler):
    def __init__(self) -> None:
        super().__init__(logging.WARNING)
        self.messages: list[str] = []

    def emit(self, record: logging.LogRecord) -> None:
        self.messages.append(record.getMessage())


@dataclass
class Comparison:
    problems: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    max_fk_error: float = 0.0
    max_inertia_error: float = 0.0

    @property
    def ok(self) -> bool:
        return not self.problems


def compare_with_drake(robot: Robot, result: SdfResult, *, samples: int = 3, seed: int = 0) -> Comparison:
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    out = Comparison()
    capture = _Capture()
    logger = logging.getLogger("drake")
    logger.addHandler(capture)
    try:
        plant = MultibodyPlant(0.0)
        Parser(plant).AddModelsFromString(result.text, "sdf")
        plant.Finalize()
    except Exception as err:  # Drake raises RuntimeError with libsdformat's message
        out.problems.append(f"Drake rejected the SDF: {str(err).strip()[:400]}")
        return out
    finally:
        logger.removeHandler(capture)
    for message in capture.messages:
        text = message.split("warning: ", 1)[-1]
        if not any(text.startswith(p) for p in (*ALLOWED_WARNINGS, *ALLOWED_PREFIXES)):
            out.warnings.append(text)
    if out.warnings:
        out.problems.append(f"Drake warned: {out.warnings[:3]}")
    names = result.names
    model = plant.GetModelInstanceByName(result.model_name)
    if len(plant.GetBodyIndices(model)) != len(robot.links):
        out.problems.append(f"{len(plant.GetBodyIndices(model))} bodies in Drake, {len(robot.links)} links in IR")
        return out
    bodies = {}
    for link in robot.links:
        body = plant.GetBodyByName(names.get("link", link.name), model)
        bodies[link.name] = body
        _compare_inertia(link.name, link.inertial, body, out)
    joints = {}
    for joint in robot.joints:
        if joint.type not in _DRAKE_TYPE:
            continue
        dj = plant.GetJointByName(names.get("joint", joint.name), model)
        joints[joint.name] = dj
        if dj.type_name() != _DRAKE_TYPE[joint.type]:
            out.problems.append(
                f"joint {joint.name!r}: Drake type {dj.type_name()}, expected {_DRAKE_TYPE[joint.type]}"
            )
            continue
        if joint.type.dof == 1:
            lo, hi = _limits(joint)
            dlo, dhi = float(dj.position_lower_limits()[0]), float(dj.position_upper_limits()[0])
            if not (_same_limit(lo, dlo) and _same_limit(hi, dhi)):
                out.problems.append(f"joint {joint.name!r}: Drake limits [{dlo}, {dhi}], IR [{lo}, {hi}]")
    if out.problems:
        return out
    rng = random.Random(seed)
    root = robot.root.name
    context = plant.CreateDefaultContext()
    for _ in range(samples):
        q: dict[str, float] = {}
        for joint in robot.actuated_joints():
            if joint.type.dof != 1:
                continue
            lo, hi = _limits(joint)
            lo, hi = max(lo, -math.pi), min(hi, math.pi)
            q[joint.name] = rng.uniform(lo, hi) if lo < hi else lo
        q = resolve_mimic(robot, q)
        for name, value in q.items():
            dj = joints.get(name)
            if dj is None:
                continue
            if dj.type_name() == "revolute":
                dj.set_angle(context, value)
            elif dj.type_name() == "prismatic":
                dj.set_translation(context, value)
        fk = forward_kinematics(robot, q)
        x_wr = plant.EvalBodyPoseInWorld(context, bodies[root]).GetAsMatrix4()
        inv = np.linalg.inv(x_wr)
        for link in robot.links:
            x_rb = inv @ plant.EvalBodyPoseInWorld(context, bodies[link.name]).GetAsMatrix4()
            err = float(np.max(np.abs(x_rb - fk[link.name])))
            out.max_fk_error = max(out.max_fk_error, err)
            if err > TOL:
                out.problems.append(f"link {link.name!r}: FK differs by {err:.3g} at q={q}")
                return out
    return out


def _limits(joint: object) -> tuple[float, float]:
    from robodesc.ir.model import Joint

    assert isinstance(joint, Joint)
    if joint.type is JointType.CONTINUOUS:
        return -UNLIMITED, UNLIMITED
    lim = joint.limit
    lo = lim.lower if lim is not None and lim.lower is not None else -UNLIMITED
    hi = lim.upper if lim is not None and lim.upper is not None else UNLIMITED
    return lo, hi


def _same_limit(ir: float, drake: float) -> bool:
    if abs(ir) >= UNLIMITED:
        return abs(drake) >= UNLIMITED and math.copysign(1, ir) == math.copysign(1, drake)
    return abs(ir - drake) <= TOL * max(1.0, abs(ir))


def _compare_inertia(name: str, inertial: object, body: object, out: Comparison) -> None:
    from robodesc.ir.geometry import Inertial

    mass = 0.0
    com = np.zeros(3)
    i_cm = np.zeros((3, 3))
    if isinstance(inertial, Inertial):
        mass = inertial.mass or 0.0
        frame = pose_matrix(inertial.origin)
        com = frame[:3, 3]
        if inertial.inertia is not None:
            rot = frame[:3, :3]
            i_cm = rot @ tensor(inertial.inertia) @ rot.T
    m = body.default_spatial_inertia()  # type: ignore[attr-defined]
    d_mass = float(m.get_mass())
    if abs(d_mass - mass) > TOL * max(1.0, mass):
        out.problems.append(f"link {name!r}: Drake mass {d_mass}, IR {mass}")
        return
    if mass == 0:
        return
    d_com = np.asarray(m.get_com())
    d_i = m.Shift(d_com).CalcRotationalInertia().CopyToFullMatrix3()
    err = max(float(np.max(np.abs(d_com - com))), float(np.max(np.abs(d_i - i_cm))))
    out.max_inertia_error = max(out.max_inertia_error, err)
    if err > TOL * max(1.0, float(np.max(np.abs(i_cm)))):
        out.problems.append(f"link {name!r}: inertia/COM differ by {err:.3g}")
