"""The whole compile: frontend → verifier → passes → verifier → emitter → validation → move.

Only this module and the API above it know every stage; each stage only knows the IR, and every
target-specific step comes from the target's :class:`~robodesc.emit.common.target.Target`.

Severity is decided here, by consequence (docs/diagnostics.md): a source defect the output can
carry faithfully is a warning (a mimic naming no joint is dropped, an invalid inertia passes
through); only what leaves nothing sensible to emit (no link, a cycle, no single root) refuses the
compile. Everything is written to a staging location beside the output, validated there, and moved
into place only when the run succeeds: a failed run leaves an earlier output byte-identical.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from robodesc.emit.common.base import BY_FLAG, BaseChoice, choose_base, report_base
from robodesc.emit.common.staging import Staging, check_output
from robodesc.emit.common.target import CheckRequest, EmitRequest, Emitted, Target
from robodesc.frontends.load import Source, load_source
from robodesc.ir.diagnostics import (
    ConfigError,
    Finding,
    Findings,
    Severity,
    UnsupportedError,
    ValidationFailed,
    VerificationError,
)
from robodesc.ir.model import Robot
from robodesc.ir.verify import PHYSICAL_CODES, verify
from robodesc.options import CompileOptions, InvalidInertia, dataclass_from_mapping
from robodesc.passes import pipeline as passes_pipeline
from robodesc.passes.context import PassContext
from robodesc.passes.copy_meshes import copy_meshes
from robodesc.passes.dangling import add_world_root, drop_dangling
from robodesc.passes.options import PassOptions, RepairPolicy, merge_options, options_from_mapping
from robodesc.passes.pipeline import resolve_options
from robodesc.passes.presets import OVERLAY_TARGET_OPTIONS, OVERLAYS
from robodesc.plugins import load_plugins
from robodesc.targets import target_spec
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Check, Status, ValidationReport

if TYPE_CHECKING:
    from robodesc.emit.common.world import PlacedWorld

Progress = Callable[[str], None]


@dataclass(slots=True)
class CompileResult:
    robot: Robot
    findings: list[Finding]
    target: str
    text: str | None = None
    files: dict[str, str] = field(default_factory=dict)
    validation: ValidationReport | None = None  # when validation ran
    # Validation rows that failed because of a defect of the source, not of robodesc (the run
    # still succeeds; they are listed as warnings).
    source_failures: list[Check] = field(default_factory=list)
    # validate --dynamics: a robodesc.validation.dynamics.DynamicsReport (None when not asked).
    dynamics: Any = None
    # Welded or floating, and why (emit/common/base.py); None for a target without a base option.
    base: BaseChoice | None = None
    # A world file compiled alone (no robot: ``robot`` is an empty stand-in): the world's name.
    world: str | None = None

    @property
    def warnings(self) -> list[Finding]:
        return [f for f in self.findings if f.severity is Severity.WARNING]


def _quiet(_: str) -> None:
    pass


def pass_options(options: CompileOptions, spec: Target) -> PassOptions:
    """The passes' options: the preset, overridden by explicit options, with the policies the
    compile options and the target imply."""
    chosen = options_from_mapping(options.passes)
    if options.preset in OVERLAYS:  # a workflow preset goes on top of the target's own
        base = merge_options(resolve_options(spec.preset, None), options_from_mapping(OVERLAYS[options.preset]))
        resolved = merge_options(base, chosen)
    else:
        resolved = resolve_options(options.preset or spec.preset, chosen)
    for name, value in spec.passes.items():
        setattr(resolved, name, value)
    # Compositions give masses without tensors; those are always filled from geometry.
    resolved.fill_inertia = True
    if options.invalid_inertia is InvalidInertia.REPAIR and resolved.repair_inertia is None:
        resolved.repair_inertia = RepairPolicy.GEOMETRY
    return resolved


def verify_source(robot: Robot, options: CompileOptions, findings: Findings, repairing: bool = False) -> None:
    """Verify what the frontend built. What leaves nothing sensible to emit is fatal (exit 2);
    elements that name what does not exist are dropped with a warning (``passes.dangling``);
    physically invalid inertia is handled by :func:`_physical` unless the passes will repair it."""
    result = verify(robot)
    # Dropped elements are warnings; --strict refuses them with every other warning at the end.
    errors = drop_dangling(robot, result.errors, findings)
    if add_world_root(robot, errors, findings):
        # A root link "world" was added: the tree is whole now, verify it again.
        result = verify(robot)
        errors = drop_dangling(robot, result.errors, findings)
    findings.extend([f for f in result.items if f.severity is not Severity.ERROR])
    _physical(errors, options, findings if not repairing else None)


def _physical(errors: list[Finding], options: CompileOptions, findings: Findings | None) -> None:
    """Structural errors refuse the compile. Physically invalid inertia refuses it only under
    ``--invalid-inertia error``; otherwise it passes through as a warning (added to ``findings``,
    when given: the first verification reports it, the one after the passes has said it already)."""
    structural = [f for f in errors if f.code not in PHYSICAL_CODES]
    physical = [f for f in errors if f.code in PHYSICAL_CODES]
    if structural:
        raise VerificationError(structural)
    if physical and options.invalid_inertia is InvalidInertia.ERROR:
        raise VerificationError(physical)
    if findings is None:
        return
    for f in physical:
        findings.add(Severity.WARNING, f.code, f.message + PASSED_THROUGH, element=f.element, loc=f.loc, stage=f.stage)


# Suffixes on what the compile lets through; reports built on its output recognise them by these.
PASSED_THROUGH = " (passed through unchanged; --invalid-inertia repair fixes it from geometry)"
CARRIED = " [a defect of the source, carried through unchanged]"


def _request(
    robot: Robot, spec: Target, stage: Staging, options: CompileOptions, findings: Findings
) -> tuple[EmitRequest, BaseChoice | None]:
    built = None
    base = None
    if spec.options is not None:
        names = {f.name for f in dataclasses.fields(spec.options)}
        given = {k: v for k, v in options.target_options.items() if k in names}
        # A target may keep an option out of the preset overlays (SDF: Gazebo's own mesh handling
        # is what gazebo_parity aims at, so its collision_approximation stays as given).
        exempt = set(getattr(spec.options, "PRESET_EXEMPT", ()))
        overlay = {
            k: v
            for k, v in OVERLAY_TARGET_OPTIONS.get(options.preset or "", {}).items()
            if k in names and k not in exempt
        }
        applied = {k: v for k, v in overlay.items() if k not in given}
        if applied:
            findings.info(
                "preset-applied",
                f"--preset {options.preset} set "
                + ", ".join(f"{k}={v}" for k, v in applied.items())
                + " (options you give win; docs/contact.md says why each)",
                element=f"target {spec.name}",
                stage="options",
            )
        built = dataclass_from_mapping(spec.options, {**applied, **given}, spec.name)
        if "fix_base" in names:
            # One base for every target, decided before the emitter (emit/common/base.py).
            base = choose_base(robot, given.get("fix_base"))
            built.fix_base = base.fixed
            if base.reason == BY_FLAG:
                # The flag overrides a composition's (or MJCF/SDF source's) base: the consumers' checks
                # then compare the files with the base the user asked for, not the one it replaced.
                robot.fixed_base = base.fixed
            report_base(robot, base, findings)
    request = EmitRequest(
        out=stage.path,
        options=built,
        mesh_paths=options.mesh_paths,
        given=frozenset(options.target_options),
        final=stage.final,
    )
    return request, base


def compile_robot(
    source: Source,
    target: str,
    out: str | None,
    options: CompileOptions,
    progress: Progress = _quiet,
) -> CompileResult:
    load_plugins(options.plugins)
    spec = target_spec(target)
    if isinstance(source, str) and _world_file(source):
        return compile_world(source, spec, out, options, progress)
    if options.world.spawn is not None and not options.world.given:
        raise ConfigError(
            "--spawn places the robot in a world: give the world with --world FILE, --terrain FILE or --cords FILE "
            "(docs/worlds.md)",
            element="--spawn",
        )
    if options.world.given and not spec.worlds:
        raise UnsupportedError(
            f"-t {spec.name} describes the robot alone and cannot hold a world; a world (--world FILE, --terrain) "
            "is written by -t mjcf, -t usd, -t sdf and --isaac-sim (docs/worlds.md)",
            element="--world" if options.world.file is not None else "--terrain",
        )
    if out is not None:
        check_output(
            out,
            folder=spec.folder,
            source=source,
            suffixes=spec.suffixes if spec.suffix_required else (),
            example=spec.output_name("robot"),
        )
    findings = Findings()
    resolved = pass_options(options, spec)
    progress("loading")
    robot = load_source(source, options.load, findings)
    progress("verifying")
    verify_source(robot, options, findings, repairing=resolved.repair_inertia is not None)
    progress("running passes: " + ", ".join(passes_pipeline.enabled_passes(resolved)))
    findings.extend(passes_pipeline.run_passes(robot, options=resolved))
    _physical(verify(robot).errors, options, None)
    if options.contact_sensors is not None:
        from robodesc.emit.common.contact_sensors import add_contact_sensors

        add_contact_sensors(robot, options.contact_sensors, findings)
    world = _world(robot, options, findings, progress)
    stage = Staging(out, spec.folder)
    try:
        # Converted and copied meshes beside a file output: a failed run takes back what it added.
        stage.track("meshes")
        request, base = _request(robot, spec, stage, options, findings)
        request = dataclasses.replace(request, world=world)
        if spec.owned is not None and stage.final is not None:
            stage.protect(spec.owned(request.options, stage.final))
        if world is not None and spec.world_files is not None and stage.final is not None:
            stage.protect(spec.world_files(request.options, stage.final))
        emitted = _emit(robot, spec, request, stage, resolved, findings, progress)
        result = CompileResult(
            robot=robot, findings=[], target=spec.name, text=emitted.text, files=emitted.files, base=base
        )
        if options.validate:
            progress("validating")
            _quiet_usd_banner()
            result.validation = validate_emitted(robot, spec, emitted, stage, options)
            if result.validation is not None:
                result.source_failures = source_defect_failures(findings, result.validation)
                consumer_messages(result.validation, findings)
        result.findings = _unique(findings)
        if options.strict:
            refuse_warnings(result.findings, result.source_failures)
        if result.validation is not None and not result.validation.ok:
            raise ValidationFailedError(result)
        if spec.finish is not None and stage.path:
            # Written into the staged output: the reports describe the files as they will be.
            result.files.update(spec.finish(robot, stage.path, result.findings, result.validation))
        result.files = {role: stage.final_path(path) for role, path in result.files.items()}
        stage.commit()
    except BaseException:
        stage.discard()
        raise
    return result


def _world_file(source: str) -> bool:
    """A path to an SDF world (``<sdf>`` holding ``<world>``): compiled alone, with no robot."""
    from robodesc.frontends.world import is_world_file

    return "\n" not in source and "<" not in source and is_world_file(source)


def compile_world(
    source: str, spec: Target, out: str | None, options: CompileOptions, progress: Progress
) -> CompileResult:
    """A world file as the only input (docs/worlds.md, "A world alone"): its static models, cords
    and physics in the target's terms, no robot. Staged, checked in the target's consumer, moved."""
    from robodesc.emit.common.world import place_world
    from robodesc.frontends.world import load_world

    given = options.world
    if spec.world_alone is None:
        raise UnsupportedError(
            f"-t {spec.name} cannot hold a world without a robot; a world file alone is written by -t mjcf, -t usd "
            "and -t sdf (docs/worlds.md)",
            element=source,
        )
    if given.file is not None or given.terrain is not None or given.spawn is not None:
        raise ConfigError(
            "the input is a world: --world, --terrain and --spawn place a robot in one (robodesc compile ROBOT "
            "--world FILE)",
            element=source,
        )
    if out is None:
        raise ConfigError(f"a world alone is written to a file: give one with -o (e.g. {spec.output_name('world')})")
    check_output(out, folder=False, source=source, suffixes=spec.suffixes if spec.suffix_required else ())
    findings = Findings()
    progress("reading the world")
    world = load_world(dataclasses.replace(given, file=source), findings)
    assert world is not None
    placed = place_world(None, world, findings, resolution=given.terrain_resolution)
    built = (
        dataclass_from_mapping(
            spec.options, {k: v for k, v in options.target_options.items() if k in _fields(spec.options)}, spec.name
        )
        if spec.options is not None
        else None
    )
    stage = Staging(out, False)
    try:
        progress(f"writing {spec.name}")
        assert stage.path is not None
        files, report = spec.world_alone(placed, stage.path, built, findings, options.validate)
        result = CompileResult(
            robot=Robot(name=world.name), findings=[], target=spec.name, files=files, world=world.name
        )
        result.validation = report
        result.findings = _unique(findings)
        if options.strict:
            refuse_warnings(result.findings, [])
        if report is not None and not report.ok:
            raise ValidationFailedError(result)
        result.files = {role: stage.final_path(path) for role, path in files.items()}
        stage.commit()
    except BaseException:
        stage.discard()
        raise
    return result


def _fields(cls: type[Any]) -> set[str]:
    return {f.name for f in dataclasses.fields(cls)}


def _world(robot: Robot, options: CompileOptions, findings: Findings, progress: Progress) -> PlacedWorld | None:
    """The world, read and placed once for whichever target writes it (emit/common/world.py)."""
    if not options.world.given:
        return None
    from robodesc.emit.common.world import place_world
    from robodesc.frontends.world import load_world

    progress("reading the world")
    world = load_world(options.world, findings)
    if world is None:
        return None
    progress("placing the robot in the world")
    given = options.world
    return place_world(
        robot, world, findings, resolution=given.terrain_resolution, spawn=given.spawn, copies=given.copies
    )


def _emit(
    robot: Robot,
    spec: Target,
    request: EmitRequest,
    stage: Staging,
    resolved: PassOptions,
    findings: Findings,
    progress: Progress,
) -> Emitted:
    """Copy meshes when asked (into the staged folder, or beside a file output), then emit."""
    kept_meshes = None
    if resolved.copy_meshes:
        if not stage.final:
            raise ConfigError("--copy-meshes needs an output file (-o)")
        # A folder target gets its meshes/ inside the staged folder; a file target beside the file.
        out_dir = stage.path if spec.folder else os.path.dirname(os.path.abspath(stage.final))
        assert out_dir is not None
        shown = os.path.join(stage.final if spec.folder else out_dir, "meshes")
        if spec.copies:
            progress(f"copying meshes to {shown}")
            ctx = PassContext(resolved)
            copy_meshes(robot, out_dir, ctx, spec.copies)
            findings.extend(ctx.findings)
        else:
            findings.info(
                "copy-meshes-default",
                f"-t {spec.name} writes every mesh it uses under {shown} without --copy-meshes; the flag changes nothing",
                element=f"robot {robot.name!r}",
                stage="copy_meshes",
            )
        if spec.folder and spec.copies:
            kept_meshes = stage.set_aside("meshes")
    progress(f"writing {spec.name}")
    emitted = spec.emit(robot, request, findings)
    if kept_meshes is not None:
        stage.put_back(kept_meshes, "meshes")
    return emitted


class ValidationFailedError(ValidationFailed):
    """The output differs from the source because of robodesc (exit 1); nothing was moved into place.
    ``result`` holds the report."""

    def __init__(self, result: CompileResult) -> None:
        report = result.validation
        failed = [c for c in report.checks if c.status is Status.FAIL] if report is not None else []
        first = failed[0] if failed else None
        what = f"{first.name} {first.element}: {first.message}" if first is not None else "a check failed"
        super().__init__(f"the output failed validation ({len(failed)} failed check(s); first: {what})")
        self.result = result


def refuse_warnings(findings: list[Finding], source_failures: list[Check]) -> None:
    """``--strict``: every warning (and every source-caused validation failure) is an error."""
    warned = [f for f in findings if f.severity is Severity.WARNING]
    for check in source_failures:
        warned.append(Finding(Severity.WARNING, f"validation:{check.name}", check.message, element=check.element))
    if warned:
        raise StrictError([dataclasses.replace(f, severity=Severity.ERROR) for f in warned])


class StrictError(VerificationError):
    """``--strict`` and the compile had warnings: refused, nothing written."""


def _quiet_usd_banner() -> None:
    # usd-core prints a banner to standard error when PXR_WORK_THREAD_LIMIT is set (the validators
    # set it); this setting, read when pxr loads, turns such alerts off.
    os.environ.setdefault("TF_ENV_SETTING_ALERTS_ENABLED", "0")


def validate_emitted(
    robot: Robot, spec: Target, emitted: Emitted, stage: Staging, options: CompileOptions
) -> ValidationReport | None:
    """Load what was emitted in the target's independent consumer and compare it with the IR."""
    if spec.check is None:
        return None
    request = CheckRequest(
        out=stage.path, options=ValidateOptions(package_paths=dict(options.load.package_paths)), folder=spec.folder
    )
    report = spec.check(robot, emitted, request)
    if report is not None and stage.path and stage.final:
        # The checks ran on the staged copy; name the output the user typed, whole path first.
        report.rename(stage.path, stage.final)
        report.rename(os.path.basename(stage.path), os.path.basename(stage.final))
    return report


