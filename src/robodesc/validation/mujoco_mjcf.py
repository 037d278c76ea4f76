"""Validate an emitted MJCF model (``robot.xml`` and its ``scene.xml``) by loading it in MuJoCo.

MuJoCo loads both files with ``MjModel.from_xml_path``, as a user does; any warning it prints while
compiling fails the load. ``robot.xml`` is then compared with the IR using the comparisons the
URDF validator uses (:mod:`robodesc.validation.compare`), with what MJCF adds:

- a link merged away by a fixed joint may be a ``<site>`` of the same name: its frame is compared
  like a body's, and its mass is expected inside the body it was merged into;
- ``armature`` per degree of freedom;
- actuators: one per movable, non-mimic joint; for position actuators ``ctrlrange`` = joint range,
  ``forcerange`` = effort and, when the caller passes the drives it asked for, ``kp``/``kv``;
- loop joints as ``<equality connect>`` (spherical) or ``weld``;
- mujoco_menagerie's model test on ``scene.xml`` (:mod:`robodesc.validation.menagerie`).

Never raises for a bad model: every problem is a failing check naming the element.
"""

from __future__ import annotations

import os
import time
import warnings
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import mujoco
import numpy as np

from robodesc.ir.geometry import Inertial, Pose
from robodesc.ir.inertia import from_tensor, parallel_axis
from robodesc.ir.model import Joint, JointType, Link, Robot
from robodesc.ir.transforms import forward_kinematics
from robodesc.validation.compare import (
    Ids,
    compare_fk,
    compare_inertials,
    compare_joints,
    compare_structure,
    expected_inertial,
    joint_label,
    link_label,
)
from robodesc.validation.menagerie import add_menagerie_check
from robodesc.validation.mujoco_load import captured_warnings
from robodesc.validation.mujoco_urdf import without_dangling_mimics
from robodesc.validation.options import TOKEN_MASS, ValidateOptions
from robodesc.validation.report import Status, Tally, ValidationReport

Mat = Any  # numpy 4x4 / 3x3 arrays
# (kp in N·m/rad or N/m, kv in N·m·s/rad or N·s/m) per joint name: what the emitter was asked for.
Drives = Mapping[str, tuple[float, float]]
EQ_CONNECT = int(mujoco.mjtEq.mjEQ_CONNECT)
EQ_WELD = int(mujoco.mjtEq.mjEQ_WELD)
OBJ_SITE = int(mujoco.mjtObj.mjOBJ_SITE)
TRN_JOINT = int(mujoco.mjtTrn.mjTRN_JOINT)
BIAS_AFFINE = int(mujoco.mjtBias.mjBIAS_AFFINE)
# MuJoCo refuses a moving body without mass, so a converter gives a massless link a token mass
# (1e-6 kg is common). Up to this much on a link the source leaves massless is that repair, not
# a changed mass: it is reported as a warning and left out of the mass comparison.
PLACEHOLDER_MASS = TOKEN_MASS  # kg: what robodesc's MJCF writer gives a moving massless link


def validate_mjcf(
    robot: Robot,
    mjcf_path: str,
    scene_path: str | None,
    options: ValidateOptions | None = None,
    *,
    expected_drives: Drives | None = None,
) -> ValidationReport:
    """Load ``mjcf_path`` (and ``scene_path``) in MuJoCo and compare the model with ``robot``.

    ``expected_drives`` maps joint names to the (kp, kv) the emitter was asked for, in SI per
    radian or metre; without it the gains are not compared (actuator presence and ranges are).
    """
    opts = options or ValidateOptions()
    report = ValidationReport(robot=robot.name, target="mjcf", consumer="mujoco")
    report.info["mujoco"] = mujoco.__version__
    report.info["input"] = mjcf_path
    robot = without_dangling_mimics(robot, report)
    started = time.perf_counter()
    model = load_mjcf(mjcf_path, "mjcf-load", report)
    if model is not None:
        compare_model(robot, model, opts, report, expected_drives)
    if scene_path is not None:
        scene = load_mjcf(scene_path, "scene-load", report)
        if scene is not None:
            add_menagerie_check(scene, os.path.basename(scene_path), report)
        else:
            report.add("menagerie", Status.SKIP, os.path.basename(scene_path), "not run: the scene does not load")
    elif model is not None:
        # Without a scene the robot alone is stepped: the verdict still says whether it is stable.
        report.add("scene-load", Status.SKIP, "scene", "no scene given; the menagerie test steps the robot file")
        add_menagerie_check(model, os.path.basename(mjcf_path), report)
    report.info["validation_seconds"] = f"{time.perf_counter() - started:.3f}"
    return report


