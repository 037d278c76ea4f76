"""issue 35's robots in PhysX with robodesc's default gains: ``robodesc validate -t isaac --dynamics
--engines physx`` on each robot's URDF (the Isaac folder's USD in ovphysx 0.7 on CPU).

    PYTHONPATH=src python benchmarks/menagerie_physx.py [--robots panda,go1]

Welded robots hold their home pose for 1 s (``hold-fixed``: the largest joint drift, rad); floating ones
are dropped onto a plane from their stance and must land upright (``drop``: height, tilt). The robots
and their URDFs are menagerie_compare.py's. Writes benchmarks/results/menagerie_physx.json and .md.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from typing import Any

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from menagerie_compare import ROBOTS, write_results  # noqa: E402

OUT = os.path.join(HERE, "results", "menagerie_physx")


def run(source: str, erd: str) -> dict[str, Any]:
    cmd = [sys.executable, "-m", "robodesc", "validate", source, "-t", "isaac", "--dynamics"]
    cmd += ["--engines", "physx", "--package", f"example-robot-data={erd}", "--json"]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False, timeout=1800)
    try:
        report = json.loads(proc.stdout)
    except json.JSONDecodeError:
        return {"error": (proc.stderr or proc.stdout)[-300:]}
    dynamics = report.get("dynamics") or {}
    row: dict[str, Any] = {"exit": proc.returncode, "ok": dynamics.get("ok")}
    for run_ in dynamics.get("runs", []):
        if run_["scenario"] in ("hold-fixed", "drop"):
            row[run_["scenario"]] = {
                k: run_.get(k) for k in ("ok", "error", "drift", "worst_joint", "height", "tilt", "settle", "seconds")
            }
    row["checks"] = {c["name"]: f"{c['status']}: {c['message']}" for c in dynamics.get("checks", [])}
    row["pose"] = (dynamics.get("info") or {}).get("pose_note", "")
    return row


def table(results: dict[str, dict[str, Any]]) -> str:
    lines = ["| robot | scenario | result | PhysX s |", "|---|---|---|---:|"]
    for name, row in results.items():
        if "error" in row:
            lines.append(f"| {name} | – | {row['error'][:100]} | |")
            continue
        for scenario in ("hold-fixed", "drop"):
            r = row.get(scenario)
            if not r:
                continue
            if scenario == "hold-fixed":
                what = f"drift {r['drift']:.4f} rad ({r['worst_joint']})" if r["drift"] is not None else r["error"]
            elif r["height"] is not None:
                what = (
                    f"landed at {r['height']:.3f} m, tilt {r['tilt']:.4f} rad, joint drift {r['drift']:.4f} rad "
                    f"({r['worst_joint']}), settled in {r['settle']} s"
                )
            else:
                what = r["error"]
            lines.append(f"| {name} | {scenario} | {'ok' if r['ok'] else '**fail**'}: {what} | {r['seconds']} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    """Run the robots (or, with ``--table``, rewrite the table from the JSON already written)."""
    from robodesc.validation.corpora import example_robot_data_root

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--robots", default="")
    parser.add_argument("--out", default=OUT)
    parser.add_argument("--table", action="store_true", help="only rewrite the .md from the .json")
    args = parser.parse_args(argv)
    if args.table:
        with open(args.out + ".json") as handle:
            text = table(json.load(handle))
        with open(args.out + ".md", "w") as handle:
            handle.write(text)
        print(text)
        return 0
    erd = example_robot_data_root()
    if erd is None:
        print("example-robot-data is not installed (the test extra installs it)", file=sys.stderr)
        return 2
    names = [n for n in args.robots.split(",") if n] or [n for n, (rel, _, opts) in ROBOTS.items() if rel and not opts]
    results: dict[str, dict[str, Any]] = {}
    for name in names:
        rel = ROBOTS[name][0]
        assert rel is not None
        results[name] = run(os.path.join(erd, "robots", rel), erd)
        print(name, json.dumps(results[name])[:300], flush=True)
    write_results(args.out, results, table(results))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
