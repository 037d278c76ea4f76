"""PhysX as a consumer of the USD robodesc writes: what ovphysx parsed, compared with the IR.

PhysX is the engine Isaac Sim runs. Its reading of a UsdPhysics stage is its own: a rigid body
without ``PhysicsMassAPI`` gets a mass from its colliders at 1000 kg/m³, or 1 kg when it has none;
angular drive gains are per degree; armature, velocity limits and joint friction come from the
PhysX (and, in ovphysx, the Newton) schemas, not from UsdPhysics. So the usd-core parser's numbers
(:mod:`.usd_physics`) do not say what PhysX simulates. This module runs
:mod:`.physx_read_worker` in PhysX's interpreter (:func:`.physx_python.physx_python`; robodesc's
process never imports ovphysx) and compares per body the mass, the centre of mass and the inertia
tensor (link frame), and per joint its degrees of freedom, limits, drive gains, maximum force,
armature, maximum velocity and friction with the IR. Without a PhysX interpreter the report is one
SKIP row.

PhysX holds these numbers in float32: the tolerances are ``PHYSX_REL_TOL`` (relative; measured
errors are below 4e-7 on Panda's inertias, see docs/validation.md).
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from robodesc.ir.model import Joint, JointType, Link, Robot
from robodesc.validation.compare import expected_inertial, joint_label, link_label
from robodesc.validation.mujoco_load import tree_depth
from robodesc.validation.options import TOKEN_MASS, ValidateOptions
from robodesc.validation.physx_python import physx_python
from robodesc.validation.report import Status, Tally, ValidationReport
from robodesc.validation.usd_physics import match_name, parser_stack_size, tensor_text, vec_text
from robodesc.validation.worker import run_worker

CONSUMER = "physx"
DEG = 180.0 / math.pi
# PhysX stores mass properties and joint properties in float32 (6e-8 relative) and computes the
# inertia about the centre of mass from the principal moments and axes: measured up to 4e-7 of the
# largest moment on Panda. 1e-5 keeps a 25x margin and still catches a hand-edited digit.
PHYSX_REL_TOL = 1e-5
# A link the source gives no mass may reach PhysX with at most a token mass (what a converter gives a
# body an engine refuses massless); more is mass the robot does not have.
MASSLESS_MAX = TOKEN_MASS
# Above this PhysX treats a bound as none (its FLT_MAX default reads back as None).
UNBOUNDED = 1.0e30
_TIMEOUT = 600.0  # s: a robot with thousands of bodies; a small arm takes 3 s
# PhysX's log lines that say nothing about the file.
_NOISE = ("GPU broadphase", "CUDA")

# Mismatches robodesc's output has on main that fixes in flight remove (issue #38): while a check
# is listed here its failures are warnings that name the fix. The lead empties an entry when the
# fix lands, and the check then fails a compile as every other consumer check does.
# Empty since the massless pass landed (every body now carries an authored mass): a massless link
# had been written without PhysicsMassAPI, and PhysX gave it its colliders' mass at 1000 kg/m³, or 1 kg.
PENDING_FIXES: dict[str, str] = {}


@dataclass
class PhysxRead:
    """What :mod:`.physx_read_worker` answered, plus PhysX's own log lines."""

    version: str = ""
    articulations: list[dict[str, Any]] = field(default_factory=list)
    bodies: dict[str, dict[str, Any]] = field(default_factory=dict)  # prim path -> mass properties
    joints: dict[str, list[dict[str, Any]]] = field(default_factory=dict)  # prim path -> one dict per DOF
    log: list[str] = field(default_factory=list)


def read_physx(usd_path: str, python: str) -> PhysxRead | str:
    """Load ``usd_path`` in PhysX through the worker; what PhysX holds, or why it could not."""
    worker = os.path.join(os.path.dirname(os.path.abspath(__file__)), "physx_read_worker.py")
    done = run_worker(python, worker, {"usd": os.path.abspath(usd_path)}, _TIMEOUT, "PhysX")
    answer, lines = done.answer, done.lines
    if answer is None:
        return done.failure
    if "error" in answer:
        return f"PhysX cannot load the USD: {answer['error']}"
    log = [
        line.strip()
        for line in lines
        if line.startswith(("[Warning]", "[Error]")) and not any(word in line for word in _NOISE)
    ]
    return PhysxRead(
        version=str(answer.get("ovphysx", "")),
        articulations=list(answer.get("articulations", [])),
        bodies=dict(answer.get("bodies", {})),
        joints=dict(answer.get("joints", {})),
        log=list(dict.fromkeys(log)),  # PhysX repeats a message per parse pass
    )


