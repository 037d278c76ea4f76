"""Validate emitted SDFormat with Drake, the strict pip-installable SDFormat parser.

The text is parsed into a ``MultibodyPlant`` without a scene graph (Drake rejects STL collision
meshes once geometry is registered; kinematics and inertia do not need it), finalized, then
compared with the IR: bodies, masses, centres of mass and inertia tensors (in the link frame),
joint types, axes and limits, and forward kinematics relative to the root at random
configurations. Drake floats the root body by default, which the root-relative comparison ignores.
"""

from __future__ import annotations

import logging
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from typing import Any

import numpy as np

from robodesc.ir.model import JointType, Robot
from robodesc.ir.transforms import forward_kinematics, resolve_mimic
from robodesc.validation.compare import (
    compare_total_mass,
    expected_inertial,
    joint_label,
    link_label,
    pose_error,
    sample_configurations,
)
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Status, Tally, ValidationReport

_DRAKE_TYPES = {
    JointType.REVOLUTE: "revolute",
    JointType.CONTINUOUS: "revolute",
    JointType.PRISMATIC: "prismatic",
    JointType.FIXED: "weld",
    JointType.SPHERICAL: "ball_rpy",
    JointType.PLANAR: "planar",
}


def drake_available() -> bool:
    try:
        import pydrake.multibody.parsing  # noqa: F401
    except ImportError:
        return False
    return True


# libsdformat writes "no limit" as ±1e16; anything this large is unlimited.
_UNLIMITED = 1e15


class _Names:
    """IR name -> SDF name (the SDF emitter renames to keep one namespace per model)."""

    def __init__(self, links: Mapping[str, str] | None, joints: Mapping[str, str] | None) -> None:
        self.links = dict(links or {})
        self.joints = dict(joints or {})

    def link(self, name: str) -> str:
        return self.links.get(name, name)

    def joint(self, name: str) -> str:
        return self.joints.get(name, name)


@contextmanager
def _drake_warnings(sink: list[str]) -> Iterator[None]:
    """Collect what Drake logs while parsing (inertia it replaced, ignored tags) for the report."""

    class Handler(logging.Handler):
        def emit(self, record: logging.LogRecord) -> None:
            sink.append(record.getMessage())

    logger = logging.getLogger("drake")
    handler = Handler(level=logging.WARNING)
    propagate = logger.propagate
    logger.addHandler(handler)
    logger.propagate = False
    try:
        yield
    finally:
        logger.removeHandler(handler)
        logger.propagate = propagate


# Deeper trees are parsed and their bodies and joints compared, but not finalized (so no FK): Drake's
# Finalize grows with depth² in memory (a chain: 35 MB at 600 links, 135 MB at 1,200, 400 MB at 2,000).
DRAKE_FINALIZE_DEPTH = 2000
# Deeper trees are not given to Drake at all: libsdformat's graph checks (Root::UpdateGraphs) take
# time that grows with the square of the depth even with model-frame poses (3.2 s CPU at 5,000 joints,
# 11 s at 10,000; a 50,000-link chain did not finish in 40 minutes on a shared machine).
DRAKE_PARSE_DEPTH = 10000


def validate_sdf(
    robot: Robot,
    sdf_text: str,
    options: ValidateOptions | None = None,
    *,
    link_names: Mapping[str, str] | None = None,
    joint_names: Mapping[str, str] | None = None,
) -> ValidationReport:
    """Parse ``sdf_text`` (emitted from ``robot``) with Drake and compare it with ``robot``.

    ``link_names``/``joint_names`` map IR names to the names the SDF emitter gave them where it
    had to rename (``build_sdf(...).names.by_kind["link"]`` / ``["joint"]``); others are expected
    unchanged.
    """
    opts = options or ValidateOptions()
    names = _Names(link_names, joint_names)
    report = ValidationReport(robot=robot.name, target="sdf", consumer="drake")
    if not drake_available():
        report.add("drake-parse", Status.SKIP, "document", "skipped: pydrake is not installed (pip install drake)")
        return report
    import pydrake
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    report.info["drake"] = str(getattr(pydrake, "__version__", "installed"))
    plant = MultibodyPlant(0.0)
    warnings: list[str] = []
    depth = robot.tree_depth()
    if depth > DRAKE_PARSE_DEPTH:
        report.add(
            "drake-parse",
            Status.WARN,
            "document",
            f"not loaded: the tree is {depth} joints deep and Drake's SDF parser takes time that grows with the "
            f"square of the depth beyond {DRAKE_PARSE_DEPTH} (libsdformat's graph checks: 11 s at 10,000, "
            "far longer at 50,000); the other checks need the parsed model",
        )
        return report
    finalize = depth <= DRAKE_FINALIZE_DEPTH
    try:
        with _drake_warnings(warnings):
            instances = Parser(plant).AddModelsFromString(sdf_text, "sdf")
            if finalize:
                plant.Finalize()
    except Exception as exc:  # Drake raises RuntimeError/ValueError with libsdformat's messages
        report.add("drake-parse", Status.FAIL, "document", f"Drake refuses the SDF: {str(exc).strip()}")
        return report
    report.add("drake-parse", Status.PASS, "document", f"parsed by Drake into {len(instances)} model(s)")
    for msg in dict.fromkeys(" ".join(w.split()) for w in warnings):
        report.add("drake-warning", Status.WARN, "document", msg[:400])
    sdf_to_ir = {v: k for k, v in names.links.items()}
    bodies = {
        sdf_to_ir.get(name, name): body for name, body in _bodies(plant, set(sdf_to_ir) | _link_names(robot)).items()
    }
    _compare_bodies(robot, bodies, opts, report)
    _compare_joints(robot, plant, names, opts, report)
    if not finalize:
        report.add(
            "fk",
            Status.WARN,
            "robot",
            f"not compared: the tree is {depth} joints deep, and Drake's MultibodyPlant.Finalize takes memory "
            f"that grows with the square of the depth (135 MB at 1,200, about 230 GB at 50,000); the SDF was "
            f"parsed and its bodies and joints compared (FK up to {DRAKE_FINALIZE_DEPTH} deep)",
        )
        return report
    _compare_fk(robot, plant, bodies, names, opts, report)
    return report


