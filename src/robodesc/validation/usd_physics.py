"""Validate emitted USD with usd-core's own physics parser (``UsdPhysics``).

``UsdPhysicsLoadStageFromPrimRange`` (``LoadUsdPhysicsFromRange`` before usd 26) is the reference
reading of a UsdPhysics stage that simulator importers build on: it resolves rigid bodies, joints
with their frames, limits and drives, and articulations. What it returns, plus ``UsdPhysics.MassAPI``
for the mass properties, is compared with the IR the file was emitted from.

USD stores these numbers as float32 (``physics:mass``, ``physics:localPos0``, ``physics:lowerLimit``
...), so the tolerances cannot be those of the double-precision consumers: every option below
``FLOAT32_REL_TOL`` / ``FLOAT32_FK_TOL`` is raised to it (see docs/validation.md for the measurements).
"""

from __future__ import annotations

import math
import os
import threading
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from robodesc.ir.model import Joint, JointType, Robot
from robodesc.ir.transforms import (
    Mat,
    axis_angle_matrix,
    forward_kinematics,
    matrix_to_quat_wxyz,
    quat_wxyz_to_matrix,
    resolve_mimic,
    rpy_to_matrix,
)
from robodesc.validation.compare import (
    compare_total_mass,
    expected_inertial,
    joint_label,
    keep_worst,
    link_label,
    pose_error,
    report_fk,
    rotation_angle,
    sample_configurations,
)
from robodesc.validation.mujoco_load import tree_depth
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Status, Tally, ValidationReport
from robodesc.validation.usd_schemas import check_schemas, register_schemas

CONSUMER = "usd-physics"
DEG = 180.0 / math.pi
# float32 carries ~6e-8 relative; 1e-6 leaves a 16x margin and still catches a 1e-5 corruption.
FLOAT32_REL_TOL = 1e-6
# Poses composed through a chain of float32 joint frames drift by ~1e-7 per joint on metre-sized
# robots; 1e-5 m / rad bounds long chains (measured worst over the corpus: see docs/validation.md).
FLOAT32_FK_TOL = 1e-5
FLOAT32_EPS = 2.0**-24  # float32's relative rounding (half an ulp)

_KIND = {
    JointType.REVOLUTE: "RevoluteJoint",
    JointType.CONTINUOUS: "RevoluteJoint",
    JointType.PRISMATIC: "PrismaticJoint",
    JointType.FIXED: "FixedJoint",
    JointType.SPHERICAL: "SphericalJoint",
    JointType.FLOATING: "D6Joint",
    JointType.PLANAR: "D6Joint",
}
_AXES = {"X": (1.0, 0.0, 0.0), "Y": (0.0, 1.0, 0.0), "Z": (0.0, 0.0, 1.0)}


@dataclass
class UsdJoint:
    """One joint as the parser resolved it (frames in the two bodies, axis token, limit)."""

    path: str
    kind: str  # "RevoluteJoint", "FixedJoint" ...
    desc: Any
    body0: str | None  # link name, None when attached to the world
    body1: str | None


@dataclass
class Parsed:
    stage: Any
    robot_path: str
    bodies: dict[str, str] = field(default_factory=dict)  # link name -> body prim path
    extra_bodies: list[str] = field(default_factory=list)  # rigid bodies matching no link
    joints: dict[str, UsdJoint] = field(default_factory=dict)  # IR joint name -> joint
    extra_joints: list[UsdJoint] = field(default_factory=list)
    articulations: list[Any] = field(default_factory=list)
    # link name -> (position, rotation) of the body in the stage, as the parser computed it
    body_poses: dict[str, tuple[Any, Any]] = field(default_factory=dict)


