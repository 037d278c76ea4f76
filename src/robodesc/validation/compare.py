"""Compare a compiled MuJoCo model with the IR it was emitted from.

Per link: presence, parent, mass, centre of mass and inertia tensor (in the link frame). Per
joint: presence, type, axis, limits, damping, friction, mimic coupling. Then forward kinematics
of every link relative to the root at random configurations within the limits. Every mismatch is
a failing check naming the element; passing elements are summed up in one row per quantity.
"""

from __future__ import annotations

import math
from collections.abc import Collection
from typing import Any

import mujoco
import numpy as np
from numpy.typing import NDArray

from robodesc.ir.inertia import tensor
from robodesc.ir.model import Joint, JointType, Link, Robot
from robodesc.ir.transforms import forward_kinematics, quat_wxyz_to_matrix, resolve_mimic, rpy_to_matrix
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Status, Tally, ValidationReport

Mat = NDArray[np.float64]
# Plain ints: MuJoCo's enums do not compare reliably with numpy integers inside ``in``.
FREE = int(mujoco.mjtJoint.mjJNT_FREE)
BALL = int(mujoco.mjtJoint.mjJNT_BALL)
HINGE = int(mujoco.mjtJoint.mjJNT_HINGE)
SLIDE = int(mujoco.mjtJoint.mjJNT_SLIDE)
EQ_JOINT = int(mujoco.mjtEq.mjEQ_JOINT)
_EXPECTED_TYPE = {
    JointType.REVOLUTE: HINGE,
    JointType.CONTINUOUS: HINGE,
    JointType.PRISMATIC: SLIDE,
    JointType.FLOATING: FREE,
    JointType.SPHERICAL: BALL,
}
_TYPE_NAME = {HINGE: "hinge", SLIDE: "slide", FREE: "free", BALL: "ball"}


class Ids:
    """Name look-ups in the compiled model (``-1`` when absent)."""

    def __init__(self, model: Any) -> None:
        self.model = model

    def body(self, name: str) -> int:
        return int(mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_BODY, name))

    def joint(self, name: str) -> int:
        return int(mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_JOINT, name))


def link_label(name: str) -> str:
    return f"link {name!r}"


def joint_label(name: str) -> str:
    return f"joint {name!r}"


def compare_structure(robot: Robot, model: Any, report: ValidationReport) -> set[str]:
    """Links and joints present with the right parents. Returns the links MuJoCo lacks."""
    ids = Ids(model)
    tally = Tally(report, "bodies", None, "")
    missing: set[str] = set()
    for link in robot.links:
        if ids.body(link.name) < 0:
            missing.add(link.name)
            tally.fail(
                link_label(link.name),
                "link is missing from the MuJoCo model (dropped or merged away); its mass and frames are lost",
            )
        else:
            tally.ok()
    ir_names = {link.name for link in robot.links}
    for b in range(1, model.nbody):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b) or f"#{b}"
        if name not in ir_names:
            tally.fail(f"body {name!r}", "MuJoCo has a body that is not a link of the robot")
    tally.finish("links")

    parents = Tally(report, "parents", None, "")
    for joint in robot.joints:
        c, p = ids.body(joint.child), ids.body(joint.parent)
        if c < 0 or p < 0:
            continue
        actual = int(model.body_parentid[c])
        if c == 0 and p != 0:
            # A link named 'world' below another link: MuJoCo (like Gazebo and Drake) takes any link
            # of that name as the world itself, so it cannot hang from anything. The source's world
            # joint has its parent and child swapped; robodesc wrote it as given.
            report.add(
                "parents",
                Status.WARN,
                joint_label(joint.name),
                f"child link 'world' of parent {joint.parent!r}: MuJoCo reads a link named 'world' as the world "
                "itself, so the robot hangs from it instead (the source's world joint has parent and child "
                "swapped; a defect of the source, carried through unchanged)",
            )
        elif actual != p:
            got = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, actual) or "world"
            parents.fail(
                joint_label(joint.name), f"child link {joint.child!r} hangs from {got!r}, not {joint.parent!r}"
            )
        else:
            parents.ok()
    parents.finish("joints")
    return missing


