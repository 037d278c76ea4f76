"""What the command line prints: findings grouped by kind, errors, the summary line, the one JSON
document, and the progress spinner. No command logic: the commands hand results here."""

from __future__ import annotations

import json
import os
import sys
import threading
from collections import defaultdict
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from robodesc.ir.diagnostics import Finding, RobodescError, Severity, SourceLoc, VerificationError

if TYPE_CHECKING:
    from robodesc.pipeline import CompileResult


def display_path(path: str | None) -> str:
    """A path as the user should read it: relative to the working directory when that is shorter."""
    if not path:
        return path or ""
    suffix = ""
    if path.endswith(" (expanded)"):
        path, suffix = path.removesuffix(" (expanded)"), " (expanded)"
    if os.path.isabs(path):
        rel = os.path.relpath(path)
        if len(rel) < len(path):
            path = rel
    return path + suffix


def render_finding(f: Finding, severity: Severity | None = None) -> str:
    loc = f.loc
    if loc is not None and loc.file:
        loc = SourceLoc(display_path(loc.file), loc.line, loc.column)
    where = f"{loc}: " if loc is not None else ""
    what = f"{f.element}: " if f.element else ""
    return f"{(severity or f.severity).value}: {where}{what}{f.message}"


def finding_dict(f: Finding) -> dict[str, object]:
    from robodesc.advice import advice_for

    out = f.as_dict()
    if out.get("file"):
        out["file"] = display_path(str(out["file"]))
    advice = advice_for(f.code)
    if advice is not None and f.severity is not Severity.INFO:
        out["consumers"] = advice.consumers
        out["repair"] = advice.repair
    return out


# Informational findings printed without -v: what the user's choice did, in one line.
SHOWN_NOTES = frozenset({"preset-applied"})


def print_findings(findings: Sequence[Finding], quiet: bool, verbose: bool = False) -> None:
    """Warnings grouped by kind: a count, one example, what consumers do and what repairs it.
    ``verbose`` lists every finding, informational ones too; ``quiet`` prints none."""
    if quiet:
        return
    if verbose:
        for f in findings:
            print(render_finding(f), file=sys.stderr)
        return
    from robodesc.advice import advice_for

    groups: dict[str, list[Finding]] = defaultdict(list)
    for f in findings:
        if f.severity is Severity.WARNING:
            groups[f.code].append(f)
        elif f.code in SHOWN_NOTES:
            print(f"note: {f.message}", file=sys.stderr)
    for code, items in groups.items():
        more = f" (and {len(items) - 1} more {code}; -v lists them)" if len(items) > 1 else ""
        print(render_finding(items[0]) + more, file=sys.stderr)
        advice = advice_for(code)
        if advice is not None and not advice.in_message:
            repair = f" Repair: {advice.repair}." if advice.repair else ""
            print(f"  -> {advice.consumers}.{repair}", file=sys.stderr)


def report_error(err: RobodescError) -> int:
    if isinstance(err, VerificationError):
        for f in err.findings:
            print(render_finding(f, Severity.ERROR), file=sys.stderr)
        codes = {f.code for f in err.findings}
        if codes & {"bad-mass", "bad-inertia"}:
            print(
                "hint: --invalid-inertia repair fixes these from geometry; --invalid-inertia warn passes them through",
                file=sys.stderr,
            )
        if err.__class__.__name__ == "StrictError":
            print("hint: --strict turned these warnings into errors; without it the output is written", file=sys.stderr)
    else:
        loc = err.loc
        if loc is not None and loc.file:
            loc = SourceLoc(display_path(loc.file), loc.line, loc.column)
        where = f"{loc}: " if loc is not None else ""
        what = f"{err.element}: " if err.element else ""
        print(f"error: {where}{what}{err.message}", file=sys.stderr)
    return err.exit_code


def error_dicts(err: BaseException) -> list[dict[str, object]]:
    if isinstance(err, VerificationError):
        return [{**finding_dict(f), "severity": "error"} for f in err.findings]
    if isinstance(err, RobodescError):
        loc = err.loc
        return [
            {
                "severity": "error",
                "code": type(err).__name__,
                "message": err.message,
                "element": err.element,
                "file": display_path(loc.file) if loc and loc.file else None,
                "line": loc.line if loc else None,
                "column": loc.column if loc else None,
            }
        ]
    return [{"severity": "error", "code": type(err).__name__, "message": str(err)}]


def summary_line(result: CompileResult, target: str, out: str | None) -> str:
    robot = result.robot
    where = display_path(out) if out else "standard output"
    if result.world is not None:
        return f"robodesc: {target} {where}: the world {result.world!r} alone (no robot); {verdict(result)}"
    mass = robot.total_mass()
    head = (
        f"robodesc: {target} {where}: {len(robot.links)} links, {len(robot.joints)} joints, "
        f"{robot.dof} DOF, {mass:.4g} kg"
    )
    base = f"; {result.base.summary()}" if result.base is not None else ""
    return f"{head}{base}; {verdict(result)}"


# The numbers validation compares with the source, and their units (simulation metrics such as
# penetration are not errors against the source and are left to the full table).
_COMPARED = {
    "fk_position": " m",
    "fk_rotation": " rad",
    "com": " m",
    "mass": " (relative)",
    "inertia": " (relative)",
    "axis": "",
    "limit": "",
}


