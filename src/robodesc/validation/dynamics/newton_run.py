"""Newton for USD, in a subprocess: Newton lives in its own interpreter (the consumer tier's Python
3.12 venv, ``tests/consumers/run.sh``), and its import (warp, its kernels) costs seconds, paid only
when Newton is asked for. :mod:`.newton_worker` runs there; JSON on its standard input and output."""

from __future__ import annotations

import json
import os
import subprocess
from typing import Any

from robodesc.ir.model import Robot
from robodesc.validation.dynamics.result import Run, settle_time
from robodesc.validation.dynamics.scenarios import Setup

ENGINE = "newton"
_TIMEOUT = 600.0  # s: a first run compiles warp kernels


def newton_python(given: str | None = None) -> str | None:
    """The interpreter that has Newton: given, ``ROBODESC_NEWTON_PYTHON``, or the consumer tier's."""
    envs = os.environ.get("ROBODESC_CONSUMERS_DIR", os.path.expanduser("~/.cache/robodesc-consumers"))
    for candidate in (given, os.environ.get("ROBODESC_NEWTON_PYTHON"), os.path.join(envs, "newton", "bin", "python")):
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
    return None


def run_file(
    robot: Robot, path: str, kind: str, setup: Setup, options: Any, scenarios: tuple[str, ...]
) -> list[Run] | str:
    python = newton_python(getattr(options, "newton_python", None))
    if python is None:
        return (
            "not available: no Newton interpreter (build it with tests/consumers/run.sh, or set ROBODESC_NEWTON_PYTHON)"
        )
    roots = robot.root_links()
    request = {
        "usd": os.path.abspath(path),
        "root": roots[0].name if roots else "",
        "scenarios": list(scenarios),
        "setup": setup.as_dict(),
    }
    worker = os.path.join(os.path.dirname(os.path.abspath(__file__)), "newton_worker.py")
    try:
        done = subprocess.run(
            [python, worker],
            input=json.dumps(request),
            capture_output=True,
            text=True,
            timeout=_TIMEOUT,
            check=False,
            env={**os.environ, "WARP_CACHE_PATH": os.environ.get("WARP_CACHE_PATH", _warp_cache())},
        )
    except subprocess.TimeoutExpired:
        return f"Newton did not finish in {_TIMEOUT:g} s"
    lines = [line for line in done.stdout.splitlines() if line.startswith("{")]
    if not lines:
        tail = (done.stderr.strip().splitlines() or ["no output"])[-1]
        return f"Newton failed (exit {done.returncode}): {tail[:300]}"
    answer = json.loads(lines[-1])
    if "error" in answer:
        return str(answer["error"])
    return [_run(kind, raw) for raw in answer["runs"]]


def _warp_cache() -> str:
    return os.path.join(os.path.expanduser("~/.cache"), "robodesc-warp")


def _run(kind: str, raw: dict[str, Any]) -> Run:
    run = Run(ENGINE, kind, str(raw["scenario"]), ok=bool(raw.get("ok")), error=str(raw.get("error", "")))
    for key in ("drift", "height", "tilt", "mu", "stick", "slide", "mass"):
        value = raw.get(key)
        setattr(run, key, None if value is None else float(value))
    run.worst_joint = str(raw.get("worst_joint", ""))
    run.seconds = float(raw.get("seconds", 0.0))
    run.final_q = {str(k): float(v) for k, v in (raw.get("final_q") or {}).items()}
    run.trajectory = [(float(t), {str(k): float(v) for k, v in q.items()}) for t, q in raw.get("trajectory", [])]
    if raw.get("heights"):
        run.settle = settle_time([(float(t), float(z)) for t, z in raw["heights"]])
    return run