def compare_inertials(
    robot: Robot, model: Any, patched: dict[str, str], options: ValidateOptions, report: ValidationReport
) -> None:
    ids = Ids(model)
    mass = Tally(report, "mass", options.mass_rel_tol, "relative")
    com = Tally(report, "com", options.position_tol, "m")
    inertia = Tally(report, "inertia", options.inertia_rel_tol, "relative")
    tokens = 0.0  # what MuJoCo holds on patched links: a token of the loader's, not the robot's mass
    for link in robot.links:
        b = ids.body(link.name)
        label = link_label(link.name)
        if b < 0:
            continue
        if link.name in patched:
            tokens += float(model.body_mass[b]) if b > 0 else 0.0
            for t in (mass, com, inertia):
                t.skip(label, f"patched to load: {patched[link.name]}")
            continue
        if b == 0:  # a link named "world" is MuJoCo's world body, which has no inertia
            continue
        m_ir, com_ir, tensor_ir = expected_inertial(link)
        m_mj = float(model.body_mass[b])
        err = abs(m_mj - m_ir) / max(abs(m_ir), 1e-12) if (m_mj or m_ir) else 0.0
        mass.measure(label, err, f"MuJoCo mass {m_mj:.9g} kg, source {m_ir:.9g} kg")
        if m_ir > 0:
            c_mj = np.asarray(model.body_ipos[b], dtype=float)
            e = float(np.linalg.norm(c_mj - com_ir))
            com.measure(
                label,
                e,
                (f"MuJoCo centre of mass {_vec(c_mj)}, source {_vec(com_ir)} (link frame, m)"),
            )
            if tensor_ir is None:
                inertia.skip(label, "source gives no inertia tensor")
            else:
                t_mj = mujoco_inertia(model, b)
                scale = max(float(np.max(np.abs(np.linalg.eigvalsh(tensor_ir)))), 1e-12)
                e = float(np.max(np.abs(t_mj - tensor_ir))) / scale
                inertia.measure(
                    label,
                    e,
                    (f"MuJoCo tensor {_tensor(t_mj)} vs source {_tensor(tensor_ir)} (link frame, kg·m²)"),
                )
    mass.finish("links", "mass")
    com.finish("links", "com")
    inertia.finish("links", "inertia")
    # Every body but the world: a mass on a body that is no link, or a link lost, shows in the total.
    # A link that is MuJoCo's world body (named "world", or fused into it: a base welded to the world,
    # merge_fixed) weighs nothing in MuJoCo, which never moves it.
    want = sum(
        expected_inertial(link)[0] for link in robot.links if link.name not in patched and ids.body(link.name) != 0
    )
    got = float(np.sum(model.body_mass[1:])) - tokens
    compare_total_mass(
        robot, got, want, options.mass_rel_tol, report, "MuJoCo (loader tokens on patched links left out)"
    )


def compare_total_mass(
    robot: Robot, got: float, want: float, tolerance: float, report: ValidationReport, reader: str
) -> None:
    """The robot's total mass as ``reader`` sums it against the source's: a row of its own
    (``total mass``), so that a lost or invented mass shows as what it is."""
    total = Tally(report, "total mass", tolerance, "relative")
    negative = [link.name for link in robot.links if link.inertial is not None and (link.inertial.mass or 0.0) < 0]
    if negative:
        # The verifier's warning names it; a consumer drops or clamps a negative mass its own way.
        total.skip(f"robot {robot.name!r}", f"the source gives a negative mass ({', '.join(negative[:3])})")
        total.finish("robot", "mass")
        return
    total.measure(
        f"robot {robot.name!r}",
        abs(got - want) / max(abs(want), 1e-12) if (got or want) else 0.0,
        f"{reader}: total {got:.9g} kg, source {want:.9g} kg",
    )
    total.finish("robot", "mass")


def expected_inertial(link: Link) -> tuple[float, Mat, Mat | None]:
    """Mass, centre of mass and inertia tensor in the link frame, as the IR says."""
    inertial = link.inertial
    if inertial is None or inertial.mass is None:
        return 0.0, np.zeros(3), np.zeros((3, 3))
    origin = inertial.origin
    c = np.asarray(origin.xyz if origin is not None else (0.0, 0.0, 0.0), dtype=float)
    if inertial.inertia is None:
        return float(inertial.mass), c, None
    r = rpy_to_matrix(origin.rpy) if origin is not None else np.eye(3)
    t: Mat = r @ tensor(inertial.inertia) @ r.T
    return float(inertial.mass), c, t


def mujoco_inertia(model: Any, body: int) -> Mat:
    r = quat_wxyz_to_matrix(tuple(float(x) for x in model.body_iquat[body]))  # type: ignore[arg-type]
    out: Mat = r @ np.diag(np.asarray(model.body_inertia[body], dtype=float)) @ r.T
    return out


