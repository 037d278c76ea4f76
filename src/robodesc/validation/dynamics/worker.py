"""An engine in another interpreter (Newton's Python 3.12 venv, PhysX's own venv): start its worker
file there, one JSON request on standard input, one JSON answer (the last line starting with ``{``)
on standard output. The worker files import nothing of robodesc."""

from __future__ import annotations

import json
import os
import subprocess
from typing import Any


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
