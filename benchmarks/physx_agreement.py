"""PhysX against each other engine, robot by robot, from ``dynamics_corpus.py``'s results (issue 38).

    python benchmarks/physx_agreement.py RESULTS.json [MORE.json ...] --md benchmarks/results/dynamics_physx_newton.md

``validate --dynamics`` gives one agreement per scenario over every engine; this splits it into
pairs: PhysX (the USD) against MuJoCo (the URDF), Newton (the USD) and Drake (the SDF), for hold
and drop. A pair differs when the run's ``agree:<scenario>`` rows name it (a WARN or FAIL: the same
thresholds as ``validate``); it agrees when both engines ran the scenario and no row names it; ``n/a``
when either did not run it; ``failed`` when either run failed. The drop's settled heights and the
hold's final joint error (the worst over the joints, rad or m) are shown per engine, and the time:
the whole command's wall time and PhysX's and Newton's shares of it.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from typing import Any

OTHERS = ("mujoco", "newton", "drake")
SCENARIOS = ("hold-fixed", "drop")
PAIR = re.compile(r"^(?:warn|fail) agree:(\S+) (\w+)/\w+ vs (\w+)/\w+:")


def pairs(row: dict[str, Any]) -> dict[str, dict[str, str]]:
    """{scenario: {other engine: "agree" | "differ" | "n/a" | "failed"}} for PhysX."""
    named: set[tuple[str, str]] = set()
    for problem in row.get("problems", []):
        m = PAIR.match(problem)
        if m and "physx" in (m.group(2), m.group(3)):
            other = m.group(3) if m.group(2) == "physx" else m.group(2)
            named.add((m.group(1), other))
    runs = {(r["engine"], r["scenario"]): r for r in row.get("runs", []) if r["file"] != "source"}
    out: dict[str, dict[str, str]] = {}
    for scenario in SCENARIOS:
        out[scenario] = {}
        mine = runs.get(("physx", scenario))
        for other in OTHERS:
            theirs = runs.get((other, scenario))
            if mine is None or theirs is None:
                out[scenario][other] = "n/a"
            elif not mine["ok"] or not theirs["ok"]:
                out[scenario][other] = "failed"
            else:
                out[scenario][other] = "differ" if (scenario, other) in named else "agree"
    return out


def _num(run: dict[str, Any] | None, key: str, fmt: str) -> str:
    return "–" if run is None or run.get(key) is None else format(run[key], fmt)


def markdown(results: dict[str, dict[str, Any]]) -> str:
    lines = [
        "# PhysX against MuJoCo, Newton and Drake, robot by robot (`validate -t usd --dynamics`)",
        "",
        "Written by `benchmarks/physx_agreement.py` from `benchmarks/dynamics_corpus.py --engines"
        " mujoco,drake,newton,physx` (method: both scripts' docstrings). Pairs: PhysX (USD) against MuJoCo"
        " (URDF), Newton (USD), Drake (SDF). hold: the worst final joint error per engine"
        " (PhysX / MuJoCo / Newton / Drake); drop: settled root height per engine, m. Time: the whole command,"
        " PhysX's and Newton's shares.",
        "",
        "| robot | hold vs MuJoCo / Newton / Drake | hold error | drop vs MuJoCo / Newton / Drake | drop height |"
        " time s (PhysX, Newton) |",
        "|---|---|---|---|---|---|",
    ]
    counts: dict[tuple[str, str, str], int] = {}
    for key in sorted(results):
        row = results[key]
        if "runs" not in row:
            lines.append(f"| {key} | {row.get('status')} | | | | {row.get('seconds')} |")
            continue
        split = pairs(row)
        for scenario, verdicts in split.items():
            for other, verdict in verdicts.items():
                counts[(scenario, other, verdict)] = counts.get((scenario, other, verdict), 0) + 1
        runs = {(r["engine"], r["scenario"]): r for r in row["runs"] if r["file"] != "source"}
        engines = ("physx", *OTHERS)
        hold = " / ".join(_num(runs.get((e, "hold-fixed")), "drift", ".3g") for e in engines)
        drop = " / ".join(_num(runs.get((e, "drop")), "height", ".3f") for e in engines)
        spent = row.get("engine_seconds", {})
        lines.append(
            f"| {key.split('/', 1)[-1]} | {' / '.join(split['hold-fixed'][o] for o in OTHERS)} | {hold} | "
            f"{' / '.join(split['drop'][o] for o in OTHERS)} | {drop} | "
            f"{row['seconds']:.0f} ({spent.get('physx', 0):.0f}, {spent.get('newton', 0):.0f}) |"
        )
    lines += ["", "| scenario | against | agree | differ | failed | n/a |", "|---|---|---|---|---|---|"]
    for scenario in SCENARIOS:
        for other in OTHERS:
            cells = [str(counts.get((scenario, other, v), 0)) for v in ("agree", "differ", "failed", "n/a")]
            lines.append(f"| {scenario} | {other} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("results", nargs="+")
    parser.add_argument("--md", required=True)
    args = parser.parse_args(argv)
    results: dict[str, dict[str, Any]] = {}
    for path in args.results:
        with open(path, encoding="utf-8") as fh:
            results.update(json.load(fh))
    text = markdown(results)
    with open(args.md, "w", encoding="utf-8") as fh:
        fh.write(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
