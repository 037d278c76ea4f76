"""The request loop the engine workers share (:mod:`.newton_worker`, :mod:`.physx_worker`).

Standard library only: the workers run in other interpreters, without robodesc installed, and import
this file from their own folder (a script's folder is first on ``sys.path``).
"""

from __future__ import annotations

import json
import math
import sys
import time
import traceback
from collections.abc import Callable
from typing import Any

Scenario = Callable[[dict[str, Any], str, "float | None"], dict[str, Any]]


def serve(engine: str, load: Callable[[], str], scenario: Scenario) -> None:
    """Read the request, run ``scenario(request, name, mu)`` for each scenario named (``mu``: the
    friction an earlier scenario read, for the slide), print the answer. ``load`` imports the engine
    and returns its version; an ImportError there is the answer ``not available``."""
    req = json.loads(sys.stdin.read())
    try:
        version = load()
    except ImportError as exc:
        print(json.dumps({"error": f"not available: {exc}"}))
        return
    runs: list[dict[str, Any]] = []
    for name in req["scenarios"]:
        started = time.perf_counter()
        known = [r["mu"] for r in runs if r.get("mu") is not None]
        try:
            run = scenario(req, name, known[0] if known else None)
        except Exception as exc:  # one scenario's failure is a row, not the end of the others
            detail = traceback.format_exception_only(type(exc), exc)[-1].strip()[:300]
            run = {"scenario": name, "ok": False, "error": detail}
        run["seconds"] = time.perf_counter() - started
        runs.append(run)
    print(json.dumps({engine: version, "runs": runs}))


def slide_run(label: str, mu: float | None, travel: Callable[[float], float]) -> dict[str, Any]:
    """The slide scenario's answer: ``travel(angle)``, the block's distance on a plane tilted to
    tan = 0.7 mu (it must stick) and to 1.3 mu (it must slide), as scenarios.slide_angles."""
    if mu is None:
        return {"scenario": "slide", "ok": False, "error": f"{label} reads no collider from the USD"}
    stick, slide = math.atan(0.7 * mu), math.atan(1.3 * mu)
    return {"scenario": "slide", "ok": True, "error": "", "mu": mu, "stick": travel(stick), "slide": travel(slide)}
