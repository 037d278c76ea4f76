"""Newton for USD, in a subprocess: Newton lives in its own interpreter (the consumer tier's Python
3.12 venv, ``tests/consumers/run.sh``), and its import (warp, its kernels) costs seconds, paid only
when Newton is asked for. :mod:`.newton_worker` runs there; JSON on its standard input and output."""

from __future__ import annotations

import os
from typing import Any

from robodesc.ir.model import Robot
from robodesc.validation.dynamics.result import Run
from robodesc.validation.dynamics.scenarios import Setup
from robodesc.validation.dynamics.worker import run_scenarios

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
    return run_scenarios(ENGINE, "Newton", "newton_worker.py", python, robot, path, kind, setup, scenarios, _TIMEOUT)
