"""The fork server ``robodesc batch`` forks its local workers from (a light module: the console
script starts the server before importing anything else of robodesc)."""

from __future__ import annotations

from typing import Any

# What the fork server imports before it forks each worker: the per-job function and the
# pipeline behind it, and the CLI, which the console script (the driver's main module) imports
# and a worker's start imports again.
WORKER_PRELOAD = ["robodesc.batch.worker", "robodesc.pipeline", "robodesc.cli"]


def worker_context() -> Any:
    """Where local workers come from: a fork server, one clean, single-threaded process that has
    imported robodesc once (a fork of the driver would copy its threads' locks); spawned
    processes, each importing robodesc for itself, where there is no fork server (Windows)."""
    import multiprocessing

    if "forkserver" not in multiprocessing.get_all_start_methods():
        return multiprocessing.get_context("spawn")
    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload(WORKER_PRELOAD)
    return context


def start_worker_server() -> None:
    """Start the fork server now (once per process; nothing where workers are spawned), so that
    its imports overlap the driver's own start and planning instead of delaying the first job."""
    from multiprocessing import forkserver

    if worker_context().get_start_method() == "forkserver":
        forkserver.ensure_running()
