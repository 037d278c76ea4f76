"""An engine in another interpreter (Newton's Python 3.12 venv, PhysX's own venv): start its worker
file there, one JSON request on standard input, one JSON answer (the last line starting with ``{``)
on standard output. The worker files import nothing of robodesc."""

from __future__ import annotations

import json
import os
import subprocess
from typing import Any

from robodesc.ir.model import Robot
from robodesc.validation.dynamics.result import Run, run_from_json
from robodesc.validation.dynamics.scenarios import Setup


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
    # Warp (Newton's kernels; ovphysx builds warp arrays for its reads) needs a cache it can write.
    answer = call_worker(python, worker, request, label, timeout, {"WARP_CACHE_PATH": warp_cache()})
    if isinstance(answer, str):
        return answer
    return [run_from_json(engine, kind, raw, setup.effort) for raw in answer["runs"]]


def call_worker(
    python: str, worker: str, request: dict[str, Any], engine: str, timeout: float, env: dict[str, str] | None = None
) -> dict[str, Any] | str:
    """The worker's answer, or why there is none (a message naming ``engine``)."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), worker)
    try:
        done = subprocess.run(
            [python, path],
            input=json.dumps(request),
            capture_output=True,
            text=True,
            timeout=timeout,
            check=False,
            env={**os.environ, **(env or {})},
        )
    except subprocess.TimeoutExpired:
        return f"{engine} did not finish in {timeout:g} s"
    lines = [line for line in done.stdout.splitlines() if line.startswith("{")]
    if not lines:
        tail = (done.stderr.strip().splitlines() or ["no output"])[-1]
        return f"{engine} failed (exit {done.returncode}): {tail[:300]}"
    answer: dict[str, Any] = json.loads(lines[-1])
    if "error" in answer:
        return str(answer["error"])
    return answer


def warp_cache() -> str:
    """Where Warp (Newton's, and ovphysx's for its arrays) compiles: ``WARP_CACHE_PATH`` or robodesc's."""
    return os.environ.get("WARP_CACHE_PATH", os.path.join(os.path.expanduser("~/.cache"), "robodesc-warp"))
