"""Where jobs run: a local process pool (pebble) or Ray tasks. Both run :func:`run_job` and hand
each :class:`JobResult` to ``done`` as it arrives; neither schedules anything itself beyond keeping
as many jobs in flight as there are workers.

A job's timeout, a worker process that dies (a consumer's segfault) and an exception are that
job's result; the other jobs go on. On Ctrl-C the workers are stopped and ``KeyboardInterrupt``
propagates to the driver, which keeps every result already handed over.
"""

from __future__ import annotations

import signal
import time
from collections.abc import Callable, Sequence
from concurrent.futures import TimeoutError as FutureTimeout
from concurrent.futures import as_completed
from typing import Any

from robodesc.batch.jobs import CRASHED, TIMEOUT, Job, JobResult
from robodesc.batch.worker import init_worker, run_job

Done = Callable[[Job, JobResult], None]


def _signal_name(exitcode: int | None) -> str:
    if exitcode is not None and exitcode < 0:
        try:
            return f"killed by {signal.Signals(-exitcode).name}"
        except ValueError:
            pass
    return f"exit code {exitcode}"


def run_local(jobs: Sequence[Job], workers: int, timeout: float | None, done: Done) -> None:
    """A pool of ``workers`` processes (spawned, so each imports robodesc once, free of the driver's
    threads); a worker that times out or dies is replaced."""
    import multiprocessing

    import pebble

    pool: Any = pebble.ProcessPool(
        max_workers=max(1, workers), initializer=init_worker, context=multiprocessing.get_context("spawn")
    )
    try:
        futures: dict[Any, Job] = {pool.schedule(run_job, args=(job,), timeout=timeout): job for job in jobs}
        for future in as_completed(futures):
            job = futures[future]
            try:
                result = future.result()
            except FutureTimeout:
                result = JobResult(job.id, TIMEOUT, seconds=timeout or 0.0, error=f"timed out after {timeout:g} s")
            except pebble.ProcessExpired as exc:
                result = JobResult(job.id, CRASHED, error=f"the worker process died ({_signal_name(exc.exitcode)})")
            except Exception as exc:  # the job could not even be sent or returned (pickling)
                result = JobResult(job.id, CRASHED, error=f"{type(exc).__name__}: {exc}")
            done(job, result)
    except BaseException:
        pool.stop()
        pool.join()
        raise
    pool.close()
    pool.join()


def run_ray(jobs: Sequence[Job], workers: int | None, timeout: float | None, done: Done, address: str | None) -> None:
    """Each job a Ray task running :func:`run_job`. ``address=None`` starts a local Ray with
    ``workers`` CPUs; otherwise it joins that cluster (``auto``, ``ray://HOST:10001``, ``HOST:6379``).
    Inputs and outputs are paths: they must be on storage every node sees."""
    import ray as ray_module

    ray: Any = ray_module
    started_here = not ray.is_initialized()
    if started_here:
        kwargs: dict[str, Any] = {"include_dashboard": False, "log_to_driver": False, "configure_logging": False}
        if address is None:
            kwargs["num_cpus"] = max(1, workers or 1)
        else:
            kwargs["address"] = address
        ray.init(**kwargs)
    task = ray.remote(num_cpus=1, max_retries=0)(_ray_job)
    in_flight = workers or max(1, int(ray.cluster_resources().get("CPU", 1)))
    queue = list(jobs)
    pending: dict[Any, tuple[Job, float]] = {}
    try:
        while queue or pending:
            while queue and len(pending) < in_flight:
                job = queue.pop(0)
                pending[task.remote(job)] = (job, time.monotonic())
            wait = None
            if timeout is not None:
                oldest = min(start for _, start in pending.values())
                wait = max(0.0, oldest + timeout - time.monotonic())
            ready, _ = ray.wait(list(pending), num_returns=1, timeout=wait)
            for ref in ready:
                job, _ = pending.pop(ref)
                done(job, _ray_result(ray, ref, job))
            now = time.monotonic()
            for ref, (job, start) in list(pending.items()):
                if timeout is not None and now - start >= timeout:
                    ray.cancel(ref, force=True)
                    pending.pop(ref)
                    done(job, JobResult(job.id, TIMEOUT, seconds=timeout, error=f"timed out after {timeout:g} s"))
    except BaseException:
        for ref in pending:
            ray.cancel(ref, force=True)
        raise
    finally:
        if started_here:
            ray.shutdown()


def _ray_job(job: Job) -> JobResult:
    import os

    os.environ.setdefault("PXR_WORK_THREAD_LIMIT", "1")
    return run_job(job)


def _ray_result(ray: Any, ref: Any, job: Job) -> JobResult:
    try:
        result: JobResult = ray.get(ref)
        return result
    except ray.exceptions.WorkerCrashedError:
        return JobResult(job.id, CRASHED, error="the worker process died")
    except ray.exceptions.RayError as exc:
        first = str(exc).strip().splitlines()
        return JobResult(job.id, CRASHED, error=f"{type(exc).__name__}: {first[0] if first else ''}")
