"""PhysX for USD, in a subprocess: ovphysx (PhysX for USD stages, on CPU) lives in its own
interpreter (:func:`robodesc.validation.physx_python.physx_python`: it cannot share robodesc's
environment). :mod:`.physx_worker` runs there; JSON on its standard input and output, as Newton's.

PhysX reads the USD exactly as written; the worker puts what the scenarios need (gravity, the floor,
the weld or the free root, the home pose and drive targets) in a layer over the file and through
ovphysx's write API, never in the file."""

from __future__ import annotations

import os
from typing import Any

from robodesc.ir.model import Robot
from robodesc.validation.dynamics.result import Run, run_from_json
from robodesc.validation.dynamics.scenarios import Setup
from robodesc.validation.dynamics.worker import call_worker, warp_cache
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
    roots = robot.root_links()
    request = {
        "usd": os.path.abspath(path),
        "root": roots[0].name if roots else "",
        "scenarios": list(scenarios),
        "setup": setup.as_dict(),
    }
    # ovphysx builds warp arrays for its reads: a cache it can write.
    answer = call_worker(python, "physx_worker.py", request, "PhysX", _TIMEOUT, {"WARP_CACHE_PATH": warp_cache()})
    if isinstance(answer, str):
        return answer
    return [run_from_json(ENGINE, kind, raw, setup.effort) for raw in answer["runs"]]
