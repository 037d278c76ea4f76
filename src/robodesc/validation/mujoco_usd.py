"""Validate emitted USD: usd-core's physics parser always, MuJoCo's UsdPhysics importer (the
``mujoco-usd`` package) too when present.

``mujoco-usd`` pins its own ``usd-core``, so robodesc never depends on it: install it in a separate
environment to run its checks. Without it the report carries one "skipped" row for it, and the
usd-core checks (:mod:`robodesc.validation.usd_physics`) still decide.
"""

from __future__ import annotations

import importlib.util

from robodesc.ir.model import Robot
from robodesc.validation.compare import compare_fk, compare_inertials, compare_joints, compare_structure
from robodesc.validation.options import ValidateOptions
from robodesc.validation.physx_usd import validate_usd_physx
from robodesc.validation.report import Status, ValidationReport
from robodesc.validation.usd_physics import validate_usd_physics

MUJOCO_USD = "mujoco-usd"


def mujoco_usd_available() -> bool:
    return importlib.util.find_spec("mujoco_usd") is not None


def validate_usd(
    robot: Robot, usd_path: str, options: ValidateOptions | None = None, target: str = "usd"
) -> ValidationReport:
    """The usd-physics report, plus the mujoco-usd checks (named ``mujoco-usd <check>``) when
    mujoco-usd imports, and PhysX's (``physx-*``) when a PhysX interpreter exists; one skip row for
    each that is not there."""
    opts = options or ValidateOptions()
    report = validate_usd_physics(robot, usd_path, opts)
    report.target = target
    mj = validate_usd_mujoco(robot, usd_path, opts)
    if mujoco_usd_available():
        report.consumer = f"{report.consumer} + {MUJOCO_USD}"
        for check in mj.checks:
            if check.name != MUJOCO_USD:
                check.name = f"{MUJOCO_USD} {check.name}"
    report.extend(mj)
    if opts.physx:
        physx = validate_usd_physx(robot, usd_path, opts, target=target)
        if "physx" in physx.info:
            report.consumer = f"{report.consumer} + {physx.consumer}"
        report.extend(physx)
    return report


def validate_usd_mujoco(robot: Robot, usd_path: str, options: ValidateOptions | None = None) -> ValidationReport:
    """Load ``usd_path`` with ``MjSpec.from_file`` through mujoco-usd and compare it with ``robot``."""
    opts = options or ValidateOptions()
    report = ValidationReport(robot=robot.name, target="usd", consumer=MUJOCO_USD)
    if not mujoco_usd_available():
        report.add(
            MUJOCO_USD,
            Status.SKIP,
            "document",
            "skipped: mujoco-usd not installed (it pins usd-core 25.11; install it in its own environment)",
        )
        return report
    import mujoco
    import mujoco_usd  # type: ignore[import-not-found]  # noqa: F401  (registers the USD decoder)

    try:
        spec = mujoco.MjSpec.from_file(usd_path)
        model = spec.compile()
    except ValueError as exc:
        report.add("mujoco-usd", Status.FAIL, "document", f"MuJoCo cannot load the USD: {str(exc).strip()}")
        return report
    report.add("mujoco-usd", Status.PASS, "document", f"loaded: {model.nbody - 1} bodies, {model.njnt} joints")
    # Prim names may have been sanitized; the comparisons name what they cannot find.
    compare_structure(robot, model, report)
    compare_inertials(robot, model, {}, opts, report)
    compare_joints(robot, model, opts, report)
    compare_fk(robot, model, opts, report)
    return report
