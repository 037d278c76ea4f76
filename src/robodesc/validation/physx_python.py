"""Where PhysX runs: the interpreter that has ``ovphysx`` (NVIDIA's PhysX for USD stages, on CPU).

ovphysx 0.7 pins ``packaging<24`` while Ray (robodesc's batch executor and test extra) needs
``packaging>=24.2``, so the two cannot share one environment: PhysX normally lives in its own venv
(the consumer tier's ``physx/``, built by ``tests/consumers/run.sh``) and robodesc talks to it
through a worker process, as it does with Newton. An interpreter that has ovphysx itself (a user
who installed ``robodesc[physx]`` without Ray) is used directly.
"""

from __future__ import annotations

import importlib.util
import os
import sys


def consumers_dir() -> str:
    """The consumer tier's environments: ``ROBODESC_CONSUMERS_DIR`` or ``~/.cache/robodesc-consumers``."""
    return os.environ.get("ROBODESC_CONSUMERS_DIR", os.path.expanduser("~/.cache/robodesc-consumers"))


def physx_python(given: str | None = None) -> str | None:
    """The interpreter that has ovphysx: ``given``, ``ROBODESC_PHYSX_PYTHON``, this one when it has
    ovphysx, else the consumer tier's ``physx`` venv; None when there is none."""
    here = sys.executable if importlib.util.find_spec("ovphysx") is not None else None
    tier = os.path.join(consumers_dir(), "physx", "bin", "python")
    for candidate in (given, os.environ.get("ROBODESC_PHYSX_PYTHON"), here, tier):
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
    return None
