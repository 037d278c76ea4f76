"""An engine in another interpreter (Newton's Python 3.12 venv, PhysX's own venv): start its worker
file there, one JSON request on standard input, one JSON answer (the last line starting with ``{``)
on standard output. The worker files import nothing of robodesc."""

from __future__ import annotations

import os
from typing import Any

from robodesc.ir.model import Robot
from robodesc.validation.dynamics.result import Run, run_from_json
from robodesc.validation.dynamics.scenarios import Setup
from robodesc.validation.worker import run_worker


def run_scenarios(
    engine: str,
    label: str,
    worker: str,
    python: str,
    robot: Robot,
    path: str,
    kind: str,
    setup: Setup,
    scenarios: tuple[str, ...],
    timeout: float,
) -> list[Run] | str:
    """The runner contract of :mod:`.run` for an engine whose ``worker`` file runs in ``python``:
    the runs, or why there are none. Both workers take the same request."""
    roots = robot.root_links()
    request = {
        "usd": os.path.abspath(path),
        "root": roots[0].name if roots else "",
        "scenarios": list(scenarios),
        "setup": setup.as_dict(),
    }
    answer = call_worker(python, worker, request, label, timeout)
    if isinstance(answer, str):
        return answer
    return [run_from_json(engine, kind, raw, setup.effort) for raw in answer["runs"]]


def call_worker(python: str, worker: str, request: dict[str, Any], engine: str, timeout: float) -> dict[str, Any] | str:
    """The answer of ``worker`` (a file beside this one), or why there is none (naming ``engine``);
    the consumers' runner (:func:`robodesc.validation.worker.run_worker`) starts it."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), worker)
    done = run_worker(python, path, request, timeout, engine)
    if done.answer is None:
        return done.failure
    if "error" in done.answer:
        return str(done.answer["error"])
    return done.answer
