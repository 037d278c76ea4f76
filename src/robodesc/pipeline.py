"""The whole compile: frontend → verifier → passes → verifier → emitter → validation.

Only this module and the API above it know every stage; each stage only knows the IR.
"""

from __future__ import annotations

import copy
import dataclasses
import importlib
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Protocol

from robodesc.emit.common.target import EmitRequest, Emitted, Target
from robodesc.frontends.load import load_path, load_string
from robodesc.ir.diagnostics import (
    ConfigError,
    Finding,
    Findings,
    Severity,
    VerificationError,
)
from robodesc.ir.model import Robot
from robodesc.ir.verify import PHYSICAL_CODES, verify
from robodesc.options import CompileOptions, InvalidInertia, dataclass_from_mapping
from robodesc.passes import pipeline as passes_pipeline
from robodesc.passes.context import PassContext
from robodesc.passes.copy_meshes import copy_meshes
from robodesc.passes.options import PassOptions, RepairPolicy, options_from_mapping
from robodesc.passes.pipeline import resolve_options

Progress = Callable[[str], None]


class Buildable(Protocol):
    def build(self) -> Robot: ...


Source = str | os.PathLike[str] | Robot | Buildable


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


def pass_options(options: CompileOptions, spec: Target) -> PassOptions:
    """The passes' options: the preset, overridden by explicit options, with the policies the
    compile options and the target imply."""
    chosen = options_from_mapping(options.passes)
    resolved = resolve_options(options.preset or spec.preset, chosen)
    for name, value in spec.passes.items():
        setattr(resolved, name, value)
    # Compositions give masses without tensors; those are always filled from geometry.
    resolved.fill_inertia = True
    if options.invalid_inertia is InvalidInertia.REPAIR and resolved.repair_inertia is None:
        resolved.repair_inertia = RepairPolicy.GEOMETRY
    return resolved


def verify_source(robot: Robot, options: CompileOptions, findings: Findings, repairing: bool = False) -> None:
    """Verify what the frontend built. Structural errors are fatal; physically invalid inertia is
    fatal unless the passes will repair it or the user asked to pass it through."""
    result = verify(robot)
    structural = [f for f in result.errors if f.code not in PHYSICAL_CODES]
    physical = [f for f in result.errors if f.code in PHYSICAL_CODES]
    findings.extend([f for f in result.items if f.severity is not Severity.ERROR])
    if structural:
        raise VerificationError(structural)
    if not physical or repairing:
        return
    if options.invalid_inertia is InvalidInertia.ERROR:
        raise VerificationError(physical)
    for f in physical:
        findings.add(
            Severity.WARNING,
            f.code,
            f.message + " (passed through: --invalid-inertia warn)",
            element=f.element,
            loc=f.loc,
            stage=f.stage,
        )


# ---- targets ---------------------------------------------------------------------------------
# The target table: a name and the package that exports its ``TARGET``. Packages are imported when a
# compile asks for them, so a USD compile does not load the URDF writer. Adding a target is adding
# a package under robodesc/emit/ and a line here.
TARGETS: dict[str, str] = {
    "urdf": "robodesc.emit.urdf",
    "sdf": "robodesc.emit.sdf",
    "usd": "robodesc.emit.usd",
    "ros2": "robodesc.emit.ros2",
    "isaac": "robodesc.emit.isaac",
}


def target_spec(name: str) -> Target:
    if name not in TARGETS:
        raise ConfigError(f"unknown target {name!r} (one of {', '.join(sorted(TARGETS))})")
    spec = importlib.import_module(TARGETS[name]).TARGET
    assert isinstance(spec, Target)
    return spec


def target_options_class(target: str) -> type[Any] | None:
    """The options dataclass a target takes."""
    return target_spec(target).options


def target_options(cls: type[Any], options: CompileOptions) -> dict[str, Any]:
    """The target options that belong to the options class ``cls``."""
    names = {f.name for f in dataclasses.fields(cls)}
    return {k: v for k, v in options.target_options.items() if k in names}


def _request(spec: Target, out: str | None, options: CompileOptions) -> EmitRequest:
    built = None
    if spec.options is not None:
        built = dataclass_from_mapping(spec.options, target_options(spec.options, options), spec.name)
    return EmitRequest(out=out, options=built, mesh_paths=options.mesh_paths, given=frozenset(options.target_options))


