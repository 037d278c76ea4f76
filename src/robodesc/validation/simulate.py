"""A short simulation: does the emitted model stand still when held, or does it blow up?

Every hinge and slide joint is held at its start position by a MuJoCo joint equality constraint
(``q = q0``). Equality constraints are solved by the constraint solver with a fixed time constant,
so the hold is stable whatever the link masses are, where position servos would need gains tuned
to each robot. Mimic joints keep the coupling MuJoCo's URDF parser gave them. The start position
is 0, clipped into the limits. Gravity is on; the base is welded (or free, with a floating base,
in which case the robot falls as one piece).

Reported: interpenetrating collision geometry at the start (contacts deeper than the tolerance
between bodies MuJoCo does not already exclude: parent/child and welded pairs) as a warning, then
NaN or infinite state and any speed above the bound during the run as failures. The run itself
has contacts turned off: MuJoCo collides the convex hulls of meshes, which overlap on most real
robots (the hull of a forearm swallows the elbow), and the resulting pushes would hide what this
check is for, whether the masses, inertias and joints make a numerically sane model.
"""

from __future__ import annotations

from typing import Any

import mujoco
import numpy as np

from robodesc.ir.model import JointType, Robot
from robodesc.ir.transforms import resolve_mimic
from robodesc.validation.compare import HINGE, SLIDE
from robodesc.validation.mujoco_load import captured_warnings
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Status, ValidationReport

_MAX_PAIRS = 10


def start_configuration(robot: Robot) -> dict[str, float]:
    q: dict[str, float] = {}
    for joint in robot.joints:
        if joint.type.dof != 1 or joint.mimic is not None:
            continue
        lim = joint.limit
        value = 0.0
        if (
            joint.type is not JointType.CONTINUOUS
            and lim is not None
            and lim.lower is not None
            and lim.upper is not None
            and lim.lower <= lim.upper
        ):
            value = min(max(0.0, lim.lower), lim.upper)
        q[joint.name] = value
    return resolve_mimic(robot, q)


def simulate(robot: Robot, spec: Any, options: ValidateOptions, report: ValidationReport) -> None:
    sim_spec = spec.copy()
    q0 = start_configuration(robot)
    mimics = {j.name for j in robot.joints if j.mimic is not None}
    for joint in sim_spec.joints:
        if int(joint.type) in (HINGE, SLIDE) and joint.name not in mimics:
            data = np.zeros(mujoco.mjNEQDATA)
            data[0] = q0.get(joint.name, 0.0)
            sim_spec.add_equality(type=mujoco.mjtEq.mjEQ_JOINT, name1=joint.name, data=data)
    sim_spec.option.timestep = options.sim_timestep
    contact_off = int(mujoco.mjtDisableBit.mjDSBL_CONTACT)
    sink: list[str] = []  # warnings were reported when the model was first compiled
    try:
        with captured_warnings(sink):
            model = sim_spec.compile()
    except ValueError as exc:
        report.add("simulation", Status.FAIL, "model", f"cannot build the simulation model: {str(exc).strip()}")
        return
    data = mujoco.MjData(model)
    for k in range(model.njnt):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, k)
        if name in q0 and int(model.jnt_type[k]) in (HINGE, SLIDE):
            data.qpos[model.jnt_qposadr[k]] = q0[name]
    # Captured from the first step on: MuJoCo would append its warnings (a singular inertia matrix
    # is found by mj_forward already) to MUJOCO_LOG.TXT in the user's working folder.
    with captured_warnings(sink):
        mujoco.mj_forward(model, data)
        _penetration(model, data, options, report)
        model.opt.disableflags |= contact_off
        mujoco.mj_forward(model, data)
        _run(robot, model, data, options, report)


def _run(robot: Robot, model: Any, data: Any, options: ValidateOptions, report: ValidationReport) -> None:
    steps = max(1, round(options.sim_duration / options.sim_timestep))
    peak = 0.0
    for step in range(steps):
        mujoco.mj_step(model, data)
        t = (step + 1) * options.sim_timestep
        if not (np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))):
            report.add("simulation", Status.FAIL, "model", f"state became NaN/infinite after {t:.3g} s")
            return
        speed = float(np.max(np.abs(data.qvel))) if model.nv else 0.0
        peak = max(peak, speed)
        if speed > options.max_speed:
            dof = int(np.argmax(np.abs(data.qvel)))
            report.add(
                "simulation",
                Status.FAIL,
                _dof_label(model, dof),
                f"exploded: speed {speed:.3g} (rad/s or m/s) after {t:.3g} s with every joint held; "
                "look for tiny or lopsided masses and inertias on this joint's links",
                error=speed,
                tolerance=options.max_speed,
            )
            return
    if int(data.warning[int(mujoco.mjtWarning.mjWARN_BADQACC)].number) > 0:
        report.add("simulation", Status.FAIL, "model", "MuJoCo reported non-finite accelerations (unstable model)")
        return
    report.note_error("sim_peak_speed", peak)
    report.add(
        "simulation",
        Status.PASS,
        "model",
        f"stable for {steps * options.sim_timestep:.3g} s under gravity with joints held "
        f"({'floating' if options.floating_base else 'fixed'} base; peak speed {peak:.3g})",
        error=peak,
        tolerance=options.max_speed,
    )


def _dof_label(model: Any, dof: int) -> str:
    j = int(model.dof_jntid[dof])
    name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j)
    if name:
        return f"joint {name!r}"
    body = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, int(model.jnt_bodyid[j]))
    return f"link {body!r} (free joint)"


def _penetration(model: Any, data: Any, options: ValidateOptions, report: ValidationReport) -> None:
    pairs: dict[tuple[str, str], float] = {}
    for i in range(data.ncon):
        c = data.contact[i]
        if c.dist < -options.penetration_tol:
            names = sorted(
                mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, int(model.geom_bodyid[g])) or "world"
                for g in (c.geom1, c.geom2)
            )
            key = (names[0], names[1])
            pairs[key] = max(pairs.get(key, 0.0), -float(c.dist))
    worst = max(pairs.values(), default=0.0)
    report.note_error("penetration", worst)
    if not pairs:
        report.add(
            "penetration",
            Status.PASS,
            "model",
            f"no collision geometry interpenetrates at the start configuration (tolerance {options.penetration_tol:g} m)",
        )
        return
    ordered = sorted(pairs.items(), key=lambda kv: (-kv[1], kv[0]))
    shown = ", ".join(f"{a}/{b} {depth * 1000:.3g} mm" for (a, b), depth in ordered[:_MAX_PAIRS])
    more = f" and {len(ordered) - _MAX_PAIRS} more" if len(ordered) > _MAX_PAIRS else ""
    report.add(
        "penetration",
        Status.WARN,
        f"{len(ordered)} link pairs",
        f"collision geometry interpenetrates at the start configuration (MuJoCo collides convex hulls of "
        f"meshes): {shown}{more}. A simulator pushes these apart: exclude the pairs or simplify the shapes",
        error=worst,
        tolerance=options.penetration_tol,
    )