def validate_usd_physics(robot: Robot, usd_path: str, options: ValidateOptions | None = None) -> ValidationReport:
    """Read ``usd_path`` through ``UsdPhysics`` and compare bodies, mass properties, joints,
    articulation root and forward kinematics with ``robot``."""
    opts = options or ValidateOptions()
    report = ValidationReport(robot=robot.name, target="usd", consumer=CONSUMER)
    report.info["input"] = usd_path
    os.environ.setdefault("PXR_WORK_THREAD_LIMIT", "1")  # read once, when pxr loads
    from pxr import Usd

    report.info["usd-physics"] = "usd-core " + ".".join(str(v) for v in Usd.GetVersion())
    # The PhysX and Newton schemas register before the stage opens, so its prims' definitions carry them.
    register_schemas()
    stage = Usd.Stage.Open(usd_path) if os.path.exists(usd_path) else None
    if stage is None:
        report.add("usd-open", Status.FAIL, "document", f"usd-core cannot open {usd_path!r}")
        return report
    prim = stage.GetDefaultPrim()
    if not prim or not prim.IsValid():
        report.add("usd-open", Status.FAIL, "document", "the stage has no default prim (the robot)")
        return report
    depth = tree_depth(robot)
    if parser_stack_size(depth) is None:
        report.add(
            "usd-open",
            Status.WARN,
            "model",
            f"not parsed: the kinematic tree is {depth} joints deep; usd-core's physics parser recurses once per "
            f"joint and would need more than {PARSER_MAX_STACK >> 30} GiB of stack. The USD was written; "
            "its physics was not checked",
        )
        return report
    check_schemas(stage, report)
    parsed = parse(stage, str(prim.GetPath()), robot)
    report.add(
        "usd-open",
        Status.PASS,
        "document",
        f"parsed: {len(parsed.bodies) + len(parsed.extra_bodies)} rigid bodies, "
        f"{len(parsed.joints) + len(parsed.extra_joints)} joints",
    )
    _compare_bodies(robot, parsed, report)
    _compare_inertials(robot, parsed, opts, report)
    _compare_joints(robot, parsed, opts, report)
    _compare_articulation(robot, parsed, report)
    _compare_fk(robot, parsed, opts, report)
    return report


# ---- reading -----------------------------------------------------------------------------------
# usd-core's physics parser walks an articulation recursively on the calling thread: a 50,000-link
# chain overflowed the main thread's 8 MiB stack (SIGSEGV; 20,000 links fitted). The parser runs on
# a thread whose stack grows with the tree's depth (reserved, not committed, memory); past the
# largest stack robodesc asks for, validation says so instead of crashing.
PARSER_STACK_PER_JOINT = 4096  # bytes: over 10x what the parser was measured to use per level
PARSER_MIN_STACK = 64 << 20
PARSER_MAX_STACK = 8 << 30


def parser_stack_size(depth: int) -> int | None:
    """The thread stack (bytes) to parse a tree ``depth`` joints deep, or None when over the cap."""
    size = max(PARSER_MIN_STACK, depth * PARSER_STACK_PER_JOINT)
    return size if size <= PARSER_MAX_STACK else None


def load_physics(stage: Any, root: str, depth: int = 0) -> dict[str, tuple[list[Any], list[Any]]]:
    """The parser's result keyed by object type name ("RigidBody", "RevoluteJoint" ...), parsed on
    a thread with a stack for a tree ``depth`` joints deep (:func:`parser_stack_size`)."""
    from pxr import UsdPhysics

    load = getattr(UsdPhysics, "UsdPhysicsLoadStageFromPrimRange", None)
    result: dict[str, Any] = {}

    def run() -> None:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", DeprecationWarning)
                raw = (load or UsdPhysics.LoadUsdPhysicsFromRange)(stage, [root])
                result["value"] = {str(kind): (list(paths), list(descs)) for kind, (paths, descs) in raw.items()}
        except BaseException as exc:  # re-raised on the caller's thread
            result["error"] = exc

    size = parser_stack_size(depth) or PARSER_MAX_STACK
    previous = threading.stack_size()
    threading.stack_size(size)
    try:
        worker = threading.Thread(target=run, name="usd-physics-parse")
        worker.start()
    finally:
        threading.stack_size(previous)
    worker.join()
    if "error" in result:
        raise result["error"]
    out: dict[str, tuple[list[Any], list[Any]]] = result["value"]
    return out


