"""The whole compile: frontend → verifier → passes → verifier → emitter → validation.

Only this module and the API above it know every stage; each stage only knows the IR.
"""

from __future__ import annotations

import copy
import dataclasses
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol

from robodesc.emit.files import staged_folder, write_atomic, write_files
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
class Emitted:
    """What an emitter produced: the main text (when it is text) and every file written."""

    text: str | None = None
    files: dict[str, str] = field(default_factory=dict)  # role -> path
    # Emitter-specific data validation needs (the SDF emitter's renamed links and joints).
    extra: dict[str, Any] = field(default_factory=dict)


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


def pass_options(options: CompileOptions, target: str = "urdf") -> PassOptions:
    """The passes' options: the preset, overridden by explicit options, with the policies the
    compile options and the target imply."""
    chosen = options_from_mapping(options.passes)
    resolved = resolve_options(options.preset or TARGET_PRESETS.get(target), chosen)
    for name, value in TARGET_PASSES.get(target, {}).items():
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
def _emit_urdf(robot: Robot, out: str | None, options: CompileOptions, findings: Findings) -> Emitted:
    with_armature = [j.name for j in robot.joints if j.armature is not None]
    if with_armature:
        findings.info(
            "urdf-armature",
            f"armature of {len(with_armature)} joints written as <dynamics armature=...> (URDF has no armature element; "
            "standard parsers ignore it, the USD output carries physxJoint:armature and newton:armature)",
            element=f"robot {robot.name!r}",
            stage="emit:urdf",
        )
    # Imported per target, like the other emitters: a USD compile does not load the URDF writer.
    from robodesc.emit.urdf import UrdfOptions, emit_urdf

    out_dir = os.path.dirname(os.path.abspath(out)) if out else None
    text = emit_urdf(robot, UrdfOptions(path_mode=options.mesh_paths, out_dir=out_dir))
    emitted = Emitted(text=text)
    if out:
        write_atomic(out, text)
        emitted.files["urdf"] = out
    return emitted


def _emit_sdf(robot: Robot, out: str | None, options: CompileOptions, findings: Findings) -> Emitted:
    from robodesc.emit.sdf import build_sdf
    from robodesc.emit.sdf_options import SdfOptions

    sdf_options = dataclass_from_mapping(SdfOptions, target_options(SdfOptions, options), "sdf")
    sdf_options.path_mode = options.mesh_paths
    sdf_options.out_dir = os.path.dirname(os.path.abspath(out)) if out else None
    result = build_sdf(robot, sdf_options)
    findings.extend(result.findings)
    text = result.text
    emitted = Emitted(
        text=text,
        extra={
            "link_names": result.names.by_kind.get("link", {}),
            "joint_names": result.names.by_kind.get("joint", {}),
            "sdf_options": sdf_options,
        },
    )
    if out:
        write_atomic(out, text)
        emitted.files["sdf"] = out
    return emitted


def _emit_ros2(robot: Robot, out: str | None, options: CompileOptions, findings: Findings) -> Emitted:
    from robodesc.emit.ros2 import Ros2Options, build_ros2_package

    if not out:
        raise ConfigError("the ROS 2 package is several files: give an output folder with -o")
    ros2_options = dataclass_from_mapping(Ros2Options, target_options(Ros2Options, options), "ros2")
    ros2_options.out_dir = os.path.abspath(out)
    package = build_ros2_package(robot, ros2_options)
    findings.extend(package.findings)
    return Emitted(files=write_folder(out, package.files))


def _emit_usd(robot: Robot, out: str | None, options: CompileOptions, findings: Findings) -> Emitted:
    from robodesc.emit.usd import emit_usd
    from robodesc.emit.usd_options import UsdOptions

    if not out:
        raise ConfigError("USD is written to a file: give one with -o robot.usda|.usdc|.usd")
    usd_options = dataclass_from_mapping(UsdOptions, target_options(UsdOptions, options), "usd")
    if "fix_base" not in options.target_options and robot.fixed_base is not None:
        usd_options.fix_base = robot.fixed_base
    findings.extend(emit_usd(robot, out, usd_options))
    return Emitted(files={"usd": out})