def compare_joints(robot: Robot, model: Any, options: ValidateOptions, report: ValidationReport) -> None:
    ids = Ids(model)
    present = Tally(report, "joints", None, "")
    kinds = Tally(report, "joint-type", None, "")
    axes = Tally(report, "axis", options.axis_tol, "")
    limits = Tally(report, "limits", options.limit_tol, "rad or m")
    dynamics = Tally(report, "dynamics", options.limit_tol, "")
    mimics = Tally(report, "mimic", options.limit_tol, "")
    ir_joint_names = set()
    for joint in robot.joints:
        label = joint_label(joint.name)
        child = ids.body(joint.child)
        j = ids.joint(joint.name)
        if joint.type is JointType.FIXED:
            if child >= 0 and int(model.body_jntnum[child]) != 0 and j < 0:
                kinds.fail(label, f"fixed joint, but MuJoCo gives link {joint.child!r} a degree of freedom")
            else:
                kinds.ok()
            continue
        ir_joint_names.add(joint.name)
        if joint.type is JointType.PLANAR:
            ir_joint_names.update(_compare_planar(joint, model, ids, present, kinds, axes))
            continue
        if j < 0:
            present.fail(label, f"{joint.type.value} joint is missing from the MuJoCo model")
            continue
        present.ok()
        jtype = int(model.jnt_type[j])
        want = _EXPECTED_TYPE[joint.type]
        if jtype != want:
            kinds.fail(label, f"MuJoCo made a {_TYPE_NAME.get(jtype, str(jtype))} joint of a {joint.type.value} joint")
            continue
        kinds.ok()
        if joint.type.dof != 1:
            continue
        a_ir = np.asarray(joint.effective_axis, dtype=float)
        a_ir = a_ir / np.linalg.norm(a_ir)
        a_mj = np.asarray(model.jnt_axis[j], dtype=float)
        axes.measure(
            label,
            float(np.linalg.norm(a_mj - a_ir)),
            f"MuJoCo axis {_vec(a_mj)}, source {_vec(a_ir)} (child link frame)",
        )
        _compare_limit(joint, model, j, limits)
        dof = int(model.jnt_dofadr[j])
        dyn = joint.dynamics
        for attr, got in (("damping", model.dof_damping[dof]), ("friction", model.dof_frictionloss[dof])):
            want_v = getattr(dyn, attr) if dyn is not None else None
            want_f = float(want_v) if want_v is not None else 0.0
            dynamics.measure(
                label,
                abs(float(got) - want_f),
                f"MuJoCo {attr} {float(got):.9g}, source {want_f:.9g}",
            )
        if joint.mimic is not None:
            _compare_mimic(joint, model, ids, j, mimics)
    for k in range(model.njnt):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, k)
        if int(model.jnt_type[k]) == FREE and name not in ir_joint_names:
            # The free joint added for a floating base: unnamed from MuJoCo's URDF loader, named
            # (``<freejoint name=...>``) in MJCF written for a floating robot.
            continue
        if name not in ir_joint_names:
            present.fail(f"joint {name!r}", "MuJoCo has a joint that the robot does not")
    present.finish("movable joints")
    kinds.finish("joints")
    axes.finish("joints", "axis")
    limits.finish("joints", "limit")
    dynamics.finish("values")
    mimics.finish("mimic joints")


# MuJoCo's URDF reader expands a planar joint NAME into two slides in the plane and a hinge about
# its normal (the joint's axis), named so.
PLANAR_PARTS = (("_TX", SLIDE), ("_TY", SLIDE), ("_RZ", HINGE))


