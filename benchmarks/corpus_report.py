"""Corpus fidelity report: every corpus robot through every available target and its validator.

    PYTHONPATH=src python benchmarks/corpus_report.py                 # all robots -> docs/corpus-report.md
    PYTHONPATH=src python benchmarks/corpus_report.py --subset small  # a few robots -> docs/corpus-report-small.md
    PYTHONPATH=src python benchmarks/corpus_report.py --subset small --check   # CI: fail if the file is stale

Targets: URDF (validated in MuJoCo), SDF (validated in Drake) and USD (validated with usd-core's
UsdPhysics parser, plus mujoco-usd when installed), each only when its emitter imports. The file is deterministic: robots in corpus
order, errors at machine precision printed as "≤1e-12", no timestamps; timings go to stdout only.
"""

from __future__ import annotations

import argparse
import copy
import os
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from robodesc.emit.common.paths import PathMode
from robodesc.emit.urdf import UrdfOptions, emit_urdf
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.ir.diagnostics import Findings, RobodescError, Severity
from robodesc.ir.model import Robot
from robodesc.ir.verify import PHYSICAL_CODES, verify
from robodesc.pipeline import drop_dangling
from robodesc.validation.corpora import CorpusRobot, all_robots
from robodesc.validation.mujoco_urdf import validate_urdf_text
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Status, ValidationReport

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SMALL = (
    "spirit",
    "ur_description/urdf/ur5_robot",
    "panda_description/urdf/panda",
    "double_pendulum_description/urdf/double_pendulum_continuous",
    "anymal_c_simple_description/urdf/anymal",
    "tiago_description/robots/tiago_no_hand",
    "left_hand_mk3",
    "stretch_description_SE3_eoa_wrist_dw3_tool_sg3",
)
FLOOR = 1e-12  # below this an error is rounding, and its exact value differs between machines


@dataclass
class TargetResult:
    target: str
    converted: str  # "yes", "no", "n/a"
    why: str = ""
    # Why it was not converted: "source" (structural defect), "target" (the emitter refuses), "robodesc" (crash).
    blame: str = ""
    report: ValidationReport | None = None
    seconds: float = 0.0


@dataclass
class RobotResult:
    robot: CorpusRobot
    links: int = 0
    load_note: str = ""
    load_error: str = ""
    defects: list[str] = field(default_factory=list)
    defect_elements: set[str] = field(default_factory=set)
    targets: list[TargetResult] = field(default_factory=list)


# ---- running -----------------------------------------------------------------------------------
def load(robot: CorpusRobot, result: RobotResult) -> Robot | None:
    # The compiler's default: a missing mesh is a warning (the reference is kept), noted here.
    opts = LoadOptions(package_paths=robot.packages, xacro_args=robot.xacro_args, missing_mesh=MissingMesh.WARN)
    try:
        loaded = load_path(robot.path, opts)
    except RobodescError as exc:
        result.load_error = exc.render()
        return None
    missing = [f for f in loaded.findings if f.code == "missing-mesh"]
    if missing:
        result.load_note = f"missing mesh (a warning): {_short_path(missing[0].render())}"
    return loaded.robot


def run_urdf(robot: Robot, options: ValidateOptions, workdir: str) -> TargetResult:
    text = emit_urdf(robot, UrdfOptions(path_mode=PathMode.ABSOLUTE))
    report = validate_urdf_text(robot, text, os.path.dirname(robot.source_file or "") or None, options)
    return TargetResult("urdf", "yes", report=report)


def run_sdf(robot: Robot, options: ValidateOptions, workdir: str) -> TargetResult:
    try:
        from robodesc.emit.sdf import SdfOptions, build_sdf
    except ImportError as exc:
        return TargetResult("sdf", "n/a", f"target not available ({exc})")
    from robodesc.validation.drake_sdf import validate_sdf

    try:
        built = build_sdf(robot, SdfOptions(path_mode=PathMode.ABSOLUTE))
    except RobodescError as exc:
        return TargetResult("sdf", "no", exc.render(), blame="target")
    report = validate_sdf(
        robot,
        built.text,
        options,
        link_names=built.names.by_kind.get("link", {}),
        joint_names=built.names.by_kind.get("joint", {}),
    )
    return TargetResult("sdf", "yes", report=report)