def _link_names(robot: Robot) -> set[str]:
    return {link.name for link in robot.links}


def _bodies(plant: Any, robot_names: set[str]) -> dict[str, Any]:
    """The bodies of the robot's model: a world file (``--world``) adds models of its own (the
    ground plane), whose bodies are not the robot's."""
    from pydrake.multibody.tree import BodyIndex

    by_model: dict[Any, dict[str, Any]] = {}
    for i in range(1, plant.num_bodies()):  # 0 is Drake's world
        body = plant.get_body(BodyIndex(i))
        by_model.setdefault(body.model_instance(), {})[body.name()] = body
    out: dict[str, Any] = {}
    for bodies in by_model.values():
        if len(by_model) == 1 or robot_names & set(bodies):
            out.update(bodies)
    return out


def _compare_bodies(robot: Robot, bodies: dict[str, Any], options: ValidateOptions, report: ValidationReport) -> None:
    present = Tally(report, "bodies", None, "")
    mass = Tally(report, "mass", options.mass_rel_tol, "relative")
    com = Tally(report, "com", options.position_tol, "m")
    inertia = Tally(report, "inertia", options.inertia_rel_tol, "relative")
    names = {link.name for link in robot.links}
    for link in robot.links:
        label = link_label(link.name)
        body = bodies.get(link.name)
        if body is None:
            if link.name == "world":
                continue
            present.fail(label, "link is missing from the Drake plant (dropped or merged away)")
            continue
        present.ok()
        m_ir, c_ir, t_ir = expected_inertial(link)
        m_dk = float(body.default_mass())
        err = abs(m_dk - m_ir) / max(abs(m_ir), 1e-12) if (m_dk or m_ir) else 0.0
        mass.measure(label, err, f"Drake mass {m_dk:.9g} kg, source {m_ir:.9g} kg")
        if m_ir <= 0:
            continue
        c_dk = np.asarray(body.default_com(), dtype=float)
        com.measure(label, float(np.linalg.norm(c_dk - c_ir)), f"Drake COM {c_dk}, source {c_ir}")
        if t_ir is None:
            inertia.skip(label, "source gives no inertia tensor")
            continue
        about_origin = np.asarray(body.default_rotational_inertia().CopyToFullMatrix3(), dtype=float)
        t_dk = about_origin - m_dk * (float(c_dk @ c_dk) * np.eye(3) - np.outer(c_dk, c_dk))
        scale = max(float(np.max(np.abs(np.linalg.eigvalsh(t_ir)))), 1e-12)
        inertia.measure(
            label,
            float(np.max(np.abs(t_dk - t_ir))) / scale,
            (f"Drake tensor {np.round(t_dk, 12).tolist()} vs source {np.round(t_ir, 12).tolist()}"),
        )
    for name in sorted(set(bodies) - names):
        present.fail(f"body {name!r}", "Drake has a body that is not a link of the robot")
    present.finish("links")
    mass.finish("links", "mass")
    com.finish("links", "com")
    inertia.finish("links", "inertia")
    want = sum(expected_inertial(link)[0] for link in robot.links)
    got = sum(float(body.default_mass()) for body in bodies.values())
    compare_total_mass(robot, got, want, options.mass_rel_tol, report, "Drake")