def compile_robot(
    source: Source,
    target: str,
    out: str | None,
    options: CompileOptions,
    progress: Progress = _quiet,
) -> CompileResult:
    spec = target_spec(target)
    findings = Findings()
    resolved = pass_options(options, spec)
    progress("loading")
    robot = load_source(source, options, findings)
    progress("verifying")
    verify_source(robot, options, findings, repairing=resolved.repair_inertia is not None)
    progress("running passes: " + ", ".join(passes_pipeline.enabled_passes(resolved)))
    findings.extend(passes_pipeline.run_passes(robot, options=resolved))
    after = verify(robot)
    errors = after.errors
    if options.invalid_inertia is InvalidInertia.WARN:
        errors = [f for f in errors if f.code not in PHYSICAL_CODES]
    if errors:
        raise VerificationError(errors)
    if resolved.copy_meshes:
        if not out:
            raise ConfigError("--copy-meshes needs an output file (-o)")
        out_dir = out if spec.folder else os.path.dirname(os.path.abspath(out))
        progress(f"copying meshes to {os.path.join(out_dir, 'meshes')}")
        ctx = PassContext(resolved)
        copy_meshes(robot, out_dir, ctx)
        findings.extend(ctx.findings)
    progress(f"writing {target}")
    emitted = spec.emit(robot, _request(spec, out, options), findings)
    result = CompileResult(
        robot=robot, findings=_unique(findings), target=target, text=emitted.text, files=emitted.files
    )
    if options.validate:
        progress("validating")
        result.validation = validate_emitted(robot, spec, emitted, out, options, after)
    if spec.finish is not None and out:
        # Written after the output moved in place: the reports describe the files as written.
        result.files.update(spec.finish(robot, out, result.findings, result.validation))
    return result


def validate_emitted(
    robot: Robot, spec: Target, emitted: Emitted, out: str | None, options: CompileOptions, verified: Findings
) -> Any:
    """Load what was emitted in an independent consumer and compare it with the IR."""
    from robodesc.validation.options import ValidateOptions

    vopts = ValidateOptions(package_paths=dict(options.package_paths))
    if spec.validator == "sdf" and emitted.text is not None:
        from robodesc.emit.sdf import build_sdf
        from robodesc.validation.drake_sdf import validate_sdf
        from robodesc.validation.report import Status

        text = emitted.text
        if robot.loop_joints:
            # Drake models trees only: check the tree, and say the closures went unchecked.
            text = build_sdf(robot, dataclasses.replace(emitted.extra["sdf_options"], loop_joints=False)).text
        report = validate_sdf(
            robot, text, vopts, link_names=emitted.extra.get("link_names"), joint_names=emitted.extra.get("joint_names")
        )
        for loop in robot.loop_joints:
            report.add(
                "loop-joint",
                Status.SKIP,
                f"loop_joint {loop.name!r}",
                "Drake models kinematic trees only; the tree was checked without this closure",
            )
    elif spec.validator == "usd" and "usd" in emitted.files:
        from robodesc.validation.mujoco_usd import validate_usd

        report = validate_usd(robot, emitted.files["usd"], vopts)
    else:
        from robodesc.validation.mujoco_urdf import validate_urdf_text

        urdf_text = emitted.text
        base_dir = os.path.dirname(os.path.abspath(out)) if out and not spec.folder else os.getcwd()
        if urdf_text is None:  # folder targets: validate the URDF they contain
            urdf = next((p for p in emitted.files.values() if p.endswith(".urdf")), None)
            if urdf is None:
                return None
            with open(urdf, encoding="utf-8") as handle:
                urdf_text = handle.read()
            base_dir = os.path.dirname(urdf)
        report = validate_urdf_text(robot, urdf_text, base_dir, vopts)
    _carried_defects(verified, report)
    return report


def _carried_defects(verified: Findings, report: Any) -> None:
    """A consumer refusing an element the SOURCE already had wrong is the source's defect faithfully
    carried through, not a compile failure: keep it visible as a warning."""
    from robodesc.validation.report import Status

    defective = {f.element for f in verified if f.code in PHYSICAL_CODES or f.code == "massless-link"}
    for check in report.checks:
        if (
            check.status is Status.FAIL
            and check.name in ("mujoco-compile", "drake-parse")
            and check.element in defective
        ):
            check.status = Status.WARN
            check.message += " [a defect of the source, carried through unchanged]"


def _unique(findings: Findings) -> list[Finding]:
    """Drop repeats (the verifier and a pass may notice the same thing)."""
    seen: set[tuple[str, str, str]] = set()
    out = []
    for f in findings:
        key = (f.code, f.element, f.message)
        if key not in seen:
            seen.add(key)
            out.append(f)
    return out
