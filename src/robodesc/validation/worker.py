"""A consumer in another interpreter: run its worker script there, JSON in and out.

Newton (Python 3.12) and PhysX (ovphysx pins ``packaging<24``) cannot share robodesc's environment,
so their workers run as child processes: one request on standard input, the answer as the last
line of standard output that starts with ``{`` (the engines print their own log lines around it).
"""

from __future__ import annotations

import json
import os
import subprocess
from dataclasses import dataclass, field
from typing import Any


@dataclass
class WorkerAnswer:
    """The worker's JSON answer (None when there is none), why not, and every line it printed."""

    answer: dict[str, Any] | None
    failure: str = ""
    lines: list[str] = field(default_factory=list)


def warp_cache() -> str:
    """Where the workers' Warp kernels are cached (Warp compiles them on first use)."""
    return os.environ.get("WARP_CACHE_PATH", os.path.join(os.path.expanduser("~/.cache"), "robodesc-warp"))


def run_worker(python: str, script: str, request: dict[str, Any], timeout: float, engine: str) -> WorkerAnswer:
    """Run ``script`` with ``python`` on ``request``; ``engine`` names it in the failure."""
    try:
        done = subprocess.run(
            [python, script],
            input=json.dumps(request),
            capture_output=True,
            text=True,
            timeout=timeout,
            check=False,
            env={**os.environ, "WARP_CACHE_PATH": warp_cache()},
        )
    except subprocess.TimeoutExpired:
        return WorkerAnswer(None, f"{engine} did not finish in {timeout:g} s")
    lines = done.stdout.splitlines()
    answers = [line for line in lines if line.startswith("{")]
    if not answers:
        tail = (done.stderr.strip().splitlines() or ["no output"])[-1]
        return WorkerAnswer(None, f"{engine} failed (exit {done.returncode}): {tail[:300]}", lines)
    return WorkerAnswer(json.loads(answers[-1]), "", lines)
