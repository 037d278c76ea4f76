"""What a validation found: one :class:`ValidationReport` of :class:`Check` rows.

A check is either a per-kind summary (``mass`` over 20 links, passing, with the largest error seen)
or one failing/warning element (``mass`` of ``link 'thigh'``). Summaries keep reports short on big
robots; failures always name the element so a user knows what to fix.
Three renderings: :meth:`ValidationReport.to_text` (terminal), :meth:`~ValidationReport.to_json`
(CI) and :meth:`~ValidationReport.to_markdown` (``--report report.md``).
"""

from __future__ import annotations

import enum
import json
from dataclasses import dataclass, field


class Status(enum.Enum):
    PASS = "pass"
    FAIL = "fail"
    # Legal but worth a look (a consumer quirk, interpenetrating collision geometry); does not fail.
    WARN = "warn"
    SKIP = "skip"


@dataclass(slots=True)
class Check:
    """One row. ``error``/``tolerance`` are the largest error measured and the bound it was held to."""

    name: str
    status: Status
    element: str = ""
    message: str = ""
    error: float | None = None
    tolerance: float | None = None

    def as_dict(self) -> dict[str, object]:
        return {
            "name": self.name,
            "status": self.status.value,
            "element": self.element,
            "message": self.message,
            "error": self.error,
            "tolerance": self.tolerance,
        }


_ORDER = {Status.FAIL: 0, Status.WARN: 1, Status.SKIP: 2, Status.PASS: 3}


@dataclass(slots=True)
class ValidationReport:
    """Checks made by one consumer (``mujoco``, ``drake``, ``mujoco-usd``) on one emitted target."""

    robot: str
    target: str  # "urdf", "sdf", "usd"
    consumer: str
    checks: list[Check] = field(default_factory=list)
    # Largest error per quantity (``fk_position`` m, ``fk_rotation`` rad, ``mass`` and ``inertia`` relative ...).
    max_errors: dict[str, float] = field(default_factory=dict)
    info: dict[str, str] = field(default_factory=dict)

    # ---- building ------------------------------------------------------------------------
    def add(
        self,
        name: str,
        status: Status,
        element: str = "",
        message: str = "",
        *,
        error: float | None = None,
        tolerance: float | None = None,
    ) -> Check:
        check = Check(name, status, element, message, error, tolerance)
        self.checks.append(check)
        return check

    def note_error(self, quantity: str, value: float) -> None:
        if value > self.max_errors.get(quantity, -1.0):
            self.max_errors[quantity] = value

    def extend(self, other: ValidationReport) -> None:
        self.checks.extend(other.checks)
        for key, value in other.max_errors.items():
            self.note_error(key, value)
        self.info.update(other.info)

    def rename(self, staged: str, final: str) -> None:
        """Say ``final`` wherever a check names ``staged``: checks run on a staged copy
        (``.robodesc-…``), and the user should read the name they typed."""
        if not staged or staged == final:
            return
        for check in self.checks:
            check.element = check.element.replace(staged, final)
            check.message = check.message.replace(staged, final)
        self.info = {key: value.replace(staged, final) for key, value in self.info.items()}

    # ---- reading -------------------------------------------------------------------------
    @property
    def ok(self) -> bool:
        """False when any check failed (the CLI then exits non-zero)."""
        return not self.failures

    @property
    def failures(self) -> list[Check]:
        return [c for c in self.checks if c.status is Status.FAIL]

    @property
    def warnings(self) -> list[Check]:
        return [c for c in self.checks if c.status is Status.WARN]

    def by_name(self, name: str) -> list[Check]:
        return [c for c in self.checks if c.name == name]

    def counts(self) -> dict[str, int]:
        out = {s.value: 0 for s in Status}
        for c in self.checks:
            out[c.status.value] += 1
        return out

    def sorted_checks(self) -> list[Check]:
        """Failures first, then warnings, skips and passes; stable within each group."""
        return sorted(self.checks, key=lambda c: _ORDER[c.status])

    def summary(self) -> str:
        c = self.counts()
        verdict = "OK" if self.ok else "FAILED"
        return (
            f"{self.target} of {self.robot!r} checked with {self.consumer}: {verdict} "
            f"({c['pass']} passed, {c['fail']} failed, {c['warn']} warnings, {c['skip']} skipped)"
        )

    # ---- rendering -----------------------------------------------------------------------
    def to_dict(self) -> dict[str, object]:
        return {
            "robot": self.robot,
            "target": self.target,
            "consumer": self.consumer,
            "ok": self.ok,
            "counts": self.counts(),
            "max_errors": dict(sorted(self.max_errors.items())),
            "info": dict(sorted(self.info.items())),
            "checks": [c.as_dict() for c in self.sorted_checks()],
        }

    def to_json(self, indent: int | None = 2) -> str:
        return json.dumps(self.to_dict(), indent=indent, sort_keys=False) + "\n"

    def to_text(self, *, max_width: int = 120) -> str:
        """A boxed table for the terminal (plain characters only; no colour codes)."""
        headers = ("status", "check", "element", "error", "message")
        rows = [
            (
                c.status.value.upper(),
                c.name,
                c.element,
                _err_text(c.error, c.tolerance),
                c.message,
            )
            for c in self.sorted_checks()
        ]
        fixed = [max([len(headers[i])] + [len(r[i]) for r in rows]) for i in range(4)]
        fixed[2] = min(fixed[2], 32)
        msg_width = max(20, max_width - sum(fixed) - 16)
        widths = [*fixed, msg_width]

        def line(left: str, mid: str, right: str) -> str:
            return left + mid.join("─" * (w + 2) for w in widths) + right

        def row(cells: tuple[str, ...]) -> list[str]:
            wrapped = [_wrap(cell, w) for cell, w in zip(cells, widths, strict=True)]
            height = max(len(w) for w in wrapped)
            out = []
            for k in range(height):
                parts = [(w[k] if k < len(w) else "").ljust(width) for w, width in zip(wrapped, widths, strict=True)]
                out.append("│ " + " │ ".join(parts) + " │")
            return out

        lines = [self.summary(), line("┌", "┬", "┐"), *row(headers), line("├", "┼", "┤")]
        for r in rows:
            lines.extend(row(r))
        lines.append(line("└", "┴", "┘"))
        if self.max_errors:
            lines.append("largest errors: " + ", ".join(f"{k} {v:.3g}" for k, v in sorted(self.max_errors.items())))
        return "\n".join(lines) + "\n"

    def to_markdown(self) -> str:
        out = [f"# Validation of {self.robot} ({self.target}, {self.consumer})", "", f"**{self.summary()}**", ""]
        if self.info:
            out += ["| | |", "|---|---|"]
            out += [f"| {_md(k)} | {_md(v)} |" for k, v in sorted(self.info.items())]
            out.append("")
        if self.max_errors:
            out += ["| quantity | largest error |", "|---|---|"]
            out += [f"| {_md(k)} | {v:.3g} |" for k, v in sorted(self.max_errors.items())]
            out.append("")
        out += ["| status | check | element | error | message |", "|---|---|---|---|---|"]
        for c in self.sorted_checks():
            out.append(
                f"| {c.status.value} | {_md(c.name)} | {_md(c.element)} | {_err_text(c.error, c.tolerance)} | {_md(c.message)} |"
            )
        return "\n".join(out) + "\n"