def run_usd(robot: Robot, options: ValidateOptions, workdir: str) -> TargetResult:
    try:
        from robodesc.emit.usd import emit_usd
    except ImportError as exc:
        return TargetResult("usd", "n/a", f"target not available ({exc})")
    from robodesc.passes.options import PassOptions
    from robodesc.passes.pipeline import run_passes
    from robodesc.validation.mujoco_usd import validate_usd

    # USD needs valid prim names; the pipeline sanitizes them before emitting, so do the same.
    robot = copy.deepcopy(robot)
    run_passes(robot, options=PassOptions(sanitize_names=True))
    path = os.path.join(workdir, f"{_slug(robot.name)}.usdc")  # binary: mesh arrays as text would dominate
    try:
        emit_usd(robot, path)
    except RobodescError as exc:
        return TargetResult("usd", "no", exc.render(), blame="target")
    return TargetResult("usd", "yes", report=validate_usd(robot, path, options))


RUNNERS: dict[str, Callable[[Robot, ValidateOptions, str], TargetResult]] = {
    "urdf": run_urdf,
    "sdf": run_sdf,
    "usd": run_usd,
}


def run_robot(robot: CorpusRobot, targets: list[str], options: ValidateOptions, workdir: str) -> RobotResult:
    result = RobotResult(robot)
    ir = load(robot, result)
    if ir is None:
        return result
    result.links = len(ir.links)
    structural = []
    # As the compiler does: an element naming what does not exist is dropped with a warning.
    found = verify(ir)
    kept = drop_dangling(ir, found.errors, Findings())
    for f in found:
        if f.severity is Severity.ERROR:
            where = f" (line {f.loc.line})" if f.loc is not None and f.loc.line is not None else ""
            result.defects.append(f"{f.element}: [{f.code}] {f.message}{where}")
            result.defect_elements.add(f.element)
            if f.code not in PHYSICAL_CODES and f in kept:
                structural.append(f"{f.element}: {f.message}")
    if structural:
        # `robodesc compile` stops on structural errors (only physical ones can be let through).
        why = f"source defect, the compiler stops: {structural[0]}" + (
            f" (and {len(structural) - 1} more)" if len(structural) > 1 else ""
        )
        result.targets = [TargetResult(t, "no", why, blame="source") for t in targets]
        return result
    for target in targets:
        started = time.perf_counter()
        try:
            tr = RUNNERS[target](ir, options, workdir)
        except Exception as exc:  # a crash is a robodesc bug: record it, keep going
            tr = TargetResult(target, "no", f"robodesc crashed: {type(exc).__name__}: {exc}", blame="robodesc")
        tr.seconds = time.perf_counter() - started
        result.targets.append(tr)
    return result


# ---- rendering ---------------------------------------------------------------------------------
def _slug(name: str) -> str:
    return "".join(c if c.isalnum() else "_" for c in name)


def _short_path(text: str) -> str:
    for prefix in sorted({sys.prefix, os.path.dirname(ROOT)}, key=len, reverse=True):
        text = text.replace(prefix + os.sep, "")
    return text.replace("|", "\\|").replace("\n", " ")


def _num(value: float | None) -> str:
    if value is None:
        return "–"
    return "≤1e-12" if value <= FLOOR else f"{value:.2g}"


def cause(check_element: str, check_name: str, result: RobotResult) -> str:
    """``source`` when the input is at fault (a verifier error on that element, or the consumer
    refusing an input property such as a massless moving link or a degenerate mesh), else ``robodesc``."""
    if check_element in result.defect_elements or check_name in ("mujoco-compile", "mesh-files"):
        return "source"
    return "robodesc"


def status_cells(tr: TargetResult) -> tuple[str, str, str, str, str]:
    """validated, FK, mass/inertia, simulation, note."""
    if tr.report is None:
        return "–", "–", "–", "–", _short_path(tr.why)
    r = tr.report
    skipped = [c for c in r.checks if c.status is Status.SKIP and c.element == "document"]
    if skipped and len(r.checks) == 1:
        return "skipped", "–", "–", "–", skipped[0].message
    fk = (
        f"{_num(r.max_errors.get('fk_position'))} m / {_num(r.max_errors.get('fk_rotation'))} rad"
        if "fk_position" in r.max_errors
        else "–"
    )
    mi = f"{_num(r.max_errors.get('mass'))} / {_num(r.max_errors.get('inertia'))}" if "mass" in r.max_errors else "–"
    sims = r.by_name("simulation")
    sim = (
        "–"
        if not sims
        else (
            "stable"
            if sims[0].status is Status.PASS
            else sims[0].status.value
            if sims[0].status is Status.SKIP
            else "UNSTABLE"
        )
    )
    validated = "pass" if r.ok else f"FAIL ({len(r.failures)})"
    return validated, fk, mi, sim, ""