def _compare_joints(
    robot: Robot, plant: Any, names: _Names, options: ValidateOptions, report: ValidationReport
) -> None:
    present = Tally(report, "joints", None, "")
    kinds = Tally(report, "joint-type", None, "")
    axes = Tally(report, "axis", options.axis_tol, "")
    limits = Tally(report, "limits", options.limit_tol, "rad or m")
    for joint in robot.joints:
        label = joint_label(joint.name)
        if not plant.HasJointNamed(names.joint(joint.name)):
            present.fail(label, f"{joint.type.value} joint is missing from the Drake plant")
            continue
        present.ok()
        dj = plant.GetJointByName(names.joint(joint.name))
        want = _DRAKE_TYPES.get(joint.type)
        if want is not None and dj.type_name() != want:
            kinds.fail(label, f"Drake made a {dj.type_name()} joint of a {joint.type.value} joint")
            continue
        kinds.ok()
        if joint.type.dof != 1:
            continue
        axis_f = np.asarray(dj.revolute_axis() if want == "revolute" else dj.translation_axis(), dtype=float)
        r_child = np.asarray(dj.frame_on_child().GetFixedPoseInBodyFrame().rotation().matrix(), dtype=float)
        a_dk = r_child @ axis_f
        a_ir = np.asarray(joint.effective_axis, dtype=float)
        a_ir = a_ir / np.linalg.norm(a_ir)
        axes.measure(
            label,
            float(np.linalg.norm(a_dk - a_ir)),
            f"Drake axis {a_dk}, source {a_ir} (child frame)",
        )
        lo, hi = float(dj.position_lower_limits()[0]), float(dj.position_upper_limits()[0])
        lim = joint.limit
        if joint.type is JointType.CONTINUOUS or lim is None or lim.lower is None or lim.upper is None:
            if abs(lo) < _UNLIMITED or abs(hi) < _UNLIMITED:
                limits.fail(label, f"source has no position limits, Drake limits it to [{lo:.9g}, {hi:.9g}]")
            else:
                limits.ok()
            continue
        l_lo, l_hi = lim.lower, lim.upper
        limits.measure(
            label,
            max(abs(lo - l_lo), abs(hi - l_hi)),
            (f"Drake range [{lo:.9g}, {hi:.9g}], source [{l_lo:.9g}, {l_hi:.9g}]"),
        )
    present.finish("joints")
    kinds.finish("joints")
    axes.finish("joints", "axis")
    limits.finish("joints", "limit")


def _compare_fk(
    robot: Robot, plant: Any, bodies: dict[str, Any], names: _Names, options: ValidateOptions, report: ValidationReport
) -> None:
    roots = robot.root_links()
    if len(roots) != 1 or roots[0].name not in bodies:
        report.add("fk", Status.SKIP, "robot", "no single root link in the Drake plant; FK not compared")
        return
    root = bodies[roots[0].name]
    context = plant.CreateDefaultContext()
    configs = sample_configurations(robot, options.fk_samples, options.seed)
    worst: dict[str, tuple[float, float]] = {}
    for q in configs:
        full = resolve_mimic(robot, q)
        for joint in robot.joints:
            if joint.type.dof != 1 or not plant.HasJointNamed(names.joint(joint.name)):
                continue
            dj = plant.GetJointByName(names.joint(joint.name))
            value = full.get(joint.name, 0.0)
            if dj.type_name() == "revolute":
                dj.set_angle(context, value)
            elif dj.type_name() == "prismatic":
                dj.set_translation(context, value)
        expected = forward_kinematics(robot, q)
        inv_root = np.linalg.inv(plant.EvalBodyPoseInWorld(context, root).GetAsMatrix4())
        for name, body in bodies.items():
            if name not in expected:
                continue
            got = inv_root @ plant.EvalBodyPoseInWorld(context, body).GetAsMatrix4()
            ep, er = pose_error(got, expected[name], options.position_rel_tol)
            prev = worst.get(name, (0.0, 0.0))
            worst[name] = (max(prev[0], ep), max(prev[1], er))
    max_p = max((w[0] for w in worst.values()), default=0.0)
    max_r = max((w[1] for w in worst.values()), default=0.0)
    report.note_error("fk_position", max_p)
    report.note_error("fk_rotation", max_r)
    tol = max(options.position_tol, options.rotation_tol)
    failing = sorted(n for n, (p, r) in worst.items() if not (p <= options.position_tol and r <= options.rotation_tol))
    parent_joint = robot.parent_joint()
    for name in failing:
        pj = parent_joint.get(name)
        if pj is not None and pj.parent in failing:
            continue
        p, r = worst[name]
        report.add(
            "fk",
            Status.FAIL,
            link_label(name),
            f"pose relative to the root differs by {p:.3g} m and {r:.3g} rad",
            error=max(p, r),
            tolerance=tol,
        )
    if not failing:
        report.add(
            "fk",
            Status.PASS,
            f"{len(worst)} links × {len(configs)} configurations",
            f"largest error {max_p:.3g} m, {max_r:.3g} rad",
            error=max(max_p, max_r),
            tolerance=tol,
        )
