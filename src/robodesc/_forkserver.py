"""The fork server ``robodesc batch`` forks its local workers from (a light module: the console
script starts the server before importing anything else of robodesc)."""

from __future__ import annotations

# What the fork server imports before it forks each worker: the per-job function and the
# pipeline behind it, and the CLI, which the console script (the driver's main module) imports
# and a worker's start imports again.
WORKER_PRELOAD = ["robodesc.batch.worker", "robodesc.pipeline", "robodesc.cli"]


def start_worker_server() -> bool:
    """Start the fork server for batch workers (once per process); False where there is none."""
    import multiprocessing
    from multiprocessing import forkserver

    if "forkserver" not in multiprocessing.get_all_start_methods():
        return False  # Windows: workers are spawned
    multiprocessing.get_context("forkserver").set_forkserver_preload(WORKER_PRELOAD)
    forkserver.ensure_running()
    return True
