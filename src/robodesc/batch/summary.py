"""The batch's summary: JSON (``summary.json``, or standard output with ``--json``), Markdown
(``summary.md``) and the final table on the terminal.

Jobs are listed in plan order, whatever order they finished in, and paths are relative to the
output folder, so that two runs of the same batch (on a local pool or on Ray) give the same summary
apart from the measured times (``seconds``, ``wall_seconds``) and which jobs were ``cached``.
"""

from __future__ import annotations

import os
import sys
from collections import Counter
from collections.abc import Mapping, Sequence
from typing import Any

from robodesc.batch.jobs import OUTCOMES, Job, JobResult

NOT_RUN = "not-run"  # the batch was interrupted before this job finished
SEVERITIES = ("error", "warning", "info")


def _rel(path: str, root: str) -> str:
    rel = os.path.relpath(path, root)
    return rel.replace(os.sep, "/")


def _validation(result: JobResult, validate: bool) -> str | None:
    if result.validation is not None:
        return "pass" if result.validation.get("ok") else "fail"
    if result.status in ("ok", "validation-failed"):
        return "off" if not validate else "none"
    return None


def job_entry(job: Job, result: JobResult | None, root: str) -> dict[str, Any]:
    if result is None:
        result = JobResult(job.id, NOT_RUN)
    severities = Counter(str(f.get("severity", "")) for f in result.findings)
    kinds = Counter(str(f.get("code", "")) for f in result.findings)
    return {
        "id": job.id,
        "input": job.input,
        "target": job.target,
        "variant": job.variant,
        "status": result.status,
        "cached": result.cached,
        "error": result.error,
        "stage": result.stage,
        "findings": {s: severities.get(s, 0) for s in SEVERITIES},
        "finding_kinds": dict(sorted(kinds.items())),
        "validation": _validation(result, job.options.validate),
        "seconds": round(result.seconds, 3),
        "output": _rel(job.output, root),
        "files": {role: _rel(path, root) for role, path in sorted(result.files.items())},
        "robot": dict(sorted(result.robot.items())) if result.robot else None,
    }


def build_summary(
    jobs: Sequence[Job],
    results: Mapping[str, JobResult],
    root: str,
    *,
    wall_seconds: float,
    interrupted: bool,
    skipped: Sequence[tuple[str, str]] = (),
) -> dict[str, Any]:
    from robodesc._version import __version__

    entries = [job_entry(job, results.get(job.id), root) for job in jobs]
    by_outcome = Counter(e["status"] for e in entries)
    kinds: Counter[str] = Counter()
    severities: Counter[str] = Counter()
    for e in entries:
        kinds.update(e["finding_kinds"])
        severities.update(e["findings"])
    return {
        "robodesc": __version__,
        "interrupted": interrupted,
        "totals": {
            "jobs": len(entries),
            "by_outcome": {o: by_outcome.get(o, 0) for o in (*OUTCOMES, NOT_RUN)},
            "cached": sum(1 for e in entries if e["cached"]),
            "findings": {s: severities.get(s, 0) for s in SEVERITIES},
            "by_finding_kind": dict(sorted(kinds.items())),
            "validation": dict(sorted(Counter(str(e["validation"]) for e in entries if e["validation"]).items())),
            "seconds": round(sum(e["seconds"] for e in entries), 3),
            "wall_seconds": round(wall_seconds, 3),
        },
        "jobs": entries,
        # Files of the input folders that are not jobs, and why (named pipes, Python without
        # --run-python, links to folders, files that hold no robot).
        "skipped": [{"path": path, "why": why} for path, why in skipped],
    }


def _cell(text: Any) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def to_markdown(summary: Mapping[str, Any]) -> str:
    totals = summary["totals"]
    lines = [
        "# robodesc batch summary",
        "",
        f"robodesc {summary['robodesc']}; {totals['jobs']} jobs"
        + (" (interrupted: jobs marked not-run did not finish)" if summary["interrupted"] else "")
        + f"; {totals['cached']} unchanged since their last run (skipped);"
        f" {totals['wall_seconds']:.1f} s wall time, {totals['seconds']:.1f} s in jobs.",
        "",
        "| outcome | jobs |",
        "|---|---|",
    ]
    lines += [f"| {name} | {count} |" for name, count in totals["by_outcome"].items() if count]
    lines += ["", "| finding kind | count |", "|---|---|"]
    lines += [f"| {_cell(kind)} | {count} |" for kind, count in totals["by_finding_kind"].items()] or ["| – | 0 |"]
    if summary.get("skipped"):
        lines += ["", "| skipped | why |", "|---|---|"]
        lines += [f"| {_cell(s['path'])} | {_cell(s['why'])} |" for s in summary["skipped"]]
    lines += [
        "",
        "| job | input | target | status | errors | warnings | infos | validation | s | outputs | message |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for e in summary["jobs"]:
        f = e["findings"]
        status = e["status"] + (" (unchanged)" if e["cached"] else "")
        outputs = ", ".join(e["files"].values()) if e["files"] else "–"
        lines.append(
            f"| {_cell(e['id'])} | {_cell(e['input'])} | {e['target']} | {status} | {f['error']} | {f['warning']} | "
            f"{f['info']} | {e['validation'] or '–'} | {e['seconds']:.2f} | {_cell(outputs)} | {_cell(e['error'])} |"
        )
    return "\n".join(lines) + "\n"


def print_table(summary: Mapping[str, Any], console: Any, limit: int = 20) -> None:
    """Counts by outcome, then the jobs that did not succeed (the first ``limit``), then one closing
    line. On a terminal as tables; piped, as plain lines that are never wrapped (a log keeps whole
    paths and messages on their lines)."""
    totals = summary["totals"]
    counts = [(name, count) for name, count in totals["by_outcome"].items() if count]
    if totals["cached"]:
        counts.append(("(unchanged, skipped)", totals["cached"]))
    bad = [e for e in summary["jobs"] if e["status"] not in ("ok",)]
    rows = [(e["id"], e["status"], _message(e)) for e in bad[:limit]]
    heading = "jobs that did not succeed" + (f" (first {limit} of {len(bad)})" if len(bad) > limit else "")
    closing = f"robodesc batch: {totals['jobs']} jobs in {totals['wall_seconds']:.1f} s"
    skipped = summary.get("skipped") or []
    if skipped:
        closing += (
            f"; skipped {len(skipped)} file(s): "
            + "; ".join(f"{s['path']} ({s['why']})" for s in skipped[:limit])
            + (" ..." if len(skipped) > limit else "")
        )
    if console.is_terminal:
        _tables(console, counts, heading, rows)
    else:
        for name, count in counts:
            print(f"{name}: {count}", file=sys.stderr)
        if rows:
            print(f"{heading}:", file=sys.stderr)
            for job, status, message in rows:
                print(f"  {job}  {status}  {message}".rstrip(), file=sys.stderr)
    print(closing, file=sys.stderr)


def _message(entry: Mapping[str, Any]) -> str:
    return str(entry["error"] or ("a validation check failed" if entry["status"] == "validation-failed" else ""))


def _tables(console: Any, counts: list[tuple[str, int]], heading: str, rows: list[tuple[str, str, str]]) -> None:
    from rich.table import Table

    table = Table()
    table.add_column("outcome")
    table.add_column("jobs", justify="right")
    for name, count in counts:
        table.add_row(name, str(count))
    console.print(table)
    if not rows:
        return
    failed = Table(title=heading)
    for column in ("job", "status", "message"):
        failed.add_column(column, overflow="fold")
    for row in rows:
        failed.add_row(*row)
    console.print(failed)
