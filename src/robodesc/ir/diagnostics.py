"""Where things came from, what went wrong, and what a stage changed.

Every IR node carries a :class:`SourceLoc`; every message robodesc prints is a
:class:`Finding` or a :class:`RobodescError`, both rendered the same way:
``file:line: joint 'knee': what is wrong``.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field


@dataclass(slots=True, frozen=True)
class SourceLoc:
    """A place in an input file. ``line`` and ``column`` are 1-based; ``None`` when unknown."""

    file: str | None = None
    line: int | None = None
    column: int | None = None

    def __str__(self) -> str:
        parts = [self.file or "<input>"]
        if self.line is not None:
            parts.append(str(self.line))
            if self.column is not None:
                parts.append(str(self.column))
        return ":".join(parts)


class Severity(enum.Enum):
    INFO = "info"
    WARNING = "warning"
    ERROR = "error"


@dataclass(slots=True, frozen=True)
class Finding:
    """One observation by a frontend, pass, verifier or emitter.

    ``element`` names the IR element (``joint 'knee'``); ``stage`` names who made the finding
    (``verify``, ``pass:sanitize_names`` ...); ``code`` is a short stable identifier for tools.
    """

    severity: Severity
    code: str
    message: str
    element: str = ""
    loc: SourceLoc | None = None
    stage: str = ""

    def render(self) -> str:
        where = f"{self.loc}: " if self.loc is not None else ""
        what = f"{self.element}: " if self.element else ""
        return f"{self.severity.value}: {where}{what}{self.message}"

    def as_dict(self) -> dict[str, object]:
        loc = self.loc
        return {
            "severity": self.severity.value,
            "code": self.code,
            "message": self.message,
            "element": self.element,
            "file": loc.file if loc else None,
            "line": loc.line if loc else None,
            "column": loc.column if loc else None,
            "stage": self.stage,
        }


@dataclass(slots=True)
class Findings:
    """An append-only list of findings with a few conveniences."""

    items: list[Finding] = field(default_factory=list)

    def add(
        self,
        severity: Severity,
        code: str,
        message: str,
        *,
        element: str = "",
        loc: SourceLoc | None = None,
        stage: str = "",
    ) -> Finding:
        finding = Finding(severity, code, message, element, loc, stage)
        self.items.append(finding)
        return finding

    def info(self, code: str, message: str, **kw: object) -> Finding:
        return self.add(Severity.INFO, code, message, **kw)  # type: ignore[arg-type]

    def warn(self, code: str, message: str, **kw: object) -> Finding:
        return self.add(Severity.WARNING, code, message, **kw)  # type: ignore[arg-type]

    def error(self, code: str, message: str, **kw: object) -> Finding:
        return self.add(Severity.ERROR, code, message, **kw)  # type: ignore[arg-type]

    def extend(self, other: Findings | list[Finding]) -> None:
        self.items.extend(other.items if isinstance(other, Findings) else other)

    @property
    def errors(self) -> list[Finding]:
        return [f for f in self.items if f.severity is Severity.ERROR]

    def __iter__(self):  # type: ignore[no-untyped-def]
        return iter(self.items)

    def __len__(self) -> int:
        return len(self.items)


class RobodescError(Exception):
    """Base of every error robodesc raises on purpose. The CLI prints ``str(err)`` and exits 2."""

    exit_code = 2

    def __init__(self, message: str, *, element: str = "", loc: SourceLoc | None = None) -> None:
        self.message = message
        self.element = element
        self.loc = loc
        super().__init__(self.render())

    def render(self) -> str:
        where = f"{self.loc}: " if self.loc is not None else ""
        what = f"{self.element}: " if self.element else ""
        return f"{where}{what}{self.message}"


class ParseError(RobodescError):
    """The input could not be read: malformed XML, a hostile construct, a bad value."""


class BrokenReferenceError(RobodescError):
    """A name or a file that the input refers to does not exist or may not be reached."""


class PathEscapeError(BrokenReferenceError):
    """A package-relative path climbs out of its package root. Always refused, whatever the policy."""


class UnsupportedError(RobodescError):
    """The input asks for something the chosen target cannot express."""


class ConfigError(RobodescError):
    """An option or a configuration key is unknown or has a bad value."""


class VerificationError(RobodescError):
    """The IR breaks an invariant. Carries every error finding, not just the first."""

    def __init__(self, findings: list[Finding]) -> None:
        self.findings = findings
        first = findings[0] if findings else None
        more = f" (and {len(findings) - 1} more)" if len(findings) > 1 else ""
        super().__init__(
            (first.message if first else "verification failed") + more,
            element=first.element if first else "",
            loc=first.loc if first else None,
        )

    def render_all(self) -> list[str]:
        return [f.render().removeprefix("error: ") for f in self.findings]


class ValidationFailed(RobodescError):
    """A consumer loaded the output and it did not match the IR."""

    exit_code = 1
