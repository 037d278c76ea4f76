"""Where jobs run: local worker processes (pebble) or Ray tasks. Both run :func:`run_job` and hand
each :class:`JobResult` to ``done`` as it arrives. Ray places its tasks itself; locally, each
worker gets the next job of its own share of the plan (:mod:`robodesc.batch.lanes`), so that
neighbouring jobs, which share meshes, run in the same process.

A job's timeout, a worker process that dies (a consumer's segfault) and an exception are that
job's result; the other jobs go on. On Ctrl-C the workers are stopped and ``KeyboardInterrupt``
propagates to the driver, which keeps every result already handed over.
"""

from __future__ import annotations

import signal
import time
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, wait
from concurrent.futures import TimeoutError as FutureTimeout
from typing import Any

from robodesc._forkserver import worker_context
from robodesc.batch.jobs import CRASHED, TIMEOUT, Job, JobResult
from robodesc.batch.lanes import Lanes
from robodesc.batch.worker import init_worker, prepare_worker, run_job

Done = Callable[[Job, JobResult], None]


def _signal_name(exitcode: int | None) -> str:
    if exitcode is not None and exitcode < 0:
        try:
            return f"killed by {signal.Signals(-exitcode).name}"
        except ValueError:
            pass
    return f"exit code {exitcode}"


def run_local(jobs: Sequence[Job], workers: int, timeout: float | None, done: Done) -> None:
    """``workers`` worker processes, each in a one-process pebble pool of its own (pebble stops a job
    at its timeout and replaces a worker that dies), fed by :class:`Lanes`: neighbouring jobs go to
    the same worker, which keeps the meshes they share."""
    import pebble

    # A pool's manager thread checks its workers every CONSTS.sleep_unit (0.1 s) and a pool only ends
    # at such a check: the last one delayed every batch by up to 0.1 s. 0.02 s ends it sooner for
    # about 0.02 s of the driver's time per worker over a 100-robot batch (0.01 s would double it).
    consts = getattr(getattr(pebble, "common", None), "CONSTS", None)
    tick = getattr(consts, "sleep_unit", None)
    if tick is not None:
        consts.sleep_unit = min(tick, 0.02)  # type: ignore[union-attr]
    lanes = Lanes(len(jobs), workers)
    context = worker_context()
    pools: list[Any] = [
        pebble.ProcessPool(max_workers=1, initializer=init_worker, context=context) for _ in lanes.ranges
    ]
    running: dict[Any, tuple[int, Job]] = {}

    def feed(lane: int, ahead: bool = False) -> None:
        index = lanes.take(lane, ahead)
        if index is not None:
            job = jobs[index]
            # pebble counts the timeout from the moment the worker starts the job, not from here.
            running[pools[lane].schedule(run_job, args=(job,), timeout=timeout)] = (lane, job)

    try:
        # Up to two jobs per worker: the next one waits in its pool's queue, so that a worker goes
        # on as soon as it has sent a result instead of idling while the driver records it and
        # sends another (about 4 ms a job).
        for lane in range(len(pools)):
            feed(lane)
        for lane in range(len(pools)):
            feed(lane, ahead=True)
        while running:
            finished, _ = wait(running, return_when=FIRST_COMPLETED)
            for future in finished:
                lane, job = running.pop(future)
                done(job, _local_result(future, job, timeout))
                # Its queued job (if any) is running now: queue the next, else (nothing queued,
                # the worker is idle) give it one, stolen if need be.
                queued = any(other == lane for other, _ in running.values())
                feed(lane, ahead=queued)
    finally:
        # Every job has its result (or the batch is being interrupted): stop all the pools, then
        # wait for them. Each pool's manager notices at its next tick; closing and joining them
        # one after another would wait a tick once per worker.
        for pool in pools:
            pool.stop()
        for pool in pools:
            pool.join()
        if tick is not None:
            consts.sleep_unit = tick  # type: ignore[union-attr]


def _local_result(future: Any, job: Job, timeout: float | None) -> JobResult:
    import pebble

    try:
        result: JobResult = future.result()
        return result
    except FutureTimeout:
        return JobResult(job.id, TIMEOUT, seconds=timeout or 0.0, error=f"timed out after {timeout:g} s")
    except pebble.ProcessExpired as exc:
        return JobResult(job.id, CRASHED, error=f"the worker process died ({_signal_name(exc.exitcode)})")
    except Exception as exc:  # the job could not even be sent or returned (pickling)
        return JobResult(job.id, CRASHED, error=f"{type(exc).__name__}: {exc}")


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
    prepare_worker()  # once per Ray worker process: it keeps what it set up for the next task
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