def load_mjcf(path: str, check: str, report: ValidationReport) -> Any:
    """``MjModel.from_xml_path``; a refusal fails ``check``, any warning while compiling fails
    ``mujoco-warning`` (MuJoCo prints it and goes on; menagerie's bar is zero warnings)."""
    element = os.path.basename(path)
    sink: list[str] = []
    try:
        with captured_warnings(sink), warnings.catch_warnings(record=True) as py_warnings:
            warnings.simplefilter("always")
            model = mujoco.MjModel.from_xml_path(path)
    except ValueError as exc:  # MuJoCo raises ValueError for anything it refuses
        report.add(check, Status.FAIL, element, f"MuJoCo refuses {path}: {str(exc).strip()}")
        return None
    sink += [str(w.message).strip() for w in py_warnings]
    for message in dict.fromkeys(sink):
        report.add("mujoco-warning", Status.FAIL, element, f"MuJoCo warns while compiling: {message}")
    report.add(check, Status.PASS, element, f"{model.nbody - 1} bodies, {model.njnt} joints, {model.nu} actuators")
    return model


def compare_model(
    robot: Robot, model: Any, options: ValidateOptions, report: ValidationReport, drives: Drives | None
) -> None:
    sites = merged_sites(robot, model, report)
    lumped, skip = lumped_robot(robot, sites)
    skip.update(placeholder_masses(lumped, model, report))
    compare_structure(lumped, model, report)
    compare_inertials(lumped, model, skip, options, report)
    compare_joints(lumped, model, options, report)
    compare_armature(robot, model, options, report)
    compare_fk(robot, model, options, report, sites)
    compare_actuators(robot, model, options, report, drives)
    compare_loops(robot, model, report)


# ---- links merged into sites ------------------------------------------------------------------
def merged_sites(robot: Robot, model: Any, report: ValidationReport) -> dict[str, str]:
    """Links that are not bodies but sites, each mapped to the link whose body now carries them.

    Only a link hanging from a fixed joint can be merged; any other is left to ``bodies`` to
    report as missing."""
    ids = Ids(model)
    parent_joint = robot.parent_joint()
    out: dict[str, str] = {}
    for link in robot.links:
        if ids.body(link.name) >= 0 or _site(model, link.name) < 0:
            continue
        joint = parent_joint.get(link.name)
        if joint is None or joint.type is not JointType.FIXED:
            why = "the root link" if joint is None else f"a link that moves on {joint.type.value} joint {joint.name!r}"
            report.add(
                "sites",
                Status.FAIL,
                link_label(link.name),
                f"is a site, not a body, but it is {why}: only links on fixed joints may be merged into their parent",
            )
            continue
        out[link.name] = joint.parent
    # Resolve chains of merged links to the body that carries them.
    for name in out:
        carrier = out[name]
        while carrier in out:
            carrier = out[carrier]
        out[name] = carrier
    if out:
        report.add("sites", Status.PASS, f"{len(out)} links", "merged into their parent bodies, kept as sites")
    return out


def _site(model: Any, name: str) -> int:
    return int(mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, name))


def lumped_robot(robot: Robot, sites: Mapping[str, str]) -> tuple[Robot, dict[str, str]]:
    """The robot as MuJoCo should hold it once the ``sites`` links are merged into their carriers.

    The carrier's inertial becomes the sum of its own and its merged links' (parallel-axis
    theorem, in the carrier's frame); joints to merged links disappear and joints from them hang
    from the carrier. Only the names, inertials and parents matter to the comparisons that use it.
    Also returns the carriers whose sum is unknown (a merged part has a mass but no tensor), with
    why, for the inertial comparison to skip.
    """
    if not sites:
        return robot, {}
    frames = forward_kinematics(robot)  # merged links sit on fixed joints: any configuration will do
    merged_into: dict[str, list[str]] = {}
    for name, carrier in sites.items():
        merged_into.setdefault(carrier, []).append(name)
    links_by_name = robot.link_map()
    links, unknown = [], {}
    for link in robot.links:
        if link.name in sites:
            continue
        parts = [links_by_name[p] for p in (link.name, *merged_into.get(link.name, []))]
        lumped = _lumped_link(link, parts, frames) if len(parts) > 1 else link
        if lumped is None:
            unknown[link.name] = "a link merged into it has a mass but no inertia tensor"
            lumped = link
        links.append(lumped)
    joints = [replace(j, parent=sites.get(j.parent, j.parent)) for j in robot.joints if j.child not in sites]
    return replace(robot, links=links, joints=joints), unknown


