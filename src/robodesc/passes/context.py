"""The one object threaded through every pass: the options and the findings list."""

from __future__ import annotations

from dataclasses import dataclass, field

from robodesc.ir.diagnostics import Finding, Findings, Severity, SourceLoc
from robodesc.passes.options import PassOptions


@dataclass(slots=True)
class PassContext:
    options: PassOptions = field(default_factory=PassOptions)
    findings: Findings = field(default_factory=Findings)
    # Set by the pipeline before each pass; findings are stamped ``pass:<stage>``.
    stage: str = ""

    def _add(
        self, severity: Severity, code: str, message: str, element: str, loc: SourceLoc | None, stage: str | None
    ) -> Finding:
        return self.findings.add(severity, code, message, element=element, loc=loc, stage=f"pass:{stage or self.stage}")

    def info(
        self, code: str, message: str, *, element: str = "", loc: SourceLoc | None = None, stage: str | None = None
    ) -> Finding:
        return self._add(Severity.INFO, code, message, element, loc, stage)

    def warn(
        self, code: str, message: str, *, element: str = "", loc: SourceLoc | None = None, stage: str | None = None
    ) -> Finding:
        return self._add(Severity.WARNING, code, message, element, loc, stage)
