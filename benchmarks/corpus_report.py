"""Corpus fidelity report: every corpus robot through every available target and its validator.

    PYTHONPATH=src python benchmarks/corpus_report.py                 # all robots -> docs/corpus-report.md
    PYTHONPATH=src python benchmarks/corpus_report.py --subset small  # a few robots -> docs/corpus-report-small.md
    PYTHONPATH=src python benchmarks/corpus_report.py --subset small --check   # CI: fail if the file is stale

A thin user of ``robodesc batch``: one job per robot and target (URDF validated in MuJoCo, SDF in
Drake, USD with usd-core's UsdPhysics parser, plus mujoco-usd when installed), each the same compile
as ``robodesc compile ROBOT -t TARGET`` with default flags, on every core
(``--jobs``); this script only renders the jobs' results. With ``--workdir DIR`` the outputs are kept
and a rerun redoes only the robots whose files changed. When ``benchmarks/results/consumers.json``
exists (robot -> {"newton": ..., "newton_isaac": ..., "isaac_importer": ..., "physx": ...,
"physx_isaac": ...}, written by the consumer tier, tests/consumers/run_tier.py), its verdicts become
extra columns; ``benchmarks/results/dynamics.json``
(``benchmarks/dynamics_corpus.py``: ``validate --dynamics`` per robot) becomes the ``dynamics`` column.

The file is deterministic: robots in corpus order, errors at machine precision printed as "≤1e-12",
no timestamps; timings go to stdout only.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from robodesc.batch.jobs import CRASHED, TIMEOUT, WROTE_OUTPUTS, Job, JobResult, finalize, with_overrides
from robodesc.batch.runner import run_batch
from robodesc.ir.verify import PHYSICAL_CODES
from robodesc.options import CompileOptions
from robodesc.pipeline import CARRIED, PASSED_THROUGH
from robodesc.validation.corpora import CorpusRobot, all_robots
from robodesc.validation.report import Check, Status, ValidationReport

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CONSUMERS = os.path.join(ROOT, "benchmarks", "results", "consumers.json")
# physx / physx_isaac: run_tier.py --kinds physx, the USD outputs in PhysX (validation/physx_usd.py).
CONSUMER_COLUMNS = ("newton", "newton_isaac", "isaac_importer", "physx", "physx_isaac", "dynamics")
# benchmarks/dynamics_corpus.py: robot -> validate --dynamics verdicts, the "dynamics" column.
DYNAMICS = os.path.join(ROOT, "benchmarks", "results", "dynamics.json")
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


# ---- running: one batch job per robot and target -------------------------------------------------
def _slug(name: str) -> str:
    return "".join(c if c.isalnum() else "_" for c in name)


def make_jobs(robots: list[CorpusRobot], targets: list[str], root: str) -> list[Job]:
    jobs = []
    for robot in robots:
        for target in targets:
            # Default flags, as a user runs them (a missing mesh and invalid inertia are warnings).
            values = {"package_paths": dict(robot.packages), "xacro_args": dict(robot.xacro_args)}
            options = with_overrides(CompileOptions(), target, values, robot.path)
            job_id = f"{_slug(robot.corpus)}/{_slug(robot.name)}/{target}"
            jobs.append(Job(job_id, robot.path, os.path.abspath(robot.path), target, "", options))
    # USD as .usdc: mesh arrays written as text would dominate the time.
    return finalize(jobs, root, suffix=".usdc")


def report_from_json(data: dict[str, Any]) -> ValidationReport:
    """The job's validation report, with checks the compiler let through as source defects counted
    as failures again: this report says what the consumer thinks of the output, cause aside."""
    report = ValidationReport(str(data["robot"]), str(data["target"]), str(data["consumer"]))
    for c in data["checks"]:
        status, message = Status(c["status"]), str(c["message"])
        if status is Status.WARN and message.endswith(CARRIED):
            status, message = Status.FAIL, message.removesuffix(CARRIED)
        report.checks.append(Check(c["name"], status, c["element"], message, c["error"], c["tolerance"]))
    report.max_errors = {k: float(v) for k, v in data["max_errors"].items()}
    return report


def _render_finding(f: dict[str, Any]) -> str:
    where = f" (line {f['line']})" if f.get("line") is not None else ""
    return f"{f['element']}: [{f['code']}] {str(f['message']).removesuffix(PASSED_THROUGH)}{where}"


def _loc_render(f: dict[str, Any]) -> str:
    loc = f["file"] + (f":{f['line']}" if f.get("line") is not None else "") if f.get("file") else ""
    return ": ".join(x for x in (loc, f["element"], str(f["message"]).removesuffix("; reference kept")) if x)


def robot_result(robot: CorpusRobot, targets: list[str], results: list[JobResult]) -> RobotResult:
    out = RobotResult(robot)
    first = results[0]
    if first.status not in WROTE_OUTPUTS and first.stage == "load":
        out.load_error = first.error
        return out
    info = next((r.robot for r in results if r.robot), None)
    out.links = int(info["links"]) if info else 0
    missing = [f for f in first.findings if f["code"] == "missing-mesh"]
    if missing:
        out.load_note = (
            "missing mesh (a warning): "
            + _loc_render(missing[0])
            + "; --missing-mesh primitive|drop|error chooses another policy"
        )
    structural = first.status not in WROTE_OUTPUTS and first.stage == "verify"
    if structural:
        # The compile stopped at the first verification, so it built no robot to describe: read
        # it again here for its size and every verifier error (physical ones included).
        _source_defects(robot, out)
    for f in first.findings:
        if f["code"] in PHYSICAL_CODES and str(f["message"]).endswith(PASSED_THROUGH):
            out.defects.append(_render_finding(f))
            out.defect_elements.add(str(f["element"]))
    for target, res in zip(targets, results, strict=True):
        tr = TargetResult(target, "yes", seconds=res.seconds)
        if res.status in WROTE_OUTPUTS:
            tr.report = report_from_json(res.validation) if res.validation else None
        elif structural:
            errors = [f"{f['element']}: {f['message']}" for f in res.findings if f["severity"] == "error"]
            tr.converted, tr.blame = "no", "source"
            # `robodesc compile` stops on structural errors (only physical ones can be let through).
            tr.why = f"source defect, the compiler stops: {errors[0]}" + (
                f" (and {len(errors) - 1} more)" if len(errors) > 1 else ""
            )
        elif res.status in (CRASHED, TIMEOUT):
            tr.converted, tr.blame, tr.why = "no", "robodesc", f"robodesc crashed: {res.error}"
        else:
            tr.converted, tr.blame, tr.why = "no", "target", res.error
        out.targets.append(tr)
    return out


def _source_defects(robot: CorpusRobot, out: RobotResult) -> None:
    from robodesc.frontends.load import load_path
    from robodesc.frontends.options import LoadOptions, MissingMesh
    from robodesc.ir.diagnostics import Severity
    from robodesc.ir.verify import verify

    options = LoadOptions(package_paths=robot.packages, xacro_args=robot.xacro_args, missing_mesh=MissingMesh.WARN)
    ir = load_path(robot.path, options).robot
    out.links = len(ir.links)
    for f in verify(ir):
        if f.severity is Severity.ERROR:
            where = f" (line {f.loc.line})" if f.loc is not None and f.loc.line is not None else ""
            out.defects.append(f"{f.element}: [{f.code}] {f.message}{where}")
            out.defect_elements.add(f.element)


def load_consumers(path: str = CONSUMERS) -> dict[str, dict[str, Any]]:
    """robot -> consumer verdicts, from the consumer benchmarks' results (empty when absent)."""
    if not os.path.exists(path):
        return {}
    with open(path, encoding="utf-8") as handle:
        data = json.load(handle)
    return {str(k): v for k, v in data.items() if isinstance(v, dict)} if isinstance(data, dict) else {}