def parse(stage: Any, root: str, robot: Robot) -> Parsed:
    """Match the parser's bodies and joints to IR links and joints: by prim name, else by
    ``displayName`` (the original name when the IR given is the unsanitized one)."""
    raw = load_physics(stage, root, tree_depth(robot))
    parsed = Parsed(stage, root)
    links = {link.name for link in robot.links}
    body_names: dict[str, str] = {}  # body prim path -> link name
    for path, desc in zip(*raw.get("RigidBody", ([], [])), strict=True):
        name = match_name(stage, str(path), links)
        if name is None or name in parsed.bodies:
            parsed.extra_bodies.append(str(path))
        else:
            parsed.bodies[name] = str(path)
            parsed.body_poses[name] = (desc.position, desc.rotation)
            body_names[str(path)] = name
    joint_names = {joint.name for joint in robot.joints}
    for kind, (paths, descs) in sorted(raw.items()):
        if not kind.endswith("Joint"):
            continue
        for path, desc in zip(paths, descs, strict=True):
            uj = UsdJoint(
                str(path),
                kind,
                desc,
                _body(desc.body0, body_names),
                _body(desc.body1, body_names),
            )
            name = match_name(stage, str(path), joint_names)
            if name is None or name in parsed.joints:
                parsed.extra_joints.append(uj)
            else:
                parsed.joints[name] = uj
    parsed.articulations = list(raw.get("Articulation", ([], []))[1])
    return parsed


def match_name(stage: Any, path: str, names: set[str]) -> str | None:
    """The name in ``names`` the prim at ``path`` stands for: its own, else its ``displayName``."""
    prim = stage.GetPrimAtPath(path)
    if prim.GetName() in names:
        return str(prim.GetName())
    shown = prim.GetDisplayName()
    return str(shown) if shown in names else None


def _body(target: Any, body_names: dict[str, str]) -> str | None:
    path = str(target)
    if not path:
        return None
    return body_names.get(path, path)  # an unknown body keeps its path so messages can show it


def _quat(q: Any) -> Mat:
    x, y, z = q.GetImaginary()
    w = float(q.GetReal())
    if w == 0.0 and x == 0.0 and y == 0.0 and z == 0.0:
        return np.eye(3)  # UsdPhysics' unauthored fallback: robodesc leaves it with a zero tensor
    return quat_wxyz_to_matrix((w, float(x), float(y), float(z)))


def _frame(pos: Any, rot: Any) -> Mat:
    m = np.eye(4)
    m[:3, :3] = _quat(rot)
    m[:3, 3] = [float(pos[0]), float(pos[1]), float(pos[2])]
    return m


def vec_text(v: Any) -> str:
    return "(" + ", ".join(f"{float(x):.9g}" for x in v) + ")"


def _rel(got: float, want: float, floor: float) -> float:
    """Relative error with an absolute floor: below ``floor`` the error is absolute."""
    return abs(got - want) / max(abs(want), floor)


# ---- bodies and mass properties ------------------------------------------------------------------
def _compare_bodies(robot: Robot, parsed: Parsed, report: ValidationReport) -> None:
    tally = Tally(report, "bodies", None, "")
    for link in robot.links:
        if link.name in parsed.bodies:
            tally.ok()
        else:
            tally.fail(link_label(link.name), "no rigid body for this link in the USD (missing or not a RigidBodyAPI)")
    for path in parsed.extra_bodies:
        tally.fail(f"body {path!r}", "the USD has a rigid body that is not a link of the robot")
    tally.finish("links")