def _grouped(log: list[str]) -> dict[str, list[str]]:
    """PhysX's messages with the prim they name taken out, each with the prims it was said of
    (ANYmal C has 18 "possibly invalid inertia tensor" lines, one per sensor frame)."""
    out: dict[str, list[str]] = {}
    for line in log:
        prims = _PRIM.findall(line)
        out.setdefault(_PRIM.sub("<prim>", line), []).extend(prims)
    return out


_PRIM = re.compile(r"(?<= at )/[\w/.-]+")


def validate_usd_physx(
    robot: Robot,
    usd_path: str,
    options: ValidateOptions | None = None,
    python: str | None = None,
    target: str = "usd",
) -> ValidationReport:
    """Load ``usd_path`` in PhysX and compare what it parsed with ``robot`` (rows named ``physx-*``)."""
    del options  # PhysX's float32 sets the tolerances; the options' are tighter than it can hold
    report = ValidationReport(robot=robot.name, target=target, consumer=CONSUMER)
    interpreter = physx_python(python)
    if interpreter is None:
        report.add(
            "physx",
            Status.SKIP,
            "document",
            "skipped: no PhysX interpreter (pip install 'robodesc[physx]' in an environment without Ray, "
            "or build the consumer tier's with tests/consumers/run.sh; ROBODESC_PHYSX_PYTHON names one)",
        )
        return report
    depth = tree_depth(robot)
    if parser_stack_size(depth) is None:
        # PhysX parses the stage with the same recursive UsdPhysics walk as usd-core (usd_physics.py):
        # past the depth usd-core is given a stack for, it is not asked either.
        report.add("physx", Status.SKIP, "model", f"not loaded in PhysX: the kinematic tree is {depth} joints deep")
        return report
    got = read_physx(usd_path, interpreter)
    if isinstance(got, str):
        report.add("physx-load", Status.FAIL, "document", f"{got} ({usd_path})")
        return report
    report.info["physx"] = f"ovphysx {got.version}"
    bodies, joints, gains = _match(robot, usd_path, got)
    report.add(
        "physx-load",
        Status.PASS,
        "document",
        f"loaded: {len(got.articulations)} articulation(s), {len(got.bodies)} bodies, {len(got.joints)} joints with DOFs",
    )
    for message, prims in _grouped(got.log).items():
        shown = ", ".join(prims[:3]) + (f" and {len(prims) - 3} more" if len(prims) > 3 else "")
        report.add("physx-warning", Status.WARN, "model", message[:400] + (f" ({shown})" if prims else ""))
    _compare_articulation(robot, got, bodies, report)
    _compare_masses(robot, got, bodies, report)
    _compare_joints(robot, got, joints, gains, report)
    for check in report.checks:
        why = PENDING_FIXES.get(check.name)
        if why and check.status is Status.FAIL:
            check.status = Status.WARN
            check.message += f" [known mismatch until {why} lands; issue #38]"
    return report


def _match(
    robot: Robot, usd_path: str, got: PhysxRead
) -> tuple[dict[str, str], dict[str, str], dict[str, tuple[float, float]]]:
    """IR link -> PhysX body path and IR joint -> joint path: by prim name, else ``displayName``
    (the original name of a sanitized one), as the usd-core checks match them. And per joint the
    drive stiffness and damping the USD authors, in its own units (per degree on an angular drive):
    the gains are the target's options, not the IR's, so PhysX's are held to what was written."""
    from pxr import Usd, UsdPhysics

    stage = Usd.Stage.Open(usd_path)
    links = {link.name for link in robot.links}
    names = {joint.name for joint in robot.joints}
    bodies: dict[str, str] = {}
    for path in got.bodies:
        name = match_name(stage, path, links)
        if name is not None and name not in bodies:
            bodies[name] = path
    joints: dict[str, str] = {}
    gains: dict[str, tuple[float, float]] = {}
    for path in got.joints:
        name = match_name(stage, path, names)
        if name is None or name in joints:
            continue
        joints[name] = path
        prim = stage.GetPrimAtPath(path)
        for kind in ("angular", "linear"):
            drive = UsdPhysics.DriveAPI.Get(prim, kind)
            if prim.HasAPI(UsdPhysics.DriveAPI, kind):
                stiffness, damping = drive.GetStiffnessAttr().Get(), drive.GetDampingAttr().Get()
                gains[name] = (float(stiffness or 0.0), float(damping or 0.0))
    return bodies, joints, gains


