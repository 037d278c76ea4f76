"""``validate --dynamics`` over the corpus: do MuJoCo (URDF), Drake (SDF) and Newton (USD) agree?

    PYTHONPATH=src python benchmarks/dynamics_corpus.py [--subset erd] [--jobs 2] [--robots a1,go1]

One ``robodesc validate ROBOT -t usd --dynamics --engines mujoco,drake,newton --json`` per robot
(the CLI a user runs: its wall time is the time reported), two at a time by default. Writes
``benchmarks/results/dynamics.json`` (robot -> agreement per scenario, failures, seconds), which
``corpus_report.py`` shows as its ``dynamics`` column, and prints a summary for docs/dynamics.md.
Default subset ``erd``: Quad-SDK and example-robot-data (71 robots; icub-models and the Stretch
variants repeat the same robots and fit no 30-minute budget on 2 cores).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from robodesc.validation.corpora import CorpusRobot, all_robots

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "benchmarks", "results", "dynamics.json")
ENGINES = "mujoco,drake,newton"


def run_one(
    robot: CorpusRobot, engines: str, timeout: float, target: str = "usd", src: str = os.path.join(ROOT, "src")
) -> dict[str, Any]:
    """``src``: the robodesc tree that runs (another checkout's, for a before/after)."""
    cmd = [sys.executable, "-m", "robodesc", "validate", robot.path, "-t", target, "--dynamics"]
    cmd += ["--engines", engines] if engines else []
    cmd += ["--json"]
    for name, path in robot.packages.items():
        cmd += ["--package", f"{name}={path}"]
    for name, value in robot.xacro_args.items():
        cmd += ["--arg", f"{name}={value}"]
    env = {**os.environ, "PYTHONPATH": src}
    started = time.perf_counter()
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env, check=False)
    except subprocess.TimeoutExpired:
        return {"status": "timeout", "seconds": timeout}
    wall = time.perf_counter() - started
    try:
        doc = json.loads(done.stdout)
    except json.JSONDecodeError:
        tail = (done.stderr.strip().splitlines() or ["no output"])[-1]
        return {"status": f"error: {tail[:200]}", "seconds": round(wall, 2)}
    dyn = doc.get("dynamics")
    if dyn is None:
        return {"status": "not run (the compile failed)", "seconds": round(wall, 2), "exit": done.returncode}
    spent = dyn["info"].get("engine_seconds", {})
    agreement = dyn["agreement"]
    problems = [
        f"{c['status']} {c['name']} {c['element']}: {c['message']}"
        for c in dyn["checks"]
        if c["status"] in ("fail", "warn")
    ]
    return {
        "status": "ok" if dyn["ok"] else "FAIL",
        "agreement": agreement,
        "dof": doc.get("summary", {}).get("dof") if doc.get("summary") else None,
        "seconds": round(wall, 2),
        "seconds_without_newton": round(wall - spent.get("newton", 0.0), 2),
        "engine_seconds": spent,
        "problems": problems,
        "runs": dyn["runs"],
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--subset", choices=("erd", "all"), default="erd")
    parser.add_argument("--robots", default="", help="comma-separated substrings of corpus names")
    parser.add_argument("--exact", action="store_true", help="--robots names whole corpus names, in that order")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--engines", default=ENGINES)
    parser.add_argument("--timeout", type=float, default=600.0)
    parser.add_argument("--out", default=OUT)
    parser.add_argument("--target", default="usd", help="the target validate checks (usd: Newton reads it)")
    args = parser.parse_args(argv)
    robots = all_robots(os.path.join(ROOT, "..", "shared", "corpus"))
    if args.subset == "erd":
        robots = [r for r in robots if r.corpus in ("quadsdk", "example-robot-data")]
    if args.robots:
        wanted = [w for w in args.robots.split(",") if w]
        if args.exact:
            by_name = {r.name: r for r in robots}
            robots = [by_name[w] for w in wanted if w in by_name]
        else:
            robots = [r for r in robots if any(w in r.name for w in wanted)]
    results: dict[str, Any] = {}
    started = time.perf_counter()
    with ThreadPoolExecutor(args.jobs) as pool:
        futures = {
            f"{r.corpus}/{r.name}": pool.submit(run_one, r, args.engines, args.timeout, args.target) for r in robots
        }
        for key, future in futures.items():
            results[key] = future.result()
            res = results[key]
            print(f"{key}: {res['status']} {res.get('agreement', '')} {res['seconds']} s", flush=True)
            _write(results, args.out)  # after every robot: a long run cut off keeps what it measured
    print(f"{len(results)} robots in {time.perf_counter() - started:.0f} s; wrote {args.out}")
    return 0


def _write(results: dict[str, Any], out: str) -> None:
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    with open(out, "w", encoding="utf-8") as fh:
        json.dump(results, fh, indent=1, sort_keys=True)


if __name__ == "__main__":
    sys.exit(main())