def _lumped_link(carrier: Link, parts: list[Link], frames: Mapping[str, Mat]) -> Link | None:
    inv = np.linalg.inv(frames[carrier.name])
    pieces = []
    for part in parts:
        mass, com, tensor_ = expected_inertial(part)
        if mass <= 0:
            continue
        if tensor_ is None:
            return None
        t = inv @ frames[part.name]
        pieces.append((mass, t[:3, :3] @ com + t[:3, 3], t[:3, :3] @ tensor_ @ t[:3, :3].T))
    total = sum(p[0] for p in pieces)
    if total <= 0:
        return replace(carrier, inertial=None)
    com = sum((p[0] * p[1] for p in pieces), np.zeros(3)) / total
    tensor_ = sum((parallel_axis(p[2], p[0], p[1] - com) for p in pieces), np.zeros((3, 3)))
    origin = Pose(xyz=(float(com[0]), float(com[1]), float(com[2])))
    return replace(carrier, inertial=Inertial(mass=total, origin=origin, inertia=from_tensor(tensor_)))


def placeholder_masses(robot: Robot, model: Any, report: ValidationReport) -> dict[str, str]:
    """Massless links that MuJoCo holds with a token mass (see ``PLACEHOLDER_MASS``): a warning each."""
    ids = Ids(model)
    out: dict[str, str] = {}
    for link in robot.links:
        b = ids.body(link.name)
        if b <= 0 or expected_inertial(link)[0] > 0:
            continue
        mass = float(model.body_mass[b])
        if 0 < mass <= PLACEHOLDER_MASS:
            out[link.name] = f"massless in the source, {mass:.3g} kg so that MuJoCo accepts it"
            report.add("mass", Status.WARN, link_label(link.name), out[link.name])
    return out


# ---- armature ---------------------------------------------------------------------------------
def compare_armature(robot: Robot, model: Any, options: ValidateOptions, report: ValidationReport) -> None:
    """``dof_armature`` vs the IR's reflected rotor inertia (0 where the IR has none)."""
    ids = Ids(model)
    tally = Tally(report, "armature", options.limit_tol, "kg·m² or kg")
    for joint in robot.joints:
        j = ids.joint(joint.name)
        if joint.type.dof != 1 or j < 0:
            continue
        want = float(joint.armature) if joint.armature is not None else 0.0
        got = float(model.dof_armature[int(model.jnt_dofadr[j])])
        tally.measure(joint_label(joint.name), abs(got - want), f"MuJoCo armature {got:.9g}, source {want:.9g}")
    tally.finish("joints", "armature")


# ---- forward kinematics, bodies and sites -----------------------------------------------------
# ---- actuators --------------------------------------------------------------------------------
def joint_actuators(model: Any) -> dict[int, list[int]]:
    """Joint id -> the actuators that drive it directly (transmission type ``joint``)."""
    out: dict[int, list[int]] = {}
    for a in range(model.nu):
        if int(model.actuator_trntype[a]) == TRN_JOINT:
            out.setdefault(int(model.actuator_trnid[a][0]), []).append(a)
    return out


def is_position_servo(model: Any, a: int) -> bool:
    """MuJoCo's ``<position>`` shortcut: force = kp·ctrl − kp·q − kv·q̇."""
    gain, bias = model.actuator_gainprm[a], model.actuator_biasprm[a]
    return (
        int(model.actuator_biastype[a]) == BIAS_AFFINE
        and float(gain[0]) > 0
        and float(bias[1]) == -float(gain[0])
        and float(bias[0]) == 0.0
    )


def actuated_joints(robot: Robot) -> list[Joint]:
    """Joints that should carry an actuator: movable, one degree of freedom, not a mimic."""
    return [j for j in robot.joints if j.type.dof == 1 and j.mimic is None]


def compare_actuators(
    robot: Robot, model: Any, options: ValidateOptions, report: ValidationReport, drives: Drives | None
) -> None:
    ids = Ids(model)
    by_joint = joint_actuators(model)
    present = Tally(report, "actuators", None, "")
    gains = Tally(report, "gains", options.gain_rel_tol, "relative")
    ranges = Tally(report, "actuator-range", options.limit_tol, "rad, m, N·m or N")
    for joint in actuated_joints(robot):
        label = joint_label(joint.name)
        j = ids.joint(joint.name)
        if j < 0:
            continue  # ``joints`` reports it
        acts = by_joint.get(j, [])
        if not acts:
            present.fail(label, "no actuator drives this movable joint")
            continue
        present.ok()
        a = acts[0]
        _compare_gains(joint, model, a, drives, gains)
        _compare_ctrlrange(joint, model, a, ranges)
        _compare_forcerange(joint, model, j, a, ranges)
    present.finish("movable joints")
    gains.finish("actuators", "gain")
    ranges.finish("ranges", "actuator_range")