def render(results: list[RobotResult], targets: list[str], subset: str) -> str:
    import mujoco

    versions = [f"mujoco {mujoco.__version__}"]
    try:
        import pydrake

        versions.append(f"drake {getattr(pydrake, '__version__', 'installed')}")
    except ImportError:
        pass
    try:
        from importlib.metadata import version

        versions.insert(0, f"robodesc {version('robodesc')}")
    except Exception:
        pass
    out = [
        "# Corpus fidelity report",
        "",
        "Generated by `benchmarks/corpus_report.py"
        + (" --subset small" if subset == "small" else "")
        + "`; do not edit by hand. "
        + ", ".join(versions)
        + ".",
        "",
        "Each robot is read from its source, emitted to every target, and the output is loaded by an",
        "independent consumer (URDF: MuJoCo, SDF: Drake, USD: usd-core's UsdPhysics parser) and compared with the IR:",
        "masses, centres of mass, inertia tensors, joint types, axes and limits, and forward kinematics",
        "of every link at random configurations; URDF also gets a 0.5 s simulation. See",
        "[validation.md](validation.md) for the checks and tolerances. Errors at machine precision show",
        "as ≤1e-12. *Cause* says whether a failure comes from the **source** (a defect the IR verifier or",
        "the consumer finds in the input: fix the input or compile with `--invalid-inertia repair`) or",
        "from **robodesc** (the output differs from the input: a bug to report). *Converted* `yes*`: the",
        "source reads only with `--missing-mesh warn` (a mesh file it names is missing).",
        "",
    ]
    # summary
    n = len(results)
    loaded = [r for r in results if not r.load_error]
    defective = [r for r in results if r.defects]
    out += ["## Summary", "", "| | " + " | ".join(targets) + " |", "|---|" + "---|" * len(targets)]

    def count(pred: Callable[[TargetResult], bool]) -> list[str]:
        return [str(sum(1 for r in results for t in r.targets if t.target == tg and pred(t))) for tg in targets]

    out.append("| robots | " + " | ".join(str(n) for _ in targets) + " |")
    out.append("| read by the frontend | " + " | ".join(str(len(loaded)) for _ in targets) + " |")
    out.append("| converted | " + " | ".join(count(lambda t: t.converted == "yes")) + " |")
    out.append(
        "| validated, all checks pass | "
        + " | ".join(count(lambda t: t.report is not None and t.report.ok and not _only_skip(t.report)))
        + " |"
    )
    out.append(
        "| validated, some check fails | "
        + " | ".join(count(lambda t: t.report is not None and not t.report.ok))
        + " |"
    )
    out.append(
        "| validation skipped (consumer missing) | "
        + " | ".join(count(lambda t: t.report is not None and _only_skip(t.report)))
        + " |"
    )
    out.append(
        "| failures caused by robodesc | "
        + " | ".join(
            str(
                sum(
                    1
                    for r in results
                    for t in r.targets
                    if t.target == tg and t.report is not None
                    for c in t.report.failures
                    if cause(c.element, c.name, r) == "robodesc"
                )
            )
            for tg in targets
        )
        + " |"
    )
    out.append(
        "| not converted: robodesc crashed | "
        + " | ".join(count(lambda t: t.converted == "no" and t.blame == "robodesc"))
        + " |"
    )
    out += ["", f"Robots whose source has defects (IR verifier errors): {len(defective)} of {n}.", ""]

    out += [
        "## Robots",
        "",
        "| corpus | robot | links | target | converted | validated | max FK error | max mass / inertia error (rel.) | simulation | note |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in results:
        name = r.robot.name
        if r.load_error:
            out.append(
                f"| {r.robot.corpus} | {name} | – | all | no | – | – | – | – | NOT READ: {_short_path(r.load_error)} |"
            )
            continue
        for t in r.targets:
            validated, fk, mi, sim, note = status_cells(t)
            conv = t.converted if t.converted != "yes" or not r.load_note else "yes*"
            if not note and r.load_note and t.target == targets[0]:
                note = r.load_note
            if not note and r.defects and t.target == targets[0]:
                note = f"{len(r.defects)} source defect(s), see below"
            out.append(
                f"| {r.robot.corpus} | {name} | {r.links} | {t.target} | {conv} | {validated} | {fk} | {mi} | {sim} | {_short_path(note)} |"
            )
    out.append("")
    out += [
        "## Source defects",
        "",
        "Findings of the IR verifier on the inputs, exactly as reported. These robots convert; the defects",
        "are carried into the output unchanged (a faithful compiler does not silently fix them).",
        "",
    ]
    for r in results:
        if r.defects:
            out.append(f"- **{r.robot.name}** ({r.robot.corpus}), {len(r.defects)} defect(s):")
            for d in r.defects:
                out.append(f"  - {_short_path(d)}")
    if not defective:
        out.append("None.")
    out += ["", "## Failures", "", "Every failing check, with the element it names and what to do about it.", ""]
    any_fail = False
    for r in results:
        for t in r.targets:
            if t.report is None:
                if t.converted == "no":
                    any_fail = True
                    out.append(
                        f"- **{r.robot.name}** [{t.target}] not converted (cause: {t.blame}): {_short_path(t.why)}"
                    )
                continue
            for c in t.report.failures:
                any_fail = True
                out.append(
                    f"- **{r.robot.name}** [{t.target}] `{c.name}` {c.element} (cause: {cause(c.element, c.name, r)}): {_short_path(c.message)}"
                )
        if r.load_error:
            any_fail = True
            out.append(f"- **{r.robot.name}** not read: {_short_path(r.load_error)}")
    if not any_fail:
        out.append("None.")
    return "\n".join(out) + "\n"


def _only_skip(report: ValidationReport) -> bool:
    return bool(report.checks) and all(c.status is Status.SKIP for c in report.checks)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--subset", choices=("all", "small"), default="all")
    parser.add_argument("--shared-corpus", default=os.path.join(ROOT, "..", "shared", "corpus"))
    parser.add_argument(
        "--out", default=None, help="default: docs/corpus-report.md (all) or docs/corpus-report-small.md"
    )
    parser.add_argument("--targets", default="urdf,sdf,usd")
    parser.add_argument("--check", action="store_true", help="do not write; exit 1 if the file would change")
    args = parser.parse_args(argv)
    os.environ.setdefault("PXR_WORK_THREAD_LIMIT", "1")
    targets = [t for t in args.targets.split(",") if t]
    robots = all_robots(args.shared_corpus)
    if args.subset == "small":
        robots = [r for r in robots if r.name in SMALL]
    out = args.out or os.path.join(
        ROOT, "docs", "corpus-report.md" if args.subset == "all" else "corpus-report-small.md"
    )
    options = ValidateOptions()
    started = time.perf_counter()
    results = []
    with tempfile.TemporaryDirectory(prefix="robodesc-corpus-") as workdir:
        for robot in robots:
            t0 = time.perf_counter()
            res = run_robot(robot, targets, options, workdir)
            results.append(res)
            per = ", ".join(f"{t.target} {t.seconds:.2f}s" for t in res.targets)
            state = (
                "NOT READ"
                if res.load_error
                else " ".join(
                    f"{t.target}:{'ok' if t.report is not None and t.report.ok else t.converted if t.report is None else 'FAIL'}"
                    for t in res.targets
                )
            )
            print(f"{time.perf_counter() - t0:6.2f}s  {robot.corpus}/{robot.name}: {state} ({per})", flush=True)
    text = render(results, targets, args.subset)
    elapsed = time.perf_counter() - started
    print(f"{len(results)} robots in {elapsed:.1f} s", flush=True)
    if args.check:
        current = ""
        if os.path.exists(out):
            with open(out, encoding="utf-8") as handle:
                current = handle.read()
        if current != text:
            print(f"{out} is out of date; regenerate it with {' '.join(sys.argv)}", file=sys.stderr)
            return 1
        return 0
    from robodesc.emit.common.files import write_atomic

    write_atomic(out, text)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