def _compare_inertials(robot: Robot, parsed: Parsed, options: ValidateOptions, report: ValidationReport) -> None:
    from pxr import UsdPhysics

    mass = Tally(report, "mass", max(options.mass_rel_tol, FLOAT32_REL_TOL), "relative")
    com = Tally(report, "com", max(options.position_tol, FLOAT32_REL_TOL), "m (relative above 1 m)")
    inertia = Tally(report, "inertia", max(options.inertia_rel_tol, FLOAT32_REL_TOL), "relative")
    usd_total = ir_total = 0.0
    derived: list[str] = []  # bodies every reader gives a mass of its own choosing
    for link in robot.links:
        path = parsed.bodies.get(link.name)
        if path is None:
            continue
        label = link_label(link.name)
        api = UsdPhysics.MassAPI(parsed.stage.GetPrimAtPath(path))
        m_attr = api.GetMassAttr() if api else None
        m_usd = m_attr.Get() if m_attr is not None and m_attr.HasAuthoredValue() else None
        # physics:mass 0 is UsdPhysics' "not given": readers derive one, as for no attribute.
        if m_usd is not None and float(m_usd) > 0:
            usd_total += float(m_usd)
        else:
            derived.append(link.name)
        m_ir, com_ir, tensor_ir = expected_inertial(link)
        ir_total += m_ir
        has_ir = link.inertial is not None and link.inertial.mass is not None
        if not has_ir or not m_usd:
            if m_usd:
                mass.fail(label, f"USD mass {m_usd:.9g} kg, the source gives none")
            elif has_ir and m_ir > 0:
                mass.fail(label, f"no physics:mass in the USD; source {m_ir:.9g} kg")
            else:
                mass.fail(
                    label,
                    "no mass in the USD: every UsdPhysics reader derives one from the colliders at 1000 kg/m³ "
                    "(PhysX gives 1 kg to a body without any); the source gives none (the massless pass "
                    "gives such a link a placeholder taken from what it is fixed to)",
                )
            continue
        mass.measure(label, _rel(float(m_usd), m_ir, 1e-12), f"USD mass {float(m_usd):.9g} kg, source {m_ir:.9g} kg")
        c = api.GetCenterOfMassAttr().Get()
        c_usd = np.array([float(x) for x in c]) if c is not None else np.zeros(3)
        com.measure(
            label,
            float(np.linalg.norm(c_usd - com_ir)) / max(1.0, float(np.linalg.norm(com_ir))),
            f"USD centre of mass {vec_text(c_usd)}, source {vec_text(com_ir)} (link frame, m)",
        )
        if tensor_ir is None:
            inertia.skip(label, "source gives no inertia tensor")
            continue
        diag = api.GetDiagonalInertiaAttr().Get()
        axes = api.GetPrincipalAxesAttr().Get()
        if diag is None or axes is None:
            inertia.fail(label, "no physics:diagonalInertia / principalAxes in the USD")
            continue
        r = _quat(axes)
        t_usd: Mat = r @ np.diag([float(x) for x in diag]) @ r.T
        scale = max(float(np.max(np.abs(np.linalg.eigvalsh(tensor_ir)))), 1e-12)
        inertia.measure(
            label,
            float(np.max(np.abs(t_usd - tensor_ir))) / scale,
            f"USD tensor {tensor_text(t_usd)} vs source {tensor_text(tensor_ir)} (link frame, kg·m²)",
        )
    mass.finish("links", "mass")
    com.finish("links", "com")
    inertia.finish("links", "inertia")
    _compare_total(robot, usd_total, ir_total, derived, options, report)


def _compare_total(
    robot: Robot,
    usd_total: float,
    ir_total: float,
    derived: list[str],
    options: ValidateOptions,
    report: ValidationReport,
) -> None:
    """The robot's total mass as a UsdPhysics reader sums it, against the source's: a row of its own,
    so that a difference shows as what it is (a lost or invented mass) wherever it comes from."""
    tolerance = max(options.mass_rel_tol, FLOAT32_REL_TOL)
    if not derived:
        compare_total_mass(robot, usd_total, ir_total, tolerance, report, "USD (authored physics:mass)")
        return
    shown = ", ".join(repr(n) for n in derived[:5]) + (f" and {len(derived) - 5} more" if len(derived) > 5 else "")
    total = Tally(report, "total mass", tolerance, "relative")
    total.fail(
        f"robot {robot.name!r}",
        f"{len(derived)} bodies have no mass in the USD ({shown}): readers add a mass from their colliders "
        f"(PhysX: 1 kg each without any) to the {usd_total:.6g} kg authored; the source weighs {ir_total:.6g} kg",
    )
    total.finish("robot", "mass")


def tensor_text(t: Mat) -> str:
    return "[" + ", ".join(f"{float(t[i, j]):.6g}" for i, j in ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))) + "]"