def load_dynamics(path: str = DYNAMICS) -> dict[str, dict[str, Any]]:
    """robot -> {"dynamics": cell}: which scenarios the engines agree on, from dynamics.json."""
    out: dict[str, dict[str, Any]] = {}
    for robot, res in load_consumers(path).items():
        agreement = res.get("agreement") or {}
        cells = [f"{k.removesuffix('-fixed')} {v}" for k, v in agreement.items() if v != "n/a"]
        verdict = "FAIL" if res.get("status") == "FAIL" else str(res.get("status", "–"))
        text = f"{verdict}: {', '.join(cells)}" if cells else verdict
        out[robot] = {"dynamics": text}
    return out


def consumer_cell(value: Any) -> str:
    if value is None:
        return "–"
    if isinstance(value, bool):
        return "pass" if value else "FAIL"
    if isinstance(value, dict):
        for key in ("status", "verdict", "result", "ok"):
            if key in value:
                return consumer_cell(value[key])
        return "–"
    return _short_path(str(value))


def physx_cell(verdicts: dict[str, Any], column: str) -> str:
    """The compile's verdict with what the tier split it into: a mismatch the check still reports as
    a known one (physx_usd.PENDING_FIXES) passes the compile, and shows here."""
    verdict = consumer_cell(verdicts.get(column))
    parts = [
        f"{what} {verdicts[f'{column}_{what}']}" for what in ("masses", "drives") if f"{column}_{what}" in verdicts
    ]
    return "; ".join([verdict, *(_short_path(p) for p in parts)])