# Validation checks that fail when the source is at fault whatever robodesc writes: the consumer
# refusing to build the model (a massless moving link) or a mesh file it cannot read.
SOURCE_CHECKS = frozenset({"mujoco-compile", "mesh-files"})
# Checks about the model as a whole, and the source defects that make them fail whatever robodesc
# writes: a consumer refusing the document (an <inertial> without <mass>; a mass without a tensor
# that no readable geometry can give, found by the geometric_inertia pass), a simulation going
# unstable (an inertia passed through unphysical, a negative damping, which Drake refuses too). Named by the source's warning.
DOCUMENT_CHECKS = frozenset({"mujoco-parse", "mjcf-load", "scene-load", "drake-parse"})
DOCUMENT_DEFECTS = frozenset({"inertial-without-mass", "no-geometry", "negative-dynamics"})
DYNAMICS_CHECKS = frozenset({"simulation", "menagerie"})
DYNAMICS_DEFECTS = PHYSICAL_CODES | {"negative-dynamics"}


def source_defect_failures(findings: Findings | list[Finding], report: ValidationReport) -> list[Check]:
    """Turn the failed checks the SOURCE is to blame for into warnings, and return them.

    A check fails because of the source when it is about an element the source already had wrong
    (a warning of the frontend or the verifier: invalid inertia, a massless link, a dropped shape),
    or when the consumer refuses the model as a whole (SOURCE_CHECKS), as the corpus report
    classifies them. What remains failed is robodesc's fault: exit 1."""
    source = [
        f
        for f in findings
        if f.code in PHYSICAL_CODES
        or (
            f.severity is Severity.WARNING
            and (f.stage.startswith(("verify", "frontend")) or f.code in DOCUMENT_DEFECTS | DYNAMICS_DEFECTS)
        )
    ]
    defective = {f.element for f in source if f.element}
    codes = {f.code for f in source}
    whole = {
        name
        for checks, defects in ((DOCUMENT_CHECKS, DOCUMENT_DEFECTS), (DYNAMICS_CHECKS, DYNAMICS_DEFECTS))
        if codes & defects
        for name in checks
    }
    out = []
    for check in report.checks:
        if check.status is Status.FAIL and (
            check.name in SOURCE_CHECKS or check.name in whole or check.element in defective
        ):
            check.status = Status.WARN
            check.message += CARRIED
            out.append(check)
    return out


def consumer_messages(report: ValidationReport, findings: Findings) -> None:
    """What the consumer said while loading the output (MuJoCo's ``WARNING: ...`` lines, captured
    rather than printed), as findings: a user sees them with the rest, and ``-q`` silences them."""
    for check in report.checks:
        if check.name.endswith("-warning") and check.status is Status.WARN:
            findings.warn(
                "consumer-warning",
                f"{report.consumer} says: {check.message}",
                element=check.element if check.element not in ("model", "document") else f"robot {report.robot!r}",
                stage="validate",
            )


def _unique(findings: Findings) -> list[Finding]:
    """Drop repeats (the verifier and a pass may notice the same thing)."""
    seen: set[tuple[str, str, str, str]] = set()
    out = []
    for f in findings:
        key = (f.code, f.element, f.message, str(f.loc))
        if key not in seen:
            seen.add(key)
            out.append(f)
    return out
