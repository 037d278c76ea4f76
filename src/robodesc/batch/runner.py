"""The driver: skip what is unchanged, run the rest, record each result as it arrives, write the
summary (also after Ctrl-C, with what finished)."""

from __future__ import annotations

import json
import os
import signal
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from robodesc.batch import cache
from robodesc.batch.jobs import OK, Job, JobResult
from robodesc.batch.summary import build_summary, to_markdown


@dataclass
class BatchRun:
    summary: dict[str, Any]
    results: dict[str, JobResult] = field(default_factory=dict)
    interrupted: bool = False


class _Progress:
    """A rich progress bar: done/total, outcomes so far, jobs per second and the time left."""

    def __init__(self, total: int, console: Any, enabled: bool, lines: bool = False) -> None:
        self.counts: dict[str, int] = {}
        self.bar: Any = None
        # Piped (a CI log): one plain line per job compiled, instead of a bar nobody sees.
        self.lines = lines and not enabled
        self.total = total
        self.done = 0
        if not enabled or total == 0:
            return
        from rich.progress import (
            BarColumn,
            MofNCompleteColumn,
            Progress,
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )

        self.bar = Progress(
            TextColumn("[bold]batch"),
            BarColumn(),
            MofNCompleteColumn(),
            TextColumn("{task.fields[counts]}"),
            TextColumn("{task.fields[rate]}"),
            TimeElapsedColumn(),
            TextColumn("ETA"),
            TimeRemainingColumn(),
            console=console,
            transient=False,
        )
        self.task = self.bar.add_task("batch", total=total, counts="", rate="")
        self.bar.start()

    def advance(self, result: JobResult) -> None:
        key = result.status + (" (unchanged)" if result.cached else "")
        self.counts[key] = self.counts.get(key, 0) + 1
        self.done += 1
        if self.lines and not result.cached:
            print(
                f"robodesc batch: [{self.done}/{self.total}] {result.status} {result.id}", file=sys.stderr, flush=True
            )
        if self.bar is None:
            return
        task = self.bar.tasks[0]
        speed = task.speed
        self.bar.update(
            self.task,
            advance=1,
            counts=", ".join(f"{n} {k}" for k, n in sorted(self.counts.items())),
            rate=f"{speed:.2f}/s" if speed else "",
        )

    def stop(self) -> None:
        if self.bar is not None:
            self.bar.stop()


def run_batch(
    jobs: Sequence[Job],
    root: str,
    *,
    executor: str = "local",
    workers: int | None = None,
    timeout: float | None = None,
    force: bool = False,
    address: str | None = None,
    progress: bool = False,
    progress_lines: bool = False,
    console: Any = None,
    skipped: Sequence[tuple[str, str]] = (),
) -> BatchRun:
    """Run ``jobs`` (from :func:`robodesc.batch.plan.plan`), writing ``root/summary.json`` and
    ``root/summary.md``. Raises nothing for a job's failure; ``KeyboardInterrupt`` is caught, the
    summary written, and ``BatchRun.interrupted`` set."""
    started = time.perf_counter()
    os.makedirs(root, exist_ok=True)
    fingerprint = cache.build_fingerprint()
    hashes = cache.Hashes()
    keys = {job.id: cache.job_key(job, fingerprint) for job in jobs}
    records = cache.Records(root)
    results: dict[str, JobResult] = {}
    todo: list[Job] = []
    for job in jobs:
        previous = None if force else cache.fresh_result(records, job, keys[job.id], hashes)
        if previous is not None:
            results[job.id] = previous
        else:
            todo.append(job)
    bar = _Progress(len(jobs), console, progress, lines=progress_lines)
    for result in results.values():
        bar.advance(result)

    def done(job: Job, result: JobResult) -> None:
        records.add(job, keys[job.id], result)
        results[job.id] = result
        bar.advance(result)

    interrupted = False
    if todo:
        records.open()
    previous_term = _stop_on_sigterm()
    try:
        if todo:
            if executor == "ray":
                from robodesc.batch.executors import run_ray

                run_ray(todo, workers, timeout, done, address)
            else:
                from robodesc.batch.executors import run_local

                run_local(todo, workers or os.cpu_count() or 1, timeout, done)
    except KeyboardInterrupt:
        interrupted = True
    finally:
        records.close()
        bar.stop()
        if previous_term is not None:
            signal.signal(signal.SIGTERM, previous_term)
    summary = build_summary(
        jobs, results, root, wall_seconds=time.perf_counter() - started, interrupted=interrupted, skipped=skipped
    )
    write_summary(root, summary)
    return BatchRun(summary, results, interrupted)


def _stop_on_sigterm() -> Any:
    """``kill`` stops a batch like Ctrl-C does (workers stopped, summary written); only in the
    main thread, where Python lets a handler be set."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        return None

    def stop(signum: int, frame: Any) -> None:
        raise KeyboardInterrupt

    return signal.signal(signal.SIGTERM, stop)


def write_summary(root: str, summary: dict[str, Any]) -> None:
    from robodesc._files import write_atomic

    write_atomic(os.path.join(root, "summary.json"), json.dumps(summary, indent=2) + "\n")
    write_atomic(os.path.join(root, "summary.md"), to_markdown(summary))


def exit_code(run: BatchRun) -> int:
    """0 every job ok, 1 a validation check failed somewhere, 2 a job failed, 130 interrupted."""
    if run.interrupted:
        return 130
    statuses = {e["status"] for e in run.summary["jobs"]}
    if statuses - {OK, "validation-failed"}:
        return 2
    return 1 if "validation-failed" in statuses else 0