def verdict(result: CompileResult) -> str:
    report = result.validation
    if report is None:
        return "not validated (--no-validate)"
    consumer = getattr(report, "consumer", "")
    unloaded = next((c for c in report.checks if c.message.startswith("not loaded: ")), None)
    if unloaded is not None:  # the consumer cannot take this model at all (MuJoCo's depth limit)
        return f"not validated by {consumer}: {unloaded.message.removeprefix('not loaded: ').split(';')[0]}"
    # A quantity a source defect is failing (a 1e12 relative mass error of an invalid source mass)
    # says nothing of what robodesc wrote: it is listed as a warning, not as the "largest error".
    carried = {c.name for c in result.source_failures}
    largest = sorted(
        (
            (v, k)
            for k, v in report.max_errors.items()
            if v is not None and k in _COMPARED and not any(k.startswith(c) or c.startswith(k) for c in carried)
        ),
        reverse=True,
    )[:2]
    errors = ", ".join(f"{k} {v:.2g}{_COMPARED[k]}" for v, k in largest)
    state = "passed" if report.ok else "FAILED"
    extra = []
    if result.source_failures:
        extra.append(f"{len(result.source_failures)} source defect(s) the consumer refused, listed as warnings")
    if errors:
        extra.append(f"largest errors: {errors}")
    return f"validation by {consumer} {state}" + (f" ({'; '.join(extra)})" if extra else "")


class Progress:
    """A spinner on standard error for steps that take more than about two seconds (a large xacro,
    many meshes, validation); nothing at all when standard error is not a terminal."""

    DELAY = 2.0

    def __init__(self, enabled: bool) -> None:
        self.console: Any = None
        if enabled:
            from rich.console import Console

            console = Console(stderr=True)
            if console.is_terminal:
                self.console = console
        self.step = ""
        self.status: Any = None
        self.timer: threading.Timer | None = None
        self.lock = threading.Lock()

    def __call__(self, step: str) -> None:
        if self.console is None:
            return
        with self.lock:
            self.step = step
            if self.status is not None:
                self.status.update(f"robodesc: {step}")
            elif self.timer is None:
                self.timer = threading.Timer(self.DELAY, self._show)
                self.timer.daemon = True
                self.timer.start()

    def _show(self) -> None:
        with self.lock:
            if self.console is None or self.timer is None:
                return
            self.status = self.console.status(f"robodesc: {self.step}")
            self.status.start()

    def stop(self) -> None:
        with self.lock:
            if self.timer is not None:
                self.timer.cancel()
                self.timer = None
            if self.status is not None:
                self.status.stop()
                self.status = None


def json_doc(
    command: str,
    exit_code: int,
    *,
    target: str | None = None,
    output: str | None = None,
    result: Any = None,
    errors: list[dict[str, object]] | None = None,
    report: Any = None,
) -> dict[str, Any]:
    """The one JSON document every exit path prints with --json."""
    doc: dict[str, Any] = {
        "command": command,
        "ok": exit_code == 0,
        "exit_code": exit_code,
        "target": target,
        "output": display_path(output) if output else None,
        "files": {},
        "summary": None,
        "findings": [],
        "errors": errors or [],
        "validation": None,
    }
    if result is not None:
        robot = result.robot
        doc["files"] = {role: display_path(p) for role, p in result.files.items()}
        doc["summary"] = {
            "robot": robot.name,
            "links": len(robot.links),
            "joints": len(robot.joints),
            "dof": robot.dof,
            "mass": robot.total_mass(),
            "base": None if result.base is None else {"fixed": result.base.fixed, "reason": result.base.reason},
            "validation": verdict(result),
        }
        doc["findings"] = [finding_dict(f) for f in result.findings]
        report = report if report is not None else result.validation
    if report is not None:
        doc["validation"] = json.loads(report.to_json())
    return doc


def clip_dict(clip: Any) -> dict[str, Any]:
    """A clip of ``--video`` (robodesc.view.video.Clip) for ``--json``."""
    return {
        "path": clip.path,
        "scenario": clip.scenario,
        "format": clip.format,
        "frames": clip.frames,
        "width": clip.width,
        "height": clip.height,
        "panels": clip.panels,
        "seconds": round(clip.seconds, 3),
    }


def print_clips(clips: list[Any], folder: str | None = None, simulated: bool = True) -> None:
    """One line per clip on standard error, naming the format and what wrote it; with ``folder``,
    a line saying why there is none (``simulated``: whether the dynamics ran at all)."""
    if folder is not None and not clips:
        why = "no engine ran a scenario the robot moves in" if simulated else "nothing was simulated (see above)"
        print(f"robodesc: --video {display_path(folder)}: no clip: {why}", file=sys.stderr)
    for clip in clips:
        how = (
            "MP4 (imageio-ffmpeg)" if clip.format == "mp4" else "GIF (Pillow; MP4 needs pip install 'robodesc[video]')"
        )
        for why in clip.skipped:
            print(f"warning: not drawn: {why}", file=sys.stderr)
        print(
            f"robodesc: {display_path(clip.path)}: {clip.scenario}, {len(clip.panels)} panel(s) "
            f"({', '.join(clip.panels)}), {clip.frames} frames {clip.width}x{clip.height}, {how} in {clip.seconds:.2f} s",
            file=sys.stderr,
        )
