"""Issue 35's defaults on the corpus, before and after: ``validate -t mjcf --dynamics`` and MuJoCo's speed.

    PYTHONPATH=src python benchmarks/mjcf_defaults_corpus.py --before-src /work/wt/h-physx-corpus-before/src \\
        [--robots spirit,go2,...] [--out benchmarks/results/mjcf_defaults_corpus.json]

The defaults merge (33b4477: gain floors, default armature, fixed links fused in MJCF, legged contact
defaults, named poses) changed what ``-t mjcf`` writes with no flags. ``--before-src`` is a checkout of
the commit before it (``git worktree add --detach DIR 3c986cd``; copy the built ``*.so`` into its
``src``). For each robot and each side (before: that tree; after: this one), with default flags:

- ``validate ROBOT -t mjcf --dynamics --json`` (MuJoCo reads the MJCF, Drake the SDF compiled beside
  it; the engines' default pose and gains): each scenario's agreement, the verdict, the wall time;
- ``compile ROBOT -t mjcf`` and MuJoCo's steps per second of CPU time on its ``scene.xml`` from the
  ``home`` keyframe (else ``qpos0``), holding it (menagerie_compare.steps_per_second: best of five
  runs of 2,000 steps), with this process's MuJoCo for both sides.

Results are written after every robot. docs/mjcf.md shows the table.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from collections import Counter
from typing import Any

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from dynamics_corpus import ROOT, run_one  # noqa: E402  (benchmarks/ is no package)
from menagerie_compare import steps_per_second  # noqa: E402

from robodesc.validation.corpora import CorpusRobot, all_robots  # noqa: E402

OUT = os.path.join(ROOT, "benchmarks", "results", "mjcf_defaults_corpus.json")


def speed(robot: CorpusRobot, src: str, folder: str) -> dict[str, Any]:
    """Compile ``robot`` with the tree ``src`` and time MuJoCo on its scene."""
    import mujoco

    out = os.path.join(folder, "robot.xml")
    cmd = [sys.executable, "-m", "robodesc", "compile", robot.path, "-t", "mjcf", "-o", out, "--no-validate"]
    for name, path in robot.packages.items():
        cmd += ["--package", f"{name}={path}"]
    for name, value in robot.xacro_args.items():
        cmd += ["--arg", f"{name}={value}"]
    done = subprocess.run(cmd, capture_output=True, text=True, env={**os.environ, "PYTHONPATH": src}, check=False)
    scene = os.path.join(folder, "scene.xml")
    if done.returncode not in (0, 1) or not os.path.isfile(scene):
        tail = (done.stderr.strip().splitlines() or [f"exit {done.returncode}"])[-1]
        return {"speed_error": tail[:200]}
    model = mujoco.MjModel.from_xml_path(scene)
    data = mujoco.MjData(model)
    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    ctrl = model.key_ctrl[key].copy() if key >= 0 else data.ctrl.copy()
    return {
        "steps_per_s": round(steps_per_second(model, data, ctrl), 1),
        "nbody": int(model.nbody),
        "nv": int(model.nv),
        "timestep": float(model.opt.timestep),
        "home": key >= 0,
    }


def side(robot: CorpusRobot, src: str, timeout: float) -> dict[str, Any]:
    row = run_one(robot, "", timeout, target="mjcf", src=src)
    row.pop("runs", None)  # the per-run numbers are validate's; the verdicts and speed are compared here
    with tempfile.TemporaryDirectory() as folder:
        row.update(speed(robot, src, folder))
    return row


def summary(results: dict[str, dict[str, Any]]) -> str:
    lines = []
    for when in ("before", "after"):
        counts: Counter[str] = Counter()
        for row in results.values():
            for scenario, verdict in (row.get(when, {}).get("agreement") or {}).items():
                counts[f"{scenario} {verdict}"] += 1
            counts[f"status {row.get(when, {}).get('status')}"] += 1
        lines.append(f"{when}: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
    return "\n".join(lines)


def markdown(results: dict[str, dict[str, Any]]) -> str:
    """The table docs/mjcf.md quotes: per robot, the verdict, each scenario's agreement and MuJoCo's
    steps per second before and after, and the counts."""
    lines = [
        "# `-t mjcf` with default flags before and after the defaults merge (issue 35)",
        "",
        "Written by `benchmarks/mjcf_defaults_corpus.py` (method: its docstring). Before: 3c986cd (the commit"
        " before the merge 33b4477); after: this branch. Verdict: `validate -t mjcf --dynamics` (MuJoCo on the"
        " MJCF, Drake on the SDF); hold / drop / slide: the engines' agreement; steps/s: MuJoCo on the"
        " scene.xml holding home (CPU time, best of five runs of 2,000 steps).",
        "",
        "| robot | verdict before → after | hold | drop | slide | steps/s before → after (×) |",
        "|---|---|---|---|---|---|",
    ]
    ratios = []
    for key in sorted(results):
        b, a = results[key]["before"], results[key]["after"]
        cells = []
        for scenario in ("hold-fixed", "drop", "slide"):
            was = (b.get("agreement") or {}).get(scenario, "–")
            now = (a.get("agreement") or {}).get(scenario, "–")
            cells.append(was if was == now else f"{was} → {now}")
        speed = "–"
        if b.get("steps_per_s") and a.get("steps_per_s"):
            ratios.append(a["steps_per_s"] / b["steps_per_s"])
            speed = f"{b['steps_per_s']:.0f} → {a['steps_per_s']:.0f} ({ratios[-1]:.2f})"
        lines.append(
            f"| {key.split('/', 1)[-1]} | {b['status']} → {a['status']} | " + " | ".join(cells) + f" | {speed} |"
        )
    ratios.sort()
    median = ratios[len(ratios) // 2] if ratios else float("nan")
    lines += [
        "",
        f"{len(results)} robots; steps/s after over before, median ×{median:.2f}.",
        "",
        "```",
        summary(results),
        "```",
    ]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--before-src", default="", help="the src folder of the checkout before the defaults")
    parser.add_argument("--robots", default="", help="comma-separated whole corpus names, in order")
    parser.add_argument("--timeout", type=float, default=600.0)
    parser.add_argument("--out", default=OUT)
    parser.add_argument("--md-only", action="store_true", help="only write the .md from --out's JSON")
    args = parser.parse_args(argv)
    if args.md_only:
        with open(args.out, encoding="utf-8") as fh:
            _write_md(json.load(fh), args.out)
        return 0
    robots = [
        r
        for r in all_robots(os.path.join(ROOT, "..", "shared", "corpus"))
        if r.corpus in ("quadsdk", "example-robot-data")
    ]
    if args.robots:
        by_name = {r.name: r for r in robots}
        robots = [by_name[w] for w in args.robots.split(",") if w in by_name]
    results: dict[str, dict[str, Any]] = {}
    if os.path.isfile(args.out):  # resume: robots already measured are kept
        with open(args.out, encoding="utf-8") as fh:
            results = json.load(fh)
    after_src = os.path.join(ROOT, "src")
    for robot in robots:
        key = f"{robot.corpus}/{robot.name}"
        if key in results:
            continue
        started = time.perf_counter()
        results[key] = {
            "before": side(robot, args.before_src, args.timeout),
            "after": side(robot, after_src, args.timeout),
        }
        b, a = results[key]["before"], results[key]["after"]
        print(
            f"{key}: before {b['status']} {b.get('agreement')} {b.get('steps_per_s')}/s; "
            f"after {a['status']} {a.get('agreement')} {a.get('steps_per_s')}/s ({time.perf_counter() - started:.0f} s)",
            flush=True,
        )
        with open(args.out, "w", encoding="utf-8") as fh:
            json.dump(results, fh, indent=1, sort_keys=True)
    _write_md(results, args.out)
    print(summary(results))
    return 0


def _write_md(results: dict[str, dict[str, Any]], out: str) -> None:
    with open(out[: -len(".json")] + ".md", "w", encoding="utf-8") as fh:
        fh.write(markdown(results))


if __name__ == "__main__":
    sys.exit(main())
