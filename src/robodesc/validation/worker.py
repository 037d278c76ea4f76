"""A consumer in another interpreter: run its worker script there, JSON in and out.

Newton (Python 3.12) and PhysX (ovphysx pins ``packaging<24``) cannot share robodesc's environment,
so their workers run as child processes: one request on standard input, the answer as the last
line of standard output that starts with ``{`` (the engines print their own log lines around it).
"""

from __future__ import annotations

import json
import os
import subprocess
import tempfile
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
    """Run ``script`` with ``python`` on ``request``; ``engine`` names it in the failure.

    The worker starts in a scratch folder, removed after it: an engine's files (MuJoCo, under
    Newton, appends its warnings to MUJOCO_LOG.TXT in the working folder) never land in the user's
    folder. Every path a request holds is absolute."""
    # A relative interpreter path (ROBODESC_NEWTON_PYTHON=venv/bin/python) is the user's folder's.
    python = os.path.abspath(python) if os.sep in python else python
    try:
        with tempfile.TemporaryDirectory(prefix="robodesc-worker-") as scratch:
            done = subprocess.run(
                [python, os.path.abspath(script)],
                input=json.dumps(request),
                capture_output=True,
                text=True,
                timeout=timeout,
                check=False,
                cwd=scratch,
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
