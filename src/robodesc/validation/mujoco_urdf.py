"""Validate emitted URDF text by loading it in MuJoCo and comparing it with the IR."""

from __future__ import annotations

import time
from dataclasses import replace

import mujoco

from robodesc.ir.model import Robot
from robodesc.validation.compare import compare_fk, compare_inertials, compare_joints, compare_structure
from robodesc.validation.mujoco_load import load_urdf_in_mujoco
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Status, ValidationReport
from robodesc.validation.simulate import simulate


def without_dangling_mimics(robot: Robot, report: ValidationReport) -> Robot:
    """A shallow copy in which a mimic of a joint that does not exist is dropped (with a warning).

    MuJoCo ignores such a mimic and the joint moves on its own; comparing against the same reading
    keeps the kinematics comparable, and the verifier reports the defect as a source problem.
    """
    names = {j.name for j in robot.joints}
    dangling = [j for j in robot.joints if j.mimic is not None and j.mimic.joint not in names]
    if not dangling:
        return robot
    for j in dangling:
        assert j.mimic is not None
        report.add(
            "mimic",
            Status.WARN,
            f"joint {j.name!r}",
            f"mimics joint {j.mimic.joint!r}, which does not exist; compared as an independent joint",
        )
    bad = {j.name for j in dangling}
    joints = [replace(j, mimic=None) if j.name in bad else j for j in robot.joints]
    return replace(robot, joints=joints)


def validate_urdf_text(
    robot: Robot, urdf_text: str, base_dir: str | None = None, options: ValidateOptions | None = None
) -> ValidationReport:
    """Load ``urdf_text`` (emitted from ``robot``) in MuJoCo and compare it with ``robot``.

    ``base_dir`` resolves relative mesh paths in the text. Never raises for a bad model: every
    problem is a failing check naming the element.
    """
    opts = options or ValidateOptions()
    report = ValidationReport(robot=robot.name, target="urdf", consumer="mujoco")
    robot = without_dangling_mimics(robot, report)
    report.info["mujoco"] = mujoco.__version__
    started = time.perf_counter()
    loaded = load_urdf_in_mujoco(robot, urdf_text, base_dir, opts, report)
    if loaded is None:
        return report
    model = loaded.model
    compare_structure(robot, model, report)
    compare_inertials(robot, model, loaded.patched, opts, report)
    compare_joints(robot, model, opts, report)
    compare_fk(robot, model, opts, report)
    if opts.simulate:
        try:
            simulate(robot, loaded.spec, opts, report)
        except ValueError as exc:  # MuJoCo raises ValueError for anything it refuses
            report.add("simulation", Status.FAIL, "model", f"MuJoCo failed during the simulation: {exc}")
    else:
        report.add("simulation", Status.SKIP, "model", "simulation check turned off")
    report.info["validation_seconds"] = f"{time.perf_counter() - started:.3f}"
    return report