class Tally:
    """Collects one quantity: failing elements become rows, the rest one summary row."""

    def __init__(self, report: ValidationReport, name: str, tolerance: float | None, unit: str) -> None:
        self.report, self.name, self.tolerance, self.unit = report, name, tolerance, unit
        self.checked = 0
        self.failed = 0
        self.max_error = 0.0
        self.skipped: list[str] = []

    def measure(self, element: str, error: float, message: str) -> None:
        self.checked += 1
        self.max_error = max(self.max_error, error)
        if self.tolerance is not None and not error <= self.tolerance:  # NaN fails too
            self.failed += 1
            self.report.add(self.name, Status.FAIL, element, message, error=error, tolerance=self.tolerance)

    def fail(self, element: str, message: str) -> None:
        self.checked += 1
        self.failed += 1
        self.report.add(self.name, Status.FAIL, element, message)

    def ok(self) -> None:
        self.checked += 1

    def skip(self, element: str, why: str) -> None:
        self.skipped.append(f"{element} ({why})")

    def finish(self, what: str, quantity: str | None = None) -> None:
        if quantity is not None and self.checked:
            self.report.note_error(quantity, self.max_error)
        if self.skipped:
            shown = "; ".join(self.skipped[:5]) + (
                f"; and {len(self.skipped) - 5} more" if len(self.skipped) > 5 else ""
            )
            self.report.add(self.name, Status.SKIP, f"{len(self.skipped)} {what}", f"not compared: {shown}")
        if self.checked and not self.failed:
            err = self.max_error if self.tolerance is not None else None
            unit = f" {self.unit}" if self.unit else ""
            largest = f"largest error {self.max_error:.3g}{unit}" if err is not None else ""
            self.report.add(
                self.name,
                Status.PASS,
                f"{self.checked} {what}",
                f"all match ({largest})" if largest else "all match",
                error=err,
                tolerance=self.tolerance,
            )


def _err_text(error: float | None, tolerance: float | None) -> str:
    if error is None:
        return ""
    if tolerance is None:
        return f"{error:.3g}"
    return f"{error:.3g} / {tolerance:.0e}"


def _md(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _wrap(text: str, width: int) -> list[str]:
    if len(text) <= width:
        return [text]
    out: list[str] = []
    cur = ""
    for word in text.split(" "):
        while len(word) > width:
            if cur:
                out.append(cur)
                cur = ""
            out.append(word[:width])
            word = word[width:]
        if not cur:
            cur = word
        elif len(cur) + 1 + len(word) <= width:
            cur += " " + word
        else:
            out.append(cur)
            cur = word
    if cur:
        out.append(cur)
    return out or [""]