def _emit_isaac(robot: Robot, out: str | None, options: CompileOptions, findings: Findings) -> Emitted:
    from robodesc.emit.isaac_settings import IsaacSettings
    from robodesc.isaac import write_isaac_folder

    if not out:
        raise ConfigError("the Isaac Sim target writes a folder: give it with -o OUT_DIR")
    settings = dataclass_from_mapping(IsaacSettings, target_options(IsaacSettings, options), "isaac")
    if "fix_base" not in options.target_options and robot.fixed_base is not None:
        settings.fix_base = robot.fixed_base
    if "init_pos" not in options.target_options and robot.placement is not None:
        settings.init_pos = robot.placement.xyz  # where the composition put the robot
    files = write_isaac_folder(robot, out, settings, findings, options.mesh_paths)
    return Emitted(files=files, extra={"settings": settings})


def target_options_class(target: str) -> type[Any] | None:
    """The options dataclass a target takes (imported lazily: each pulls its emitter's module)."""
    if target == "sdf":
        from robodesc.emit.sdf_options import SdfOptions

        return SdfOptions
    if target == "usd":
        from robodesc.emit.usd_options import UsdOptions

        return UsdOptions
    if target == "isaac":
        from robodesc.emit.isaac_settings import IsaacSettings

        return IsaacSettings
    if target == "ros2":
        from robodesc.emit.ros2_options import Ros2Options

        return Ros2Options
    return None


def target_options(cls: type[Any], options: CompileOptions) -> dict[str, Any]:
    """The target options that belong to the options class ``cls``."""
    names = {f.name for f in dataclasses.fields(cls)}
    return {k: v for k, v in options.target_options.items() if k in names}


def write_folder(out: str, files: Mapping[str, str | bytes]) -> dict[str, str]:
    """Write ``files`` into folder ``out`` as one unit."""
    with staged_folder(out) as staging:
        write_files(staging, files)
    return {name: os.path.join(out, name) for name in sorted(files)}


Target = Callable[[Robot, str | None, CompileOptions, Findings], Emitted]
TARGETS: dict[str, Target] = {
    "urdf": _emit_urdf,
    "sdf": _emit_sdf,
    "usd": _emit_usd,
    "ros2": _emit_ros2,
    "isaac": _emit_isaac,
}
# Targets whose output is a folder rather than a file.
FOLDER_TARGETS = {"ros2", "isaac"}
# What a target cannot do without: USD prim names must be identifiers, and Isaac merges materials
# that share a name.
TARGET_PASSES: dict[str, dict[str, bool]] = {
    "usd": {"sanitize_names": True, "unique_materials": True},
    "isaac": {"sanitize_names": True, "unique_materials": True},
}
# The preset a target implies when the user names none.
TARGET_PRESETS = {"isaac": "isaac_sim"}


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
    resolved = pass_options(options, target)
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
        out_dir = out if target in FOLDER_TARGETS else os.path.dirname(os.path.abspath(out))
        progress(f"copying meshes to {os.path.join(out_dir, 'meshes')}")
        ctx = PassContext(resolved)
        copy_meshes(robot, out_dir, ctx)
        findings.extend(ctx.findings)
    progress(f"writing {target}")
    emitted = TARGETS[target](robot, out, options, findings)
    result = CompileResult(
        robot=robot, findings=_unique(findings), target=target, text=emitted.text, files=emitted.files
    )
    if options.validate:
        progress("validating")
        result.validation = validate_emitted(robot, target, emitted, out, options, after)
    if target == "isaac" and out:
        from robodesc.isaac import findings_markdown

        # Written after the folder moved in place: the report describes the files as written.
        write_atomic(os.path.join(out, "findings.md"), findings_markdown(robot, result.findings))
        result.files["findings"] = os.path.join(out, "findings.md")
        if result.validation is not None:
            write_atomic(os.path.join(out, "validation.md"), result.validation.to_markdown())
            write_atomic(os.path.join(out, "validation.json"), result.validation.to_json())
            result.files["validation"] = os.path.join(out, "validation.md")
    return result


def validate_emitted(
    robot: Robot, target: str, emitted: Emitted, out: str | None, options: CompileOptions, verified: Findings
) -> Any:
    """Load what was emitted in an independent consumer and compare it with the IR."""
    from robodesc.validation.options import ValidateOptions

    vopts = ValidateOptions(package_paths=dict(options.package_paths))
    if target == "sdf" and emitted.text is not None:
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
    elif target == "usd" and "usd" in emitted.files:
        from robodesc.validation.mujoco_usd import validate_usd

        report = validate_usd(robot, emitted.files["usd"], vopts)
    else:
        from robodesc.validation.mujoco_urdf import validate_urdf_text

        urdf_text = emitted.text
        base_dir = os.path.dirname(os.path.abspath(out)) if out and target == "urdf" else os.getcwd()
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
