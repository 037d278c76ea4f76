"""``-t usd``'s default drive gains: do they hold a robot? (issue 38)

    PYTHONPATH=src python benchmarks/usd_default_gains.py [--robots ur10_robot,panda] [--engines mujoco,physx]

For each robot, ``robodesc validate ROBOT -t usd --dynamics --json`` twice: with the old constant
gains (``--stiffness 100 --damping 1``, every engine given them) and with the default (gains derived
per joint, emit/common/gains.py). Reports each engine's hold drift (the largest |q - q_home| after
1 s, welded base) and worst joint, and whether the engines agree. Writes
``benchmarks/results/usd_default_gains.json`` and prints a Markdown table for docs/dynamics.md.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from typing import Any

from robodesc.validation.corpora import example_robot_data_robots

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "benchmarks", "results", "usd_default_gains.json")
ROBOTS = "ur10_robot,ur5_robot,simple_humanoid,panda,kinova,z1"
GAINS = {"constant 100/1": ["--stiffness", "100", "--damping", "1"], "derived (default)": []}


def run(path: str, engines: str, extra: list[str]) -> dict[str, Any]:
    cmd = [sys.executable, "-m", "robodesc", "validate", path, "-t", "usd", "--dynamics", "--engines", engines]
    env = {**os.environ, "PYTHONPATH": os.path.join(ROOT, "src")}
    started = time.perf_counter()
    done = subprocess.run([*cmd, *extra, "--json"], capture_output=True, text=True, env=env, timeout=1800)
    seconds = time.perf_counter() - started
    try:
        report = json.loads(done.stdout)
    except json.JSONDecodeError:
        return {"error": (done.stderr or done.stdout)[-300:], "seconds": seconds}
    dyn = report.get("dynamics") or {}
    holds = {
        r["engine"]: {"drift": r["drift"], "joint": r["worst_joint"], "ok": r["ok"], "error": r["error"]}
        for r in dyn.get("runs", [])
        if r["scenario"] == "hold-fixed" and r["file"] != "source"
    }
    agree = dyn.get("agreement", {}).get("hold-fixed")
    fails = [c["message"] for c in dyn.get("checks", []) if c["status"] == "fail"]
    return {"holds": holds, "agree": agree, "fails": fails, "seconds": round(seconds, 1)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--robots", default=ROBOTS)
    parser.add_argument("--engines", default="mujoco,physx")
    args = parser.parse_args()
    by_name = {r.name.rsplit("/", 1)[-1]: r for r in example_robot_data_robots()}
    results: dict[str, Any] = {}
    for name in args.robots.split(","):
        robot = by_name[name]
        results[name] = {label: run(robot.path, args.engines, extra) for label, extra in GAINS.items()}
        print(name, json.dumps(results[name]), flush=True)
    with open(OUT, "w") as f:
        json.dump({"engines": args.engines, "robots": results}, f, indent=1, sort_keys=True)
    engines = args.engines.split(",")
    print(f"\n| robot | gains | hold drift (rad) {' / '.join(engines)} | worst joint | engines agree |")
    print("|---|---|---|---|---|")
    for name, by_gains in results.items():
        for label, res in by_gains.items():
            holds = res.get("holds", {})
            drifts = " / ".join(
                f"{holds[e]['drift']:.3g}" if e in holds and holds[e]["drift"] is not None else "–" for e in engines
            )
            worst = next((h["joint"] for h in holds.values() if h["joint"]), "")
            print(f"| {name} | {label} | {drifts} | {worst} | {res.get('agree', res.get('error', ''))} |")


if __name__ == "__main__":
    main()
