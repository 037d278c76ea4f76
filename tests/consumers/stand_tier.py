"""The default-spawn check over the corpus: does each robot's Isaac folder stand from its defaults?

    python tests/consumers/stand_tier.py --envs ~/.cache/robodesc-consumers [--robots go1,spirit]
        [--src path/to/other/robodesc/src --label before --spawn-z 0.6]

Compiles every corpus robot with ``--isaac-sim`` (``--no-fix-base`` for the floating ones, as
run_tier.py decides) with default flags otherwise, then runs stand_check.py on all folders in one
Newton process (SolverMuJoCo, 1 s at 200 Hz, a ground plane). ``--src`` compiles with another
robodesc tree (the "before" of docs/isaac.md's table); ``--spawn-z`` overrides the spawn height of
floating robots (the old modules spawned at the origin, inside the ground). Results:
``benchmarks/results/stand_<label>.json`` and a count per verdict on stdout.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from run_tier import FLOATING, _compile_flags  # noqa: E402


def compile_one(robot: object, src: str, work: str) -> dict[str, object]:
    name = str(robot.name)  # type: ignore[attr-defined]
    folder = os.path.join(work, re.sub(r"[^A-Za-z0-9_.-]+", "_", name))
    floating = bool(FLOATING.search(name))
    flags = _compile_flags(robot) + (["--no-fix-base"] if floating else [])  # type: ignore[arg-type]
    cmd = [
        sys.executable,
        "-m",
        "robodesc",
        "compile",
        str(robot.path),
        "--isaac-sim",
        "-o",
        folder,
        "-q",
        "--no-validate",
        *flags,
    ]  # type: ignore[attr-defined]
    env = {**os.environ, "PYTHONPATH": src}
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600, check=False)
    if proc.returncode != 0 and "--invalid-inertia repair" in proc.stderr + proc.stdout:
        proc = subprocess.run(
            [*cmd, "--invalid-inertia", "repair"], capture_output=True, text=True, env=env, timeout=600, check=False
        )
    return {"name": name, "folder": folder, "floating": floating, "rc": proc.returncode, "error": proc.stderr[-300:]}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--envs", required=True)
    ap.add_argument("--robots", default=None)
    ap.add_argument("--src", default=os.path.join(ROOT, "src"))
    ap.add_argument("--label", default="after")
    ap.add_argument("--spawn-z", type=float, default=None)
    ap.add_argument("--jobs", type=int, default=2)
    args = ap.parse_args(argv)
    sys.path.insert(0, os.path.join(ROOT, "src"))
    from robodesc.validation.corpora import all_robots

    robots = all_robots(os.path.join(os.path.dirname(ROOT), "shared", "corpus"))
    if args.robots:
        robots = [r for r in robots if any(w in r.name for w in args.robots.split(","))]
    work = os.path.join(args.envs, "work_stand", args.label)
    os.makedirs(work, exist_ok=True)
    with ThreadPoolExecutor(args.jobs) as pool:
        compiled = list(pool.map(lambda r: compile_one(r, os.path.abspath(args.src), work), robots))
    cases = [
        {"name": c["name"], "folder": c["folder"], "spawn_z": args.spawn_z if c["floating"] else None}
        for c in compiled
        if c["rc"] == 0
    ]
    cases_path = os.path.join(work, "cases.json")
    with open(cases_path, "w", encoding="utf-8") as f:
        json.dump(cases, f, indent=1)
    out = os.path.join(work, "stand.json")
    subprocess.run(
        [
            os.path.join(args.envs, "newton", "bin", "python"),
            os.path.join(HERE, "stand_check.py"),
            "--cases",
            cases_path,
            "--out",
            out,
        ],
        check=False,
    )
    with open(out, encoding="utf-8") as f:
        stood = json.load(f)
    results = {}
    for c in compiled:
        r = stood.get(c["name"], {"status": f"fail: not converted ({c['error'].strip().splitlines()[-1:] or ''})"})
        results[c["name"]] = {"floating": c["floating"], **r}
    final = os.path.join(ROOT, "benchmarks", "results", f"stand_{args.label}.json")
    with open(final, "w", encoding="utf-8") as f:
        json.dump(results, f, indent=1, default=str)
        f.write("\n")
    for kind in (True, False):
        group = {k: v for k, v in results.items() if v["floating"] is kind}
        ok = sum(1 for v in group.values() if v["status"] == "pass")
        print(f"{'floating' if kind else 'fixed'}: {ok}/{len(group)} pass")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