# ---- joints --------------------------------------------------------------------------------------
def _compare_joints(robot: Robot, parsed: Parsed, options: ValidateOptions, report: ValidationReport) -> None:
    present = Tally(report, "joints", None, "")
    kinds = Tally(report, "joint-type", None, "")
    ends = Tally(report, "parents", None, "")
    axes = Tally(report, "axis", max(options.axis_tol, FLOAT32_REL_TOL), "")
    limits = Tally(report, "limits", max(options.limit_tol, FLOAT32_REL_TOL), "relative (deg or m)")
    for joint in robot.joints:
        label = joint_label(joint.name)
        uj = parsed.joints.get(joint.name)
        if uj is None:
            present.fail(label, f"{joint.type.value} joint is missing from the USD")
            continue
        present.ok()
        want = _KIND[joint.type]
        if uj.kind != want:
            kinds.fail(label, f"the USD has a {uj.kind} for a {joint.type.value} joint (expected {want})")
            continue
        kinds.ok()
        if (uj.body0, uj.body1) != (joint.parent, joint.child):
            ends.fail(
                label,
                f"body0/body1 are {uj.body0!r}/{uj.body1!r}, expected parent {joint.parent!r} and child {joint.child!r}",
            )
        else:
            ends.ok()
        if joint.type.dof != 1:
            continue
        a_ir = np.asarray(joint.effective_axis, dtype=float)
        a_ir = a_ir / np.linalg.norm(a_ir)
        token = str(uj.desc.axis)
        a_usd = _quat(uj.desc.localPose1Orientation) @ np.asarray(_AXES.get(token, (math.nan,) * 3))
        axes.measure(
            label,
            float(np.linalg.norm(a_usd - a_ir)),
            f"USD axis {token} turned by localRot1 is {vec_text(a_usd)} in the child frame, source {vec_text(a_ir)}",
        )
        _compare_limit(joint, uj, limits)
    for uj in parsed.extra_joints:
        if uj.desc.excludeFromArticulation:
            continue  # loop closures (the IR keeps them apart from the tree)
        if uj.kind == "FixedJoint" and uj.body0 is None:
            continue  # the base weld of a fixed base; checked with the articulation root
        present.fail(f"joint {uj.path!r}", f"the USD has a {uj.kind} that the robot does not")
    present.finish("joints")
    kinds.finish("joints")
    ends.finish("joints")
    axes.finish("joints", "axis")
    limits.finish("joints", "limit")


def _compare_limit(joint: Joint, uj: UsdJoint, tally: Tally) -> None:
    label = joint_label(joint.name)
    limit = uj.desc.limit
    lim = joint.limit
    has = joint.type is not JointType.CONTINUOUS and lim is not None and lim.lower is not None and lim.upper is not None
    angular = joint.type.is_angular
    unit, unit_name = (DEG, "deg") if angular else (1.0, "m")
    if not has:
        if limit.enabled:
            tally.fail(
                label, f"source has no position limits, the USD limits it to [{limit.lower:.9g}, {limit.upper:.9g}]"
            )
        else:
            tally.ok()
        return
    assert lim is not None and lim.lower is not None and lim.upper is not None
    lo, hi = lim.lower * unit, lim.upper * unit
    if not limit.enabled:
        tally.fail(label, f"the USD leaves the joint unlimited; source limits [{lo:.9g}, {hi:.9g}] {unit_name}")
        return
    err = max(_rel(float(limit.lower), lo, 1.0), _rel(float(limit.upper), hi, 1.0))
    tally.measure(
        label,
        err,
        f"USD limits [{float(limit.lower):.9g}, {float(limit.upper):.9g}] {unit_name}, "
        f"source [{lo:.9g}, {hi:.9g}] {unit_name}"
        + (f" (= [{lim.lower:.9g}, {lim.upper:.9g}] rad)" if angular else ""),
    )


# ---- articulation root ---------------------------------------------------------------------------
def _compare_articulation(robot: Robot, parsed: Parsed, report: ValidationReport) -> None:
    """Fixed base: the root API on the robot prim plus a ``root_joint`` (no body0, body1 = root
    link). Floating base: the root API on the root link. Exactly one either way."""
    from pxr import Usd, UsdPhysics

    stage = parsed.stage
    roots = [
        str(p.GetPath())
        for p in Usd.PrimRange(stage.GetPrimAtPath(parsed.robot_path))
        if p.HasAPI(UsdPhysics.ArticulationRootAPI)
    ]
    try:
        root_link = robot.root.name
    except ValueError:
        report.add("articulation", Status.SKIP, "robot", "the robot has no single root link")
        return
    if len(roots) != 1:
        report.add(
            "articulation",
            Status.FAIL,
            "robot",
            f"{len(roots)} prims carry PhysicsArticulationRootAPI ({', '.join(roots) or 'none'}); expected exactly one",
        )
        return
    welds = [uj for uj in parsed.extra_joints if uj.kind == "FixedJoint" and uj.body0 is None]
    root_body = parsed.bodies.get(root_link)
    if roots[0] == parsed.robot_path:
        layout = "fixed"
        if [uj.body1 for uj in welds] != [root_link]:
            report.add(
                "articulation",
                Status.FAIL,
                f"link {root_link!r}",
                "fixed base, but no single FixedJoint welds the root link to the world "
                f"(found {[uj.path for uj in welds]})",
            )
            return
    elif root_body is not None and roots[0] == root_body:
        layout = "floating"
        if welds:
            report.add(
                "articulation",
                Status.FAIL,
                f"joint {welds[0].path!r}",
                "floating base, but a joint welds a body to the world (PhysX then treats the base as fixed)",
            )
            return
    else:
        report.add(
            "articulation",
            Status.FAIL,
            "robot",
            f"the articulation root is on {roots[0]!r}: expected the robot prim (fixed base) or link {root_link!r}",
        )
        return
    if robot.fixed_base is not None and robot.fixed_base != (layout == "fixed"):
        want = "fixed" if robot.fixed_base else "floating"
        report.add("articulation", Status.FAIL, "robot", f"the source says {want} base, the USD is {layout}-base")
        return
    if len(parsed.articulations) != 1:
        report.add(
            "articulation",
            Status.FAIL,
            "robot",
            f"usd-core resolves {len(parsed.articulations)} articulations; expected one",
        )
        return
    report.add("articulation", Status.PASS, roots[0], f"one articulation, {layout} base")


