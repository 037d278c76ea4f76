"""Validate emitted USD with MuJoCo's UsdPhysics importer (the ``mujoco-usd`` package), when present.

``mujoco-usd`` pins its own ``usd-core``, so robodesc never depends on it: install it in a separate
environment to run this check. Without it the report carries one clear "skipped" row.
"""

from __future__ import annotations

import importlib.util

from robodesc.ir.model import Robot
from robodesc.validation.compare import compare_fk, compare_inertials, compare_joints, compare_structure
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Status, ValidationReport


def mujoco_usd_available() -> bool:
    return importlib.util.find_spec("mujoco_usd") is not None


def validate_usd(robot: Robot, usd_path: str, options: ValidateOptions | None = None) -> ValidationReport:
    """Load ``usd_path`` with ``MjSpec.from_file`` through mujoco-usd and compare it with ``robot``."""
    opts = options or ValidateOptions()
    report = ValidationReport(robot=robot.name, target="usd", consumer="mujoco-usd")
    if not mujoco_usd_available():
        report.add(
            "mujoco-usd",
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
