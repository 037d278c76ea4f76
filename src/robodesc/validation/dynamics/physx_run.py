"""PhysX for USD, in a subprocess: ovphysx (PhysX for USD stages, on CPU) lives in its own
interpreter (:func:`robodesc.validation.physx_python.physx_python`: it cannot share robodesc's
environment). :mod:`.physx_worker` runs there; JSON on its standard input and output, as Newton's.

PhysX reads the USD exactly as written; the worker puts what the scenarios need (gravity, the floor,
the weld or the free root, the home pose and drive targets) in a layer over the file and through
ovphysx's write API, never in the file."""

from __future__ import annotations

from typing import Any

from robodesc.ir.model import Robot
from robodesc.validation.dynamics.result import Run
from robodesc.validation.dynamics.scenarios import Setup
from robodesc.validation.dynamics.worker import run_scenarios
from robodesc.validation.physx_python import physx_python

ENGINE = "physx"
_TIMEOUT = 900.0  # s: a mesh-heavy robot's three scenarios on a shared CPU
NOT_AVAILABLE = (
    "not available: no interpreter with ovphysx (pip install 'robodesc[physx]' in an environment without Ray, "
    "or build the consumer tier's with tests/consumers/run.sh, or set ROBODESC_PHYSX_PYTHON)"
)


def run_file(
    robot: Robot, path: str, kind: str, setup: Setup, options: Any, scenarios: tuple[str, ...]
) -> list[Run] | str:
    python = physx_python(getattr(options, "physx_python", None))
    if python is None:
        return NOT_AVAILABLE
    return run_scenarios(ENGINE, "PhysX", "physx_worker.py", python, robot, path, kind, setup, scenarios, _TIMEOUT)