def _compare_planar(joint: Joint, model: Any, ids: Ids, present: Tally, kinds: Tally, axes: Tally) -> set[str]:
    """Check MuJoCo's three joints for a planar joint; returns their names (the robot's, not extras)."""
    label = joint_label(joint.name)
    names = {joint.name + suffix: kind for suffix, kind in PLANAR_PARTS}
    found = {name: ids.joint(name) for name in names}
    if any(j < 0 for j in found.values()):
        if ids.joint(joint.name) >= 0:  # a consumer that keeps one planar joint
            present.ok()
            return set()
        missing = ", ".join(n for n, j in found.items() if j < 0)
        present.fail(label, f"planar joint: MuJoCo lacks {missing} (its expansion into two slides and a hinge)")
        return {n for n, j in found.items() if j >= 0}
    present.ok()
    child = ids.body(joint.child)
    a_ir = np.asarray(joint.effective_axis, dtype=float)
    a_ir = a_ir / np.linalg.norm(a_ir)
    for name, j in found.items():
        if int(model.jnt_type[j]) != names[name] or (child >= 0 and int(model.jnt_bodyid[j]) != child):
            kinds.fail(label, f"MuJoCo's {name!r} is not the {_TYPE_NAME[names[name]]} of link {joint.child!r}")
            return set(found)
    kinds.ok()
    normal = np.asarray(model.jnt_axis[found[joint.name + "_RZ"]], dtype=float)
    slides = [np.asarray(model.jnt_axis[found[joint.name + s]], dtype=float) for s in ("_TX", "_TY")]
    # The hinge turns about the plane's normal and both slides lie in the plane.
    err = max(float(np.linalg.norm(normal - a_ir)), *(abs(float(np.dot(v, a_ir))) for v in slides))
    axes.measure(label, err, f"MuJoCo planar normal {_vec(normal)}, source {_vec(a_ir)} (child link frame)")
    return set(found)


def _compare_limit(joint: Joint, model: Any, j: int, tally: Tally) -> None:
    label = joint_label(joint.name)
    limited = bool(model.jnt_limited[j])
    lim = joint.limit
    has = joint.type is not JointType.CONTINUOUS and lim is not None and lim.lower is not None and lim.upper is not None
    if not has:
        if limited:
            lo, hi = (float(x) for x in model.jnt_range[j])
            tally.fail(label, f"source has no position limits, MuJoCo limits it to [{lo:.9g}, {hi:.9g}]")
        else:
            tally.ok()
        return
    assert lim is not None and lim.lower is not None and lim.upper is not None
    if lim.lower >= lim.upper:
        # MuJoCo ignores a zero-width or inverted range and leaves the joint unlimited.
        tally.report.add(
            "limits",
            Status.WARN,
            label,
            f"limits [{lim.lower:.9g}, {lim.upper:.9g}] have no width; MuJoCo ignores them and the joint moves freely",
        )
        return
    if not limited:
        tally.fail(label, f"MuJoCo leaves the joint unlimited; source limits [{lim.lower:.9g}, {lim.upper:.9g}]")
        return
    lo, hi = (float(x) for x in model.jnt_range[j])
    err = max(abs(lo - lim.lower), abs(hi - lim.upper))
    unit = "rad" if joint.type.is_angular else "m"
    tally.measure(
        label,
        err,
        f"MuJoCo range [{lo:.9g}, {hi:.9g}] {unit}, source [{lim.lower:.9g}, {lim.upper:.9g}] {unit}",
    )


def _compare_mimic(joint: Joint, model: Any, ids: Ids, j: int, tally: Tally) -> None:
    assert joint.mimic is not None
    label = joint_label(joint.name)
    leader = ids.joint(joint.mimic.joint)
    mult = joint.mimic.multiplier if joint.mimic.multiplier is not None else 1.0
    off = joint.mimic.offset if joint.mimic.offset is not None else 0.0
    for e in range(model.neq):
        coupling = _joint_coupling(model, e, j, leader)
        if coupling is None:
            continue
        got_mult, got_off, nonlinear = coupling
        tally.measure(
            label,
            max(abs(got_off - off), abs(got_mult - mult), nonlinear),
            f"MuJoCo couples q = {got_mult:.9g}·q_leader + {got_off:.9g}"
            + (f" + terms up to {nonlinear:.3g}·q_leader^k (k > 1)" if nonlinear else "")
            + f", source {mult:.9g}·q_leader + {off:.9g}",
        )
        return
    tally.fail(label, f"no MuJoCo equality constraint makes it follow joint {joint.mimic.joint!r}")


def _joint_coupling(model: Any, e: int, j: int, leader: int) -> tuple[float, float, float] | None:
    """(multiplier, offset, largest non-linear coefficient) of ``q_j = multiplier·q_leader + offset``
    as joint equality ``e`` states it, or None when ``e`` does not couple these two joints.

    MuJoCo's ``<equality joint>`` says ``q1 = a0 + a1·q2 + a2·q2² + ...``. MuJoCo's URDF loader puts
    the mimicking joint first; other converters write the leader first, which states the same
    linear coupling inverted (``q = (q_leader - a0) / a1``).
    """
    if int(model.eq_type[e]) != EQ_JOINT:
        return None
    pair = (int(model.eq_obj1id[e]), int(model.eq_obj2id[e]))
    a0, a1, *higher = (float(x) for x in model.eq_data[e][:5])
    nonlinear = max(abs(h) for h in higher)
    if pair == (j, leader):
        return a1, a0, nonlinear
    if pair == (leader, j) and a1 != 0.0:
        return 1.0 / a1, -a0 / a1, nonlinear
    return None