def _compare_gains(joint: Joint, model: Any, a: int, drives: Drives | None, tally: Tally) -> None:
    label = joint_label(joint.name)
    kp, kv = float(model.actuator_gainprm[a][0]), -float(model.actuator_biasprm[a][2])
    if drives is None or joint.name not in drives:
        return
    want_kp, want_kv = drives[joint.name]
    if want_kp == 0 and want_kv == 0:
        # A zero-gain servo is passive: MuJoCo stores it as gain 0, which reads as no servo at all.
        tally.measure(label, abs(kp) + abs(kv), f"MuJoCo kp {kp:.9g}, kv {kv:.9g}; expected 0 and 0 (a passive joint)")
        return
    if not is_position_servo(model, a):
        tally.fail(label, f"expected a position actuator with kp {want_kp:.9g}; MuJoCo's is not a position servo")
        return
    err = max(_rel(kp, want_kp), _rel(kv, want_kv))
    unit = "N·m/rad" if joint.type.is_angular else "N/m"
    tally.measure(label, err, f"MuJoCo kp {kp:.9g}, kv {kv:.9g}; expected kp {want_kp:.9g}, kv {want_kv:.9g} ({unit})")


def _rel(got: float, want: float) -> float:
    return abs(got - want) / max(abs(want), 1e-12) if (got or want) else 0.0


def _compare_ctrlrange(joint: Joint, model: Any, a: int, tally: Tally) -> None:
    """A position actuator's control is a joint target: its range is the joint's limits."""
    lim = joint.limit
    if joint.type is JointType.CONTINUOUS or lim is None or lim.lower is None or lim.upper is None:
        return  # an unlimited joint's target may be anywhere
    if lim.lower >= lim.upper or not is_position_servo(model, a):
        return  # ``limits`` warns about a zero-width range; other actuators' controls are not positions
    label = joint_label(joint.name)
    if not model.actuator_ctrllimited[a]:
        tally.fail(label, f"position actuator has no ctrlrange; joint range [{lim.lower:.9g}, {lim.upper:.9g}]")
        return
    lo, hi = (float(x) for x in model.actuator_ctrlrange[a])
    tally.measure(
        label,
        max(abs(lo - lim.lower), abs(hi - lim.upper)),
        f"ctrlrange [{lo:.9g}, {hi:.9g}], joint range [{lim.lower:.9g}, {lim.upper:.9g}]",
    )


def _compare_forcerange(joint: Joint, model: Any, j: int, a: int, tally: Tally) -> None:
    """The URDF effort limit bounds the force: on the actuator, or on the joint (``actfrcrange``,
    where MuJoCo's URDF loader puts it); either clamps what the actuator can apply."""
    effort = joint.limit.effort if joint.limit is not None else None
    if effort is None or effort <= 0:
        return
    label = joint_label(joint.name)
    if model.actuator_forcelimited[a]:
        # The joint gets gear x the actuator's force: a motor through a reduction is clamped at
        # effort / gear (robodesc writes it so); a servo's gear is 1.
        gear = abs(float(model.actuator_gear[a][0])) or 1.0
        lo, hi = (float(x) * gear for x in model.actuator_forcerange[a])
        where = "forcerange x gear"
    elif model.jnt_actfrclimited[j]:
        lo, hi = (float(x) for x in model.jnt_actfrcrange[j])
        where = "joint actuatorfrcrange"
    else:
        tally.fail(label, f"the actuator's force is unlimited; source effort limit {effort:.9g}")
        return
    tally.measure(
        label,
        max(abs(lo + effort), abs(hi - effort)) / max(effort, 1.0),
        f"{where} [{lo:.9g}, {hi:.9g}], source effort ±{effort:.9g}",
    )


# ---- loop joints ------------------------------------------------------------------------------
def compare_loops(robot: Robot, model: Any, report: ValidationReport) -> None:
    """Each loop joint closes through an equality: ``connect`` when spherical, ``weld`` otherwise."""
    if not robot.loop_joints:
        return
    ids = Ids(model)
    tally = Tally(report, "loops", None, "")
    for loop in robot.loop_joints:
        want = EQ_CONNECT if loop.type == "spherical" else EQ_WELD
        pair = {ids.body(loop.link1.link), ids.body(loop.link2.link)}
        found = [e for e in range(model.neq) if int(model.eq_type[e]) == want and _eq_bodies(model, e) == pair]
        if found:
            tally.ok()
        else:
            kind = "connect" if want == EQ_CONNECT else "weld"
            tally.fail(
                f"loop joint {loop.name!r}",
                f"no <equality {kind}> joins links {loop.link1.link!r} and {loop.link2.link!r}",
            )
    tally.finish("loop joints")


def _eq_bodies(model: Any, e: int) -> set[int]:
    """The two bodies an equality joins (its objects may be bodies or sites)."""
    objs = (int(model.eq_obj1id[e]), int(model.eq_obj2id[e]))
    if int(model.eq_objtype[e]) == OBJ_SITE:
        return {int(model.site_bodyid[o]) for o in objs}
    return set(objs)
