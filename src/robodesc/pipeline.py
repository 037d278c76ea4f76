"""The whole compile: frontend → verifier → passes → verifier → emitter → validation.

Only this module and the API above it know every stage; each stage only knows the IR.
"""

from __future__ import annotations

import copy
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Protocol

from robodesc.emit.files import write_atomic
from robodesc.emit.urdf import UrdfOptions, emit_urdf
from robodesc.frontends.load import load_path, load_string
from robodesc.ir.diagnostics import (
    ConfigError,
    Finding,
    Findings,
    Severity,
    UnsupportedError,
    VerificationError,
)
from robodesc.ir.model import Robot
from robodesc.ir.verify import PHYSICAL_CODES, verify
from robodesc.options import CompileOptions, InvalidInertia

Progress = Callable[[str], None]


class Buildable(Protocol):
    def build(self) -> Robot: ...


Source = str | os.PathLike[str] | Robot | Buildable


@dataclass(slots=True)
class Emitted:
    """What an emitter produced: the main text (when it is text) and every file written."""

    text: str | None = None
    files: dict[str, str] = field(default_factory=dict)  # role -> path


@dataclass(slots=True)
class CompileResult:
    robot: Robot
    findings: list[Finding]
    target: str
    text: str | None = None
    files: dict[str, str] = field(default_factory=dict)
    validation: Any = None  # a robodesc.validation report when validation ran

    @property
    def warnings(self) -> list[Finding]:
        return [f for f in self.findings if f.severity is Severity.WARNING]


def _quiet(_: str) -> None:
    pass


def load_source(source: Source, options: CompileOptions, findings: Findings) -> Robot:
    """Any accepted source → a fresh IR the caller may mutate."""
    if isinstance(source, Robot):
        return copy.deepcopy(source)
    build = getattr(source, "build", None)
    if callable(build):
        robot = build()
        if not isinstance(robot, Robot):
            raise ConfigError(f"{type(source).__name__}.build() returned {type(robot).__name__}, not a Robot")
        return robot
    text = os.fspath(source)  # type: ignore[arg-type]
    if text.lstrip().startswith("<"):
        loaded = load_string(text, options.load_options())
    else:
        loaded = load_path(text, options.load_options())
    findings.extend(loaded.findings)
    return loaded.robot


def verify_source(robot: Robot, options: CompileOptions, findings: Findings) -> bool:
    """Verify what the frontend built. Returns True when inertia repair was requested for defects."""
    result = verify(robot)
    structural = [f for f in result.errors if f.code not in PHYSICAL_CODES]
    physical = [f for f in result.errors if f.code in PHYSICAL_CODES]
    findings.extend([f for f in result.items if f.severity is not Severity.ERROR])
    if structural:
        raise VerificationError(structural)
    if not physical:
        return False
    if options.invalid_inertia is InvalidInertia.ERROR:
        raise VerificationError(physical)
    if options.invalid_inertia is InvalidInertia.WARN:
        for f in physical:
            findings.add(
                Severity.WARNING,
                f.code,
                f.message + " (passed through: --invalid-inertia warn)",
                element=f.element,
                loc=f.loc,
                stage=f.stage,
            )
        return False
    return True


def run_passes(robot: Robot, options: CompileOptions, findings: Findings, repair: bool) -> Robot:
    if options.preset is None and not options.passes and not repair:
        return robot
    try:
        from robodesc.passes import pipeline as passes
    except ImportError:
        raise UnsupportedError("passes are not available in this build") from None
    pass_options = passes.PassOptions.from_mapping(options.passes)  # type: ignore[attr-defined]
    if repair:
        pass_options.repair_inertia = True
    findings.extend(passes.run_passes(robot, preset=options.preset, options=pass_options))
    return robot


# ---- targets ---------------------------------------------------------------------------------
def _emit_urdf(robot: Robot, out: str | None, options: CompileOptions, findings: Findings) -> Emitted:
    out_dir = os.path.dirname(os.path.abspath(out)) if out else None
    text = emit_urdf(robot, UrdfOptions(path_mode=options.mesh_paths, out_dir=out_dir))
    emitted = Emitted(text=text)
    if out:
        write_atomic(out, text)
        emitted.files["urdf"] = out
    return emitted


Target = Callable[[Robot, str | None, CompileOptions, Findings], Emitted]
TARGETS: dict[str, Target] = {"urdf": _emit_urdf}


def compile_robot(
    source: Source,
    target: str,
    out: str | None,
    options: CompileOptions,
    progress: Progress = _quiet,
) -> CompileResult:
    if target not in TARGETS:
        raise ConfigError(f"unknown target {target!r} (one of {', '.join(sorted(TARGETS))})")
    findings = Findings()
    progress("loading")
    robot = load_source(source, options, findings)
    progress("verifying")
    repair = verify_source(robot, options, findings)
    if options.preset or options.passes or repair:
        progress("running passes")
    robot = run_passes(robot, options, findings, repair)
    errors = verify(robot).errors
    if options.invalid_inertia is InvalidInertia.WARN:
        errors = [f for f in errors if f.code not in PHYSICAL_CODES]
    if errors:
        raise VerificationError(errors)
    progress(f"writing {target}")
    emitted = TARGETS[target](robot, out, options, findings)
    return CompileResult(robot=robot, findings=list(findings), target=target, text=emitted.text, files=emitted.files)