# ---- forward kinematics -----------------------------------------------------------------------
def sample_configurations(robot: Robot, n: int, seed: int) -> list[dict[str, float]]:
    """q = 0 plus ``n`` uniform samples within the limits (±pi or ±0.5 m where unlimited)."""
    rng = np.random.default_rng(seed)
    out: list[dict[str, float]] = [{}]
    movable = [j for j in robot.joints if j.type.dof == 1 and j.mimic is None]
    for _ in range(n):
        q: dict[str, float] = {}
        for joint in movable:
            lo, hi = (-math.pi, math.pi) if joint.type.is_angular else (-0.5, 0.5)
            lim = joint.limit
            if (
                joint.type is not JointType.CONTINUOUS
                and lim is not None
                and lim.lower is not None
                and lim.upper is not None
            ):
                if lim.lower < lim.upper:
                    lo, hi = lim.lower, lim.upper
                else:
                    lo = hi = lim.lower
            q[joint.name] = float(rng.uniform(lo, hi))
        out.append(q)
    return out


def mujoco_fk(model: Any, data: Any, ids: Ids, q: dict[str, float]) -> None:
    data.qpos[:] = model.qpos0
    for name, value in q.items():
        j = ids.joint(name)
        if j >= 0 and int(model.jnt_type[j]) in (HINGE, SLIDE):
            data.qpos[model.jnt_qposadr[j]] = value
    mujoco.mj_kinematics(model, data)


def body_pose(data: Any, b: int) -> Mat:
    t = np.eye(4)
    t[:3, :3] = quat_wxyz_to_matrix(tuple(float(x) for x in data.xquat[b]))  # type: ignore[arg-type]
    t[:3, 3] = data.xpos[b]
    return t


def rotation_angle(r: Mat) -> float:
    """Angle of a rotation matrix; atan2 keeps full precision near 0, where acos loses half the digits."""
    s = 0.5 * math.sqrt(float((r[2, 1] - r[1, 2]) ** 2 + (r[0, 2] - r[2, 0]) ** 2 + (r[1, 0] - r[0, 1]) ** 2))
    c = (float(np.trace(r)) - 1.0) / 2.0
    return math.atan2(s, c)


def pose_error(got: Mat, want: Mat, rel_tol: float = 0.0) -> tuple[float, float]:
    """Position (m) and rotation (rad) distance between two 4x4 poses; the position distance beyond
    ``rel_tol`` times ``want``'s distance from the origin (the rounding of the magnitudes compared)."""
    ep = float(np.linalg.norm(got[:3, 3] - want[:3, 3]))
    if rel_tol:
        ep = max(0.0, ep - rel_tol * float(np.linalg.norm(want[:3, 3])))
    return ep, rotation_angle(want[:3, :3].T @ got[:3, :3])


def keep_worst(
    worst: dict[str, tuple[float, float, dict[str, float]]],
    link: str,
    got: Mat,
    want: Mat,
    q: dict[str, float],
    options: ValidateOptions,
) -> None:
    """Record ``link``'s pose error at ``q`` when it is its largest so far, measured against the
    position and rotation tolerances (what :func:`report_fk` reports)."""
    ep, er = pose_error(got, want, options.position_rel_tol)
    prev = worst.get(link)
    if prev is None or max(ep / options.position_tol, er / options.rotation_tol) > max(
        prev[0] / options.position_tol, prev[1] / options.rotation_tol
    ):
        worst[link] = (ep, er, q)


