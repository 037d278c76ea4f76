"""``robodesc validate FILE``: read a robot, emit URDF and check it with MuJoCo.

This module knows the frontend and the URDF emitter (validating a file needs both); the checks
themselves (:mod:`robodesc.validation.mujoco_urdf`) only read the IR and emitted text.
"""

from __future__ import annotations

import os

from robodesc.emit.paths import PathMode
from robodesc.emit.urdf import UrdfOptions, emit_urdf
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Severity
from robodesc.ir.verify import verify
from robodesc.validation.mujoco_urdf import validate_urdf_text
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Status, ValidationReport


def validate_file(
    path: str, options: ValidateOptions | None = None, load_options: LoadOptions | None = None
) -> ValidationReport:
    """Load ``path`` (URDF/xacro), emit URDF with absolute mesh paths and validate it in MuJoCo.

    Source defects the IR verifier finds (non-physical inertia, dangling references) are added as
    ``source`` checks: warnings, since they are the input's and a faithful compiler keeps them.
    Raises :class:`~robodesc.ir.diagnostics.RobodescError` only when the file cannot be read at all.
    """
    opts = options or ValidateOptions()
    lopts = load_options or LoadOptions()
    if not opts.package_paths and lopts.package_paths:
        opts.package_paths = dict(lopts.package_paths)
    loaded = load_path(path, lopts)
    robot = loaded.robot
    text = emit_urdf(robot, UrdfOptions(path_mode=PathMode.ABSOLUTE, out_dir=os.path.dirname(os.path.abspath(path))))
    report = ValidationReport(robot=robot.name, target="urdf", consumer="mujoco")
    add_source_findings(robot, report)
    report.extend(validate_urdf_text(robot, text, os.path.dirname(os.path.abspath(path)), opts))
    report.info["input"] = path
    return report


def add_source_findings(robot: object, report: ValidationReport) -> None:
    """The IR verifier's findings about the input, as ``source`` checks."""
    from robodesc.ir.model import Robot

    assert isinstance(robot, Robot)
    findings = verify(robot)
    errors = [f for f in findings if f.severity is Severity.ERROR]
    for f in errors:
        where = f" ({f.loc})" if f.loc is not None else ""
        report.add("source", Status.WARN, f.element, f"source defect [{f.code}]: {f.message}{where}")
    if not errors:
        report.add("source", Status.PASS, "robot", "the IR verifier finds no defect in the source")