def _compare_articulation(robot: Robot, got: PhysxRead, bodies: Mapping[str, str], report: ValidationReport) -> None:
    """One articulation holding every link, with the source's base."""
    missing = [link.name for link in robot.links if link.name not in bodies]
    loose = [name for name, path in bodies.items() if got.bodies[path]["kind"] != "link"]
    tally = Tally(report, "physx-bodies", None, "")
    for name in missing:
        tally.fail(link_label(name), "PhysX has no body for this link")
    for name in loose:
        tally.fail(link_label(name), "PhysX simulates this link as a free rigid body, outside the articulation")
    for _ in range(len(robot.links) - len(missing) - len(loose)):
        tally.ok()
    tally.finish("links")
    if len(got.articulations) != 1:
        paths = ", ".join(a["path"] for a in got.articulations) or "none"
        report.add(
            "physx-articulation",
            Status.FAIL,
            "robot",
            f"PhysX builds {len(got.articulations)} articulations ({paths}); expected one",
        )
        return
    art = got.articulations[0]
    dofs = sum(j.type.dof for j in robot.joints)  # mimic followers too: PhysX gives each its DOF
    problems = []
    if art["dofs"] != dofs:
        problems.append(f"{art['dofs']} degrees of freedom, the source has {dofs}")
    if robot.fixed_base is not None and bool(art["fixed_base"]) != robot.fixed_base:
        problems.append(
            f"a {'fixed' if art['fixed_base'] else 'floating'} base, the source says {'fixed' if robot.fixed_base else 'floating'}"
        )
    if problems:
        report.add("physx-articulation", Status.FAIL, art["path"], "PhysX reads " + "; ".join(problems))
    else:
        base = "fixed" if art["fixed_base"] else "floating"
        report.add(
            "physx-articulation",
            Status.PASS,
            art["path"],
            f"one articulation, {art['links']} links, {dofs} DOFs, {base} base",
        )


# ---- mass properties -------------------------------------------------------------------------------
def _compare_masses(robot: Robot, got: PhysxRead, bodies: Mapping[str, str], report: ValidationReport) -> None:
    mass = Tally(report, "physx-mass", PHYSX_REL_TOL, "relative")
    massless = Tally(report, "physx-massless", MASSLESS_MAX, "kg")
    com = Tally(report, "physx-com", PHYSX_REL_TOL, "m (relative above 1 m)")
    inertia = Tally(report, "physx-inertia", PHYSX_REL_TOL, "relative")
    for link in robot.links:
        path = bodies.get(link.name)
        if path is None:
            continue
        _compare_link(link, got.bodies[path], mass, massless, com, inertia)
    mass.finish("links with mass", "physx-mass")
    massless.finish("links without mass")
    com.finish("links", "physx-com")
    inertia.finish("links", "physx-inertia")
    _compare_total(robot, got, bodies, report)


def _compare_link(
    link: Link, body: Mapping[str, Any], mass: Tally, massless: Tally, com: Tally, inertia: Tally
) -> None:
    label = link_label(link.name)
    m_px = float(body["mass"] or 0.0)
    m_ir, com_ir, tensor_ir = expected_inertial(link)
    if not m_ir > 0.0:  # no <inertial>, or URDF's mass 0: no mass of its own
        massless.measure(
            label,
            m_px,
            f"PhysX gives this link {m_px:.6g} kg; the source gives it no mass (a body without an authored mass gets "
            "one from its colliders at 1000 kg/m³, or 1 kg without colliders)",
        )
        return
    mass.measure(label, abs(m_px - m_ir) / max(m_ir, 1e-12), f"PhysX mass {m_px:.9g} kg, source {m_ir:.9g} kg")
    c_px = np.asarray(body["com"] or [math.nan] * 3, dtype=float)
    com.measure(
        label,
        float(np.linalg.norm(c_px - com_ir)) / max(1.0, float(np.linalg.norm(com_ir))),
        f"PhysX centre of mass {vec_text(c_px)}, source {vec_text(com_ir)} (link frame, m)",
    )
    if tensor_ir is None:
        inertia.skip(label, "source gives no inertia tensor")
        return
    values = body["inertia"] or []
    if len(values) != 9:
        inertia.fail(label, "PhysX returned no inertia tensor")
        return
    # ovphysx reads the tensor about the centre of mass in the body's axes (checked on Panda, whose
    # principal axes are turned: 4e-7 against 0.98 in the principal frame).
    t_px = np.asarray(values, dtype=float).reshape(3, 3)
    scale = max(float(np.max(np.abs(np.linalg.eigvalsh(tensor_ir)))), 1e-12)
    inertia.measure(
        label,
        float(np.max(np.abs(t_px - tensor_ir))) / scale,
        f"PhysX tensor {tensor_text(t_px)}, source {tensor_text(tensor_ir)} (about the centre of mass, link axes, kg·m²)",
    )