def compare_fk(
    robot: Robot,
    model: Any,
    options: ValidateOptions,
    report: ValidationReport,
    sites: Collection[str] = (),
) -> None:
    """FK of every link at sampled configurations, relative to the root, against the IR. Links in
    ``sites`` were merged away and are MuJoCo sites of the same name (an MJCF's fixed children)."""
    ids = Ids(model)
    roots = robot.root_links()
    if len(roots) != 1 or ids.body(roots[0].name) < 0:
        report.add("fk", Status.SKIP, "robot", "no single root link present in MuJoCo; FK not compared")
        return
    root_id = ids.body(roots[0].name)
    data = mujoco.MjData(model)
    worst: dict[str, tuple[float, float, dict[str, float]]] = {}
    configs = sample_configurations(robot, options.fk_samples, options.seed)
    for q in configs:
        expected = forward_kinematics(robot, q)
        mujoco_fk(model, data, ids, resolve_mimic(robot, q))
        inv_root = np.linalg.inv(body_pose(data, root_id))
        for link in robot.links:
            pose = _frame_pose(model, data, ids, link.name, link.name in sites)
            if pose is not None and link.name in expected:
                keep_worst(worst, link.name, inv_root @ pose, expected[link.name], q, options)
    report_fk(robot, worst, len(configs), options, report)


def _frame_pose(model: Any, data: Any, ids: Ids, name: str, is_site: bool) -> Any:
    """The world pose (4x4) of body ``name``, or of site ``name``; None when there is none."""
    if not is_site:
        b = ids.body(name)
        return body_pose(data, b) if b >= 0 else None
    s = int(mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, name))
    if s < 0:
        return None
    t = np.eye(4)
    t[:3, :3] = np.asarray(data.site_xmat[s], dtype=float).reshape(3, 3)
    t[:3, 3] = data.site_xpos[s]
    return t


def report_fk(
    robot: Robot,
    worst: dict[str, tuple[float, float, dict[str, float]]],
    n_configs: int,
    options: ValidateOptions,
    report: ValidationReport,
    tolerances: dict[str, tuple[float, float]] | None = None,
) -> None:
    """Turn the worst (position, rotation, configuration) error per link into ``fk`` rows.

    ``tolerances`` (link -> position, rotation) replaces the options' for the links it names: a
    consumer storing float32 gets one that grows with the rounding of the numbers on the link's path."""
    max_p = max((w[0] for w in worst.values()), default=0.0)
    max_r = max((w[1] for w in worst.values()), default=0.0)
    report.note_error("fk_position", max_p)
    report.note_error("fk_rotation", max_r)
    default = (options.position_tol, options.rotation_tol)
    per_link = tolerances or {}

    def bad(name: str) -> bool:
        w = worst.get(name)
        tol_p, tol_r = per_link.get(name, default)
        return w is not None and not (w[0] <= tol_p and w[1] <= tol_r)

    parent_joint = robot.parent_joint()
    failing = [link.name for link in robot.links if bad(link.name)]
    # A wrong joint moves its whole subtree: report the topmost wrong links, count the rest.
    culprits = [n for n in failing if not (n in parent_joint and bad(parent_joint[n].parent))]
    for name in culprits:
        ep, er, q = worst[name]
        joint = parent_joint.get(name)
        below = _descendants(robot, name) & set(failing)
        where = f" (reached through joint {joint.name!r})" if joint is not None else ""
        if joint is not None and joint.name in q:
            q_text = f"{joint.name}={q[joint.name]:.4g} with the other joints at sampled values"
        else:
            q_text = "q = 0" if not q else "a sampled configuration"
        report.add(
            "fk",
            Status.FAIL,
            link_label(name),
            f"pose relative to the root differs by {ep:.3g} m and {er:.3g} rad{where} at {q_text}"
            + (f"; {len(below)} links below it are off as a consequence" if below else ""),
            error=max(ep, er),
            tolerance=max(per_link.get(name, default)),
        )
    if not failing:
        report.add(
            "fk",
            Status.PASS,
            f"{len(worst)} links × {n_configs} configurations",
            f"largest error {max_p:.3g} m, {max_r:.3g} rad",
            error=max(max_p, max_r),
            tolerance=max([max(default), *(max(t) for t in per_link.values())]),
        )


def _descendants(robot: Robot, name: str) -> set[str]:
    by_parent = robot.child_joints()
    out: set[str] = set()
    stack = [name]
    while stack:
        for joint in by_parent.get(stack.pop(), []):
            if joint.child not in out:
                out.add(joint.child)
                stack.append(joint.child)
    return out


def _vec(v: Any) -> str:
    return "(" + ", ".join(f"{float(x):.9g}" for x in v) + ")"


def _tensor(t: Mat) -> str:
    return "[" + ", ".join(f"{float(t[i, j]):.6g}" for i, j in ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))) + "]"