# ---- forward kinematics --------------------------------------------------------------------------
def usd_forward_kinematics(robot: Robot, parsed: Parsed, root: str, q: dict[str, float]) -> dict[str, Mat]:
    """Link poses relative to ``root`` composed through the USD joints only:
    ``parent · frame0 · motion(axis token, q) · frame1⁻¹``. ``q`` holds IR values (rad, m) by IR joint
    name, mimic followers included."""
    edges: dict[str, list[tuple[str, str, UsdJoint]]] = {}  # body -> [(other body, ir joint name, joint)]
    for name, uj in parsed.joints.items():
        if uj.body0 is None or uj.body1 is None or uj.desc.excludeFromArticulation:
            continue
        edges.setdefault(uj.body0, []).append((uj.body1, name, uj))
    out = {root: np.eye(4)}
    stack = [root]
    while stack:
        parent = stack.pop()
        for child, name, uj in edges.get(parent, []):
            if child in out:
                continue
            d = uj.desc
            motion = np.eye(4)
            axis = _AXES.get(str(getattr(d, "axis", "")))
            value = q.get(name, 0.0)
            if axis is not None and uj.kind == "RevoluteJoint":
                motion[:3, :3] = axis_angle_matrix(axis, value)
            elif axis is not None and uj.kind == "PrismaticJoint":
                motion[:3, 3] = np.asarray(axis) * value
            f0 = _frame(d.localPose0Position, d.localPose0Orientation)
            f1 = _frame(d.localPose1Position, d.localPose1Orientation)
            out[child] = out[parent] @ f0 @ motion @ np.linalg.inv(f1)
            stack.append(child)
    return out


def _f32_rounding(values: tuple[float, ...]) -> float:
    """How far float32 moves these numbers (the norm of the change)."""
    exact = np.asarray(values, dtype=np.float64)
    return float(np.linalg.norm(exact - exact.astype(np.float32).astype(np.float64)))


def float32_fk_tolerances(robot: Robot, options: ValidateOptions) -> dict[str, tuple[float, float]]:
    """Per link, FK tolerances that follow the numbers written: USD stores each joint's frame in
    float32, so the error a link may show is what that rounding adds up to along its path from the
    root (the translation's rounding, plus each rotation's rounding times the offsets after it),
    twice over, on top of the options' tolerances. A 20,000-link chain of 0.1 m offsets drifts by
    ~3e-5 m at its tip (0.1 is 1.5e-9 off in float32); a short robot keeps the fixed tolerance."""
    rot: dict[str, float] = {}
    pos: dict[str, float] = {}
    for joint in robot.topological_joints():  # parents before children
        origin = joint.origin
        xyz = origin.xyz if origin is not None else (0.0, 0.0, 0.0)
        r_parent, p_parent = rot.get(joint.parent, 0.0), pos.get(joint.parent, 0.0)
        turn = 0.0
        if origin is not None and any(origin.rpy):
            q = matrix_to_quat_wxyz(rpy_to_matrix(origin.rpy))
            turn = 2.0 * _f32_rounding(q)
        axis = joint.effective_axis
        if sum(1 for a in axis if a != 0.0) > 1:  # an axis off the coordinate axes is rounded too
            turn += 2.0 * _f32_rounding(tuple(float(a) for a in np.asarray(axis) / np.linalg.norm(axis)))
        rot[joint.child] = r_parent + turn
        pos[joint.child] = p_parent + _f32_rounding(tuple(xyz)) + r_parent * math.hypot(*xyz)
    return {
        name: (options.position_tol + 2.0 * pos[name], options.rotation_tol + 2.0 * rot[name])
        for name in pos
        if pos[name] or rot[name]
    }