def _compare_total(robot: Robot, got: PhysxRead, bodies: Mapping[str, str], report: ValidationReport) -> None:
    want = robot.total_mass()
    have = sum(float(got.bodies[path]["mass"] or 0.0) for path in bodies.values())
    tokens = sum(1 for link in robot.links if not expected_inertial(link)[0] > 0.0) * MASSLESS_MAX
    error = abs(have - want) / max(want, 1e-12)
    tolerance = PHYSX_REL_TOL + tokens / max(want, 1e-12)
    status = Status.PASS if error <= tolerance else Status.FAIL
    report.add(
        "physx-total-mass",
        status,
        "robot",
        f"PhysX weighs the robot {have:.6g} kg, the source {want:.6g} kg",
        error=error,
        tolerance=tolerance,
    )
    report.note_error("physx-total-mass", error)


# ---- joints ------------------------------------------------------------------------------------------
@dataclass
class _JointTallies:
    present: Tally
    limits: Tally
    drive: Tally
    max_force: Tally
    armature: Tally
    velocity: Tally
    friction: Tally


def _compare_joints(
    robot: Robot,
    got: PhysxRead,
    joints: Mapping[str, str],
    authored: Mapping[str, tuple[float, float]],
    report: ValidationReport,
) -> None:
    t = _JointTallies(
        Tally(report, "physx-dofs", None, ""),
        Tally(report, "physx-limits", PHYSX_REL_TOL, "relative (deg or m)"),
        Tally(report, "physx-drive", PHYSX_REL_TOL, "relative"),
        Tally(report, "physx-max-force", PHYSX_REL_TOL, "relative"),
        Tally(report, "physx-armature", PHYSX_REL_TOL, "relative"),
        Tally(report, "physx-max-velocity", PHYSX_REL_TOL, "relative"),
        Tally(report, "physx-friction", PHYSX_REL_TOL, "relative"),
    )
    by_name = robot.joint_map()
    # The USD couples these to their leader and writes them no velocity limit (emit/usd/joints.py's
    # _follower_velocity: PhysX runs away with one).
    leaders = {j.name: by_name.get(j.mimic.joint) for j in robot.joints if j.mimic is not None}
    followers = {name for name, leader in leaders.items() if leader is not None and leader.type.dof == 1}
    for joint in robot.joints:
        label = joint_label(joint.name)
        path = joints.get(joint.name)
        axes = got.joints.get(path, []) if path is not None else []
        if len(axes) != joint.type.dof:
            if joint.type.dof or axes:
                t.present.fail(
                    label, f"PhysX gives this {joint.type.value} joint {len(axes)} DOFs, expected {joint.type.dof}"
                )
            continue
        t.present.ok()
        if joint.type.dof == 1:
            _compare_dof(joint, axes[0], authored.get(joint.name), t, follower=joint.name in followers)
    for tally in (t.present, t.limits, t.drive, t.max_force, t.armature, t.velocity, t.friction):
        tally.finish("joints", tally.name)


