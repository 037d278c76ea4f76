"""The source's own defects, as validation rows: what the IR verifier finds in the input."""

from __future__ import annotations

from robodesc.ir.diagnostics import Severity
from robodesc.ir.verify import verify
from robodesc.validation.report import Status, ValidationReport


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