# ---- rendering ---------------------------------------------------------------------------------
def _slug(name: str) -> str:
    return "".join(c if c.isalnum() else "_" for c in name)


def _short_path(text: str) -> str:
    for prefix in sorted({sys.prefix, sys.base_prefix, os.path.dirname(ROOT)}, key=len, reverse=True):
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


def render(
    results: list[RobotResult], targets: list[str], subset: str, consumers: dict[str, dict[str, Any]] | None = None
) -> str:
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
        "independent consumer (URDF: MuJoCo, SDF: Drake, USD: usd-core's UsdPhysics parser, and PhysX where its interpreter exists) and compared with the IR:",
        "masses, centres of mass, inertia tensors, joint types, axes and limits, and forward kinematics",
        "of every link at random configurations; URDF also gets a 0.5 s simulation. See",
        "[validation.md](validation.md) for the checks and tolerances. Errors at machine precision show",
        "as ≤1e-12. *Cause* says whether a failure comes from the **source** (a defect the IR verifier or",
        "the consumer finds in the input: fix the input or compile with `--invalid-inertia repair`) or",
        "from **robodesc** (the output differs from the input: a bug to report). *Converted* `yes*`: a",
        "mesh file the source names is missing (a warning by default; the reference is kept).",
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

    consumers = consumers or {}
    extra = [c for c in CONSUMER_COLUMNS if any(c in v for v in consumers.values())]
    out += [
        "## Robots",
        "",
        "| corpus | robot | links | target | converted | validated | max FK error | max mass / inertia error (rel.) | simulation | note |"
        + "".join(f" {c} |" for c in extra),
        "|---|---|---|---|---|---|---|---|---|---|" + "---|" * len(extra),
    ]
    if extra:
        out[-3:-2] = [
            f"Columns {', '.join(extra)}: the verdicts of those consumers on the robot "
            "(`benchmarks/results/consumers.json`), on its first row.",
            "",
        ]

    def consumer_cells(r: RobotResult) -> str:
        verdicts = consumers.get(f"{r.robot.corpus}/{r.robot.name}", consumers.get(r.robot.name, {}))
        return "".join(
            f" {physx_cell(verdicts, c) if c.startswith('physx') else consumer_cell(verdicts.get(c))} |" for c in extra
        )

    for r in results:
        name = r.robot.name
        if r.load_error:
            out.append(
                f"| {r.robot.corpus} | {name} | – | all | no | – | – | – | – | NOT READ: {_short_path(r.load_error)} |"
                + consumer_cells(r)
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
                + (consumer_cells(r) if t is r.targets[0] else " |" * len(extra))
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
    parser.add_argument("--targets", default="urdf,sdf,usd,mjcf")
    parser.add_argument("--check", action="store_true", help="do not write; exit 1 if the file would change")
    parser.add_argument("--jobs", type=int, help="parallel workers (default: the number of cores)")
    parser.add_argument("--timeout", type=float, default=900.0, help="seconds one robot and target may take")
    parser.add_argument(
        "--workdir", help="keep the compiled robots here; a rerun then redoes only the robots whose files changed"
    )
    args = parser.parse_args(argv)
    os.environ.setdefault("PXR_WORK_THREAD_LIMIT", "1")
    targets = [t for t in args.targets.split(",") if t]
    robots = all_robots(args.shared_corpus)
    if args.subset == "small":
        robots = [r for r in robots if r.name in SMALL]
    out = args.out or os.path.join(
        ROOT, "docs", "corpus-report.md" if args.subset == "all" else "corpus-report-small.md"
    )
    started = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="robodesc-corpus-") as tmp:
        root = args.workdir or tmp
        jobs = make_jobs(robots, targets, root)
        run = run_batch(jobs, root, workers=args.jobs, timeout=args.timeout)
    if run.interrupted:
        print("interrupted", file=sys.stderr)
        return 130
    results = []
    for index, robot in enumerate(robots):
        mine = [run.results[job.id] for job in jobs[index * len(targets) : (index + 1) * len(targets)]]
        res = robot_result(robot, targets, mine)
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
        print(f"{robot.corpus}/{robot.name}: {state} ({per})", flush=True)
    consumers = load_consumers()
    for robot, cells in load_dynamics().items():
        # The row looks up "corpus/name", then "name": join the entry the consumers already have.
        name = robot.split("/", 1)[-1]
        key = name if robot not in consumers and name in consumers else robot
        consumers.setdefault(key, {}).update(cells)
    text = render(results, targets, args.subset, consumers)
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
    from robodesc._files import write_atomic

    write_atomic(out, text)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