def _compare_dof(
    joint: Joint, dof: Mapping[str, Any], authored: tuple[float, float] | None, t: _JointTallies, *, follower: bool
) -> None:
    label = joint_label(joint.name)
    angular = joint.type.is_angular
    unit, unit_name = (DEG, "deg") if angular else (1.0, "m")
    lim = joint.limit
    lo_px, hi_px = [*(dof.get("limit") or []), None, None][:2]
    bounded = (
        joint.type is not JointType.CONTINUOUS and lim is not None and lim.lower is not None and lim.upper is not None
    )
    if bounded:
        assert lim is not None and lim.lower is not None and lim.upper is not None
        lo, hi = lim.lower * unit, lim.upper * unit
        if lo_px is None or hi_px is None:
            t.limits.fail(label, f"PhysX leaves the joint unlimited; source limits [{lo:.9g}, {hi:.9g}] {unit_name}")
        else:
            err = max(abs(lo_px - lo) / max(abs(lo), 1.0), abs(hi_px - hi) / max(abs(hi), 1.0))
            t.limits.measure(
                label,
                err,
                f"PhysX limits [{lo_px:.9g}, {hi_px:.9g}] {unit_name}, source [{lo:.9g}, {hi:.9g}] {unit_name}",
            )
    elif lo_px is not None and hi_px is not None:
        t.limits.fail(
            label,
            f"the source has no position limits, PhysX limits the joint to [{lo_px:.9g}, {hi_px:.9g}] {unit_name}",
        )
    else:
        t.limits.ok()
    per = f"/{unit_name}"
    if authored is not None:
        kp, kd = float(dof.get("stiffness") or 0.0), float(dof.get("damping") or 0.0)
        effort_unit = _effort(angular)
        t.drive.measure(
            label,
            max(
                abs(kp - authored[0]) / max(abs(authored[0]), 1e-9), abs(kd - authored[1]) / max(abs(authored[1]), 1e-9)
            ),
            f"PhysX drive stiffness {kp:.9g} {effort_unit}{per}, damping {kd:.9g} {effort_unit}{per}/s; "
            f"the USD authors {authored[0]:.9g} and {authored[1]:.9g}",
        )
    effort = lim.effort if lim is not None and lim.effort is not None and lim.effort > 0 else None
    max_force = dof.get("max_force")
    if not dof.get("drive_type") and effort is None:
        # No drive (a mimic follower without an effort limit): PhysX reads its force bound as 0, and
        # with nothing driving the joint there is no force to bound.
        max_force = None
    _bound(t.max_force, label, max_force, effort, f"maximum {_effort(angular)}", _effort(angular))
    velocity = lim.velocity * unit if lim is not None and lim.velocity is not None and lim.velocity > 0 else None
    if follower:
        velocity = None
    _bound(t.velocity, label, dof.get("max_velocity"), velocity, "maximum velocity", f"{unit_name}/s")
    armature = float(joint.armature or 0.0)
    have = float(dof.get("armature") or 0.0)
    t.armature.measure(
        label,
        abs(have - armature) / max(armature, 1e-9),
        f"PhysX armature {have:.9g}, source {armature:.9g} ({'kg·m²' if angular else 'kg'})",
    )
    friction = float(joint.dynamics.friction or 0.0) if joint.dynamics is not None else 0.0
    static, dynamic = float(dof.get("static_friction") or 0.0), float(dof.get("dynamic_friction") or 0.0)
    # URDF's <dynamics friction> is a Coulomb effort: the one PhysX applies while the joint slides.
    t.friction.measure(
        label,
        abs(dynamic - friction) / max(friction, 1e-9),
        f"PhysX dynamic friction {dynamic:.9g} {_effort(angular)} (static {static:.9g}), source friction {friction:.9g}",
    )


def _effort(angular: bool) -> str:
    return "N·m" if angular else "N"


def _bound(tally: Tally, label: str, have: float | None, want: float | None, what: str, unit: str) -> None:
    """A bound PhysX may hold as 'none' (FLT_MAX): equal when both are given, else both absent.
    The source's bound goes through the same rule: an effort or velocity limit of 1e30 (a common
    way to write "none" in URDF) is read by PhysX as unbounded, which is what the source means."""
    have = None if have is None or have >= UNBOUNDED else float(have)
    want = None if want is None or want >= UNBOUNDED else float(want)
    if want is None and have is None:
        tally.ok()
    elif want is None:
        tally.fail(label, f"PhysX bounds the {what} at {have:.9g} {unit}; the source gives none")
    elif have is None:
        tally.fail(label, f"PhysX leaves the {what} unbounded; the source gives {want:.9g} {unit}")
    else:
        tally.measure(
            label, abs(have - want) / max(abs(want), 1e-9), f"PhysX {what} {have:.9g} {unit}, source {want:.9g} {unit}"
        )
