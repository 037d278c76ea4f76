"""The corpus in Isaac Lab 3.0 kit-less (CPU): does every robot's Isaac folder stand from its defaults?

    python tests/consumers/isaaclab_tier.py --envs ~/.cache/robodesc-consumers [--robots go1,spirit]
        [--src path/to/other/robodesc/src --label before]

Run by ``tests/consumers/run.sh`` when ``ROBODESC_CONSUMERS_ISAACLAB=1``. Compiles every corpus robot
with ``--isaac-sim`` (``--no-fix-base`` for the floating ones, as run_tier.py decides) and default
flags otherwise, then runs isaaclab_check.py on the folders in the Isaac Lab environment: each
module's ``ROBOT_CFG`` spawned at its own ``init_state`` above a ground box, position targets held at
the default pose, 1 s at 200 Hz (MJWarp, ``implicitfast``, CPU). A floating robot must keep up·z >=
0.9 at every step, a fixed one must keep every joint within 0.1 rad of its start, and stiffness,
damping and armature must read back as the module wrote them. ``--src`` compiles with another
robodesc tree (the "before" of docs/isaac.md). Results: the ``label`` entry of
``benchmarks/results/isaaclab_corpus.json`` and the table in ``isaaclab_corpus.md``.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from typing import Any

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from isaaclab_check import THROUGH_GROUND  # noqa: E402
from stand_tier import compile_one  # noqa: E402

RESULTS = os.path.join(ROOT, "benchmarks", "results", "isaaclab_corpus.json")
STEPS = 200  # 1 s at 200 Hz


def collected(work: str) -> dict[str, Any]:
    """What a run of this label has checked so far: the finished processes' results and the one
    still running (or stopped)."""
    found: dict[str, Any] = {}
    for name in ("isaaclab_done.json", "isaaclab_part.json"):
        path = os.path.join(work, name)
        if os.path.isfile(path):
            with open(path, encoding="utf-8") as f:
                found.update(json.load(f))
    return found


def check_all(envs: str, cases: list[dict[str, Any]], work: str, resume: bool = False) -> dict[str, Any]:
    """isaaclab_check.py over ``cases`` in as few processes as it takes: a process that dies (a
    segfault in a solver) loses only the robot it was on, which is recorded, and the rest go on.
    Results accumulate in ``work/isaaclab_done.json``; ``resume`` keeps those and runs the rest.
    Floating robots run first: they are what the tier is for."""
    python = os.path.join(envs, "isaaclab", "bin", "python")
    done_path = os.path.join(work, "isaaclab_done.json")
    done: dict[str, Any] = {}
    if resume and os.path.isfile(done_path):
        with open(done_path, encoding="utf-8") as f:
            done = json.load(f)
    todo = sorted((c for c in cases if c["name"] not in done), key=lambda c: not c.get("floating", False))
    while todo:
        cases_path = os.path.join(work, "isaaclab_cases.json")
        out = os.path.join(work, "isaaclab_part.json")
        with open(cases_path, "w", encoding="utf-8") as f:
            json.dump(todo, f, indent=1)
        if os.path.exists(out):
            os.remove(out)
        cmd = [python, os.path.join(HERE, "isaaclab_check.py"), "--cases", cases_path, "--out", out]
        cmd += ["--module-spawn", "--steps", str(STEPS)]
        try:
            proc = subprocess.run(cmd, capture_output=True, text=True, timeout=300 * len(todo), check=False)
            tail = (proc.stderr or proc.stdout)[-300:]
        except subprocess.TimeoutExpired:
            tail = "timed out"
        part: dict[str, Any] = {}
        if os.path.isfile(out):
            with open(out, encoding="utf-8") as f:
                part = json.load(f)
        done.update(part)
        todo = [c for c in todo if c["name"] not in done]
        if todo:  # the first one left is the one the process died on
            crashed = todo.pop(0)
            done[crashed["name"]] = {"status": f"fail: Isaac Lab process died ({tail.strip().splitlines()[-1:]})"}
        with open(done_path, "w", encoding="utf-8") as f:
            json.dump(done, f)
    return {c["name"]: done[c["name"]] for c in cases if c["name"] in done}


def _compiled(robot: Any, src: str, work: str, reuse: bool) -> dict[str, Any]:
    """compile_one, or the record of an earlier compile of this label (``--reuse``)."""
    record = os.path.join(work, re.sub(r"[^A-Za-z0-9_.-]+", "_", str(robot.name)) + ".compile.json")
    if reuse and os.path.isfile(record):
        with open(record, encoding="utf-8") as f:
            found: dict[str, Any] = json.load(f)
        return found
    result = compile_one(robot, src, work)
    with open(record, "w", encoding="utf-8") as f:
        json.dump(result, f)
    return result


def rejudge(result: dict[str, Any]) -> dict[str, Any]:
    """A result checked with the first rule for a fall through the ground (root below 0 m, which
    failed Tiago's base_footprint resting at -0.000 m), judged with today's (below -0.25 m)."""
    status = str(result.get("status", ""))
    z = (result.get("checks", {}).get("root_pos") or [0.0, 0.0, 0.0])[2]
    if not status.startswith("fail: ") or z < THROUGH_GROUND:
        return result
    problems = [p for p in status[len("fail: ") :].split("; ") if not p.startswith("fell through the ground")]
    return {**result, "status": "fail: " + "; ".join(problems) if problems else "pass"}


def markdown(everything: dict[str, dict[str, Any]]) -> str:
    lines = [
        "# Isaac Lab 3.0 kit-less: the corpus spawned from its default modules",
        "",
        "Written by `tests/consumers/isaaclab_tier.py` (docs/isaac.md, 'Defaults that stand'). Each robot",
        "is compiled with `--isaac-sim` (`--no-fix-base` for floating robots) and default flags; its",
        "module's `ROBOT_CFG` spawns at its own `init_state` on CPU (Newton, MJWarp `implicitfast`), targets",
        "held at the default pose, 1 s at 200 Hz. Floating: up·z >= 0.9 at every step; fixed: every joint",
        "within 0.1 rad of its start; gains read back (relative 1e-4).",
        "",
    ]
    described = everything.get("_labels", {})
    labels = [la for la in everything if not la.startswith("_")]
    lines += [f"- `{la}`: {described[la]}" for la in labels if la in described]
    lines += [""] if described else []
    for label in labels:
        results = everything[label]
        for kind, word in ((True, "floating robots upright for 1 s"), (False, "fixed robots within 0.1 rad")):
            group = [r for r in results.values() if r.get("floating") is kind]
            ok = sum(1 for r in group if r["status"] == "pass")
            unrun = sum(1 for r in group if r["status"].startswith("not run"))
            note = f" ({unrun} not run in the time budget)" if unrun else ""
            lines.append(f"- **{label}**: {word}: {ok} / {len(group) - unrun}{note}")
    lines += ["", "| robot | base | " + " | ".join(labels) + " |", "|---|---|" + "---|" * len(labels)]
    names = list(dict.fromkeys(n for label in labels for n in everything[label]))
    for name in names:
        floating = next((everything[la][name].get("floating") for la in labels if name in everything[la]), None)
        cells = []
        for label in labels:
            r = everything[label].get(name)
            if r is None:
                cells.append("not run")
                continue
            checks = r.get("checks", {})
            measure = ""
            if "lowest_up_z" in checks:
                value = checks["lowest_up_z"] if floating else checks.get("joint_drift", 0.0)
                measure = f" ({'up·z' if floating else 'drift'} {value:.3f})"
            status = "pass" if r["status"] == "pass" else r["status"]
            cells.append((status + measure if status == "pass" else status).replace("|", "\\|").replace("\n", " "))
        lines.append(f"| {name} | {'floating' if floating else 'fixed'} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--envs", required=True)
    ap.add_argument("--robots", default=None, help="comma list of robot names (substring match); default all")
    ap.add_argument("--src", default=os.path.join(ROOT, "src"), help="the robodesc tree that compiles")
    ap.add_argument("--label", default="after")
    ap.add_argument("--jobs", type=int, default=2, help="compiles at a time")
    ap.add_argument("--out", default=RESULTS)
    ap.add_argument("--compile-only", action="store_true", help="compile the folders, check nothing")
    ap.add_argument("--reuse", action="store_true", help="keep folders an earlier run of this label compiled")
    ap.add_argument("--resume", action="store_true", help="keep results an earlier run of this label checked")
    ap.add_argument("--collect", action="store_true", help="write what a (stopped) run of this label checked")
    ap.add_argument("--describe", default=None, help="what this label's robodesc is, for the table")
    args = ap.parse_args(argv)
    sys.path.insert(0, os.path.join(ROOT, "src"))
    from robodesc.validation.corpora import all_robots

    robots = all_robots(os.path.join(os.path.dirname(ROOT), "shared", "corpus"))
    if args.robots:  # a full name matches itself only; any other word, every name containing it
        words = args.robots.split(",")
        names = {r.name for r in robots}
        robots = [r for r in robots if r.name in words or any(w in r.name for w in words if w not in names)]
    work = os.path.join(args.envs, "work_isaaclab", args.label)
    os.makedirs(work, exist_ok=True)
    with ThreadPoolExecutor(args.jobs) as pool:
        compiled = list(pool.map(lambda r: _compiled(r, os.path.abspath(args.src), work, args.reuse), robots))
    if args.compile_only:
        return 0
    cases = [{"name": c["name"], "folder": c["folder"], "floating": c["floating"]} for c in compiled if c["rc"] == 0]
    if args.collect:  # no Isaac Lab: the results so far, robots not reached marked so
        checked = collected(work)
        for c in cases:
            checked.setdefault(c["name"], {"status": "not run (the run was stopped at the time budget)"})
    else:
        checked = check_all(args.envs, cases, work, args.resume)
    results: dict[str, Any] = {}
    for c in compiled:
        why = (c["error"].strip().splitlines() or [""])[-1]
        r = checked.get(c["name"], {"status": f"fail: not converted ({why})"})
        r.pop("traceback", None)
        results[c["name"]] = rejudge({"floating": c["floating"], **r})
    everything: dict[str, Any] = {}
    if os.path.isfile(args.out):
        with open(args.out, encoding="utf-8") as f:
            everything = json.load(f)
    # A subset run updates its robots and keeps the rest of the label's results.
    everything[args.label] = {**everything.get(args.label, {}), **results} if args.robots else results
    if args.describe:
        everything.setdefault("_labels", {})[args.label] = args.describe
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(everything, f, indent=1, default=str)
        f.write("\n")
    with open(args.out[: -len(".json")] + ".md", "w", encoding="utf-8") as f:
        f.write(markdown(everything))
    for kind in (True, False):
        group = {k: v for k, v in results.items() if v["floating"] is kind}
        ok = sum(1 for v in group.values() if v["status"] == "pass")
        print(f"{args.label} {'floating' if kind else 'fixed'}: {ok}/{len(group)} pass")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