def _compare_fk(robot: Robot, parsed: Parsed, options: ValidateOptions, report: ValidationReport) -> None:
    roots = robot.root_links()
    if len(roots) != 1 or roots[0].name not in parsed.bodies:
        report.add("fk", Status.SKIP, "robot", "no single root link present in the USD; FK not compared")
        return
    root = roots[0].name
    opts = ValidateOptions(
        position_tol=max(options.position_tol, FLOAT32_FK_TOL),
        rotation_tol=max(options.rotation_tol, FLOAT32_FK_TOL),
        position_rel_tol=max(options.position_rel_tol, FLOAT32_REL_TOL),
    )
    worst: dict[str, tuple[float, float, dict[str, float]]] = {}
    unreached: set[str] = set()
    configs = sample_configurations(robot, options.fk_samples, options.seed)
    for q in configs:
        expected = forward_kinematics(robot, q)
        got = usd_forward_kinematics(robot, parsed, root, resolve_mimic(robot, q))
        for link in robot.links:
            if link.name not in parsed.bodies or link.name not in expected:
                continue
            if link.name not in got:
                unreached.add(link.name)
                continue
            keep_worst(worst, link.name, got[link.name], expected[link.name], q, opts)
    for name in sorted(unreached):
        report.add("fk", Status.FAIL, link_label(name), f"not reachable from the root link {root!r} through USD joints")
    tolerances = float32_fk_tolerances(robot, opts)
    report_fk(robot, worst, len(configs), opts, report, tolerances)
    _compare_rest_pose(robot, parsed, root, opts, report, tolerances)


def _compare_rest_pose(
    robot: Robot,
    parsed: Parsed,
    root: str,
    options: ValidateOptions,
    report: ValidationReport,
    tolerances: dict[str, tuple[float, float]] | None = None,
) -> None:
    """Where usd-core puts each body at rest (the parser's body transform, what a simulator spawns)
    against the IR at q = 0, relative to the root body."""
    tol = max(options.position_tol, options.rotation_tol)
    tally = Tally(report, "rest-pose", tol, "m or rad")
    expected = forward_kinematics(robot)
    inv_root = np.linalg.inv(_frame(*parsed.body_poses[root]))
    root_reach = float(np.linalg.norm(np.asarray(parsed.body_poses[root][0], dtype=float)))
    for link in robot.links:
        pose = parsed.body_poses.get(link.name)
        if pose is None or link.name not in expected:
            continue
        want = expected[link.name]
        ep, er = pose_error(inv_root @ _frame(*pose), want)
        message = (
            f"usd-core places the body {ep:.3g} m and {er:.3g} rad from the source pose at q = 0 (relative to the root)"
        )
        orient = parsed.stage.GetPrimAtPath(parsed.bodies[link.name]).GetAttribute("xformOp:orient")
        value = orient.Get() if orient else None
        if value is not None and er > tol:
            authored = rotation_angle(want[:3, :3].T @ inv_root[:3, :3] @ _quat(value))
            if authored <= FLOAT32_FK_TOL and orient.GetTypeName() == "quatf" and float(value.GetReal()) == 1.0:
                message += (
                    f"; the authored xformOp:orient is right to {authored:.1g} rad, but its w rounds to 1 in float32"
                    " and usd-core's transform evaluation then drops the rotation (an orient written as quatd keeps it)"
                )
        # usd-core's parser hands body poses back as float32 (GfVec3f, GfQuatf): a body 1,000 m from
        # the origin is only known to ~6e-5 m. The tolerance follows those numbers, and the joint
        # frames' rounding along the path (float32_fk_tolerances).
        path_p, path_r = (tolerances or {}).get(link.name, (0.0, 0.0))
        reach = float(np.linalg.norm(np.asarray(pose[0], dtype=float))) + root_reach
        allowed = max(tol + 4.0 * FLOAT32_EPS * reach + path_p, tol + 4.0 * FLOAT32_EPS + path_r)
        if max(ep, er) <= allowed:
            tally.checked += 1
            tally.max_error = max(tally.max_error, ep, er)
            continue
        tally.measure(link_label(link.name), max(ep, er), message)
    tally.finish("links")
