"""The Isaac Sim 6 route's results as one JSON list and a Markdown table (``isaac6_layer.py``'s rows).

    python tests/consumers/isaac6_report.py RUN.jsonl [MORE.jsonl|.json ...] \\
        --json benchmarks/results/isaac6_layer.json --md benchmarks/results/isaac6_layer.md

Rows are merged by robot, a later file's row replacing an earlier one's (a re-run after a fix).
"""

from __future__ import annotations

import argparse
import json
import re
from collections import Counter
from pathlib import Path
from typing import Any

ROUTES = ("robodesc", "settings", "layer")


def load(paths: list[str]) -> list[dict[str, Any]]:
    rows: dict[str, dict[str, Any]] = {}
    for path in paths:
        text = Path(path).read_text(encoding="utf-8")
        items = json.loads(text) if text.lstrip().startswith("[") else [json.loads(x) for x in text.splitlines() if x]
        for item in items:
            rows.pop(item["robot"], None)  # keep the run order of the latest rows
            rows[item["robot"]] = item
    return list(rows.values())


def cause_of_missing(message: str) -> str:
    """A prim the layer could not address, grouped by why."""
    if "inside an instance" in message:
        extra = re.search(r"mesh collider \S+ \((.*?): inside an instance", message)
        what = (
            ", ".join(sorted({re.sub(r"^physx\w*:|^physics:", "", w.strip()) for w in extra.group(1).split(",")}))
            if extra
            else ""
        )
        return f"instanced mesh collider carrying {what}"
    if message.startswith("loop joint"):
        return "loop joint " + (message.split("(", 1)[1].rstrip(")") if "(" in message else "")
    return message.split(" '", 1)[0] + " not in the import"


def cause_of_diff(diff: str) -> str:
    """A PhysX quantity that differs from robodesc's USD, grouped by attribute."""
    if diff.startswith("articulations"):
        return "fixed base floats" if "'isFixedBase': [0.0]" in diff.split("(robodesc")[0] else "articulation"
    parts = diff.split(" ")
    return parts[2].rstrip(":") if len(parts) > 2 else diff


def cause_of_behaviour(diff: str) -> str:
    head, _, rest = diff.partition(": ")
    scenario = head.split(" ", 1)[1]
    if rest.startswith("failed:"):
        return f"{scenario} fails ({rest[len('failed: ') :].split(' (reference')[0]})"
    what = "a joint ends elsewhere" if rest.startswith("joint") else rest.split(" ")[0]
    return f"{scenario} {what}"


def _num(value: Any, digits: int) -> str:
    return "–" if value is None else f"{value:.{digits}f}"


def _route(row: dict[str, Any], route: str, scenario: str, key: str) -> Any:
    return row.get("behaviour", {}).get(route, {}).get(scenario, {}).get(key)


def markdown(rows: list[dict[str, Any]]) -> str:
    ran = [r for r in rows if "error" not in r]
    imported = [r for r in ran if r.get("import") == "pass"]
    complete = [r for r in imported if not r.get("prims_missing")]
    equal = [r for r in imported if r.get("physx") == "match"]
    behaved = [r for r in imported if "behaves" in r]
    same = [r for r in behaved if r["behaves"] == "same"]
    settings_same = [r for r in behaved if not r.get("settings_behaviour_diffs")]
    layer_s = sorted(r["layer_s"] for r in imported if "layer_s" in r)
    lines = [
        "# The Isaac Sim 6 route: robodesc's physics layer over Isaac Sim 6.2's own URDF import",
        "",
        '`tests/consumers/isaac6_layer.py` (docs/isaac.md, "The Isaac Sim 6 route"): each robot compiled',
        "`--isaac-sim --physics-scene`, its URDF imported by Isaac Sim 6.2's isolated importer with",
        "`importer_settings.json`, the layer made again from the import (`robodesc layer --onto`), and three",
        "stages read and run in PhysX (ovphysx 0.7, CPU): robodesc's own USD (the reference), the import",
        "with `importer_settings.json` alone, and the import with the layer (root layer from",
        "`emit/isaac/composed.py`). Structure: every link's mass, inertia and shape friction, every joint's",
        "gains, limits, effort and velocity bounds, armature and friction, the articulation (relative 1e-5).",
        "Behaviour: `validate --dynamics`' hold, drop (floating robots) and slide, 1 s at 1 kHz, the same stance",
        "on every stage, compared with robodesc's USD within docs/dynamics.md's thresholds (hold 0.02 rad per",
        "joint, drop height 0.03 m, tilt 10°, mass 1 %, friction 1e-3). Meshes are the corpus's real files.",
        "",
        f"- robots run: {len(rows)} ({len(rows) - len(ran)} failed before PhysX); imported: {len(imported)}",
        f"- layer with every prim addressed: {len(complete)} of {len(imported)}",
        f"- import + layer equal to robodesc's USD in PhysX (structure): {len(equal)} of {len(imported)}",
        f"- import + layer behaves as robodesc's USD (hold, drop, slide): {len(same)} of {len(behaved)}",
        f"- import + importer_settings.json alone behaves as robodesc's USD: {len(settings_same)} of {len(behaved)}",
    ]
    if layer_s:
        lines.append(
            f"- time the layer adds (inside the compile): median {layer_s[len(layer_s) // 2]:.3f} s, "
            f"max {layer_s[-1]:.3f} s"
        )
    lines += ["", "## Where the importer's layout defeats the layer, by cause", ""]
    missing = Counter(cause_of_missing(m) for r in imported for m in r.get("prims_missing", []))
    robots_by = {
        cause: sorted(
            {r["robot"] for r in imported for m in r.get("prims_missing", []) if cause_of_missing(m) == cause}
        )
        for cause in missing
    }
    for cause, count in missing.most_common():
        lines.append(f"- {cause}: {count} prims ({', '.join(robots_by[cause])})")
    if not missing:
        lines.append("- none")
    lines += ["", "The folder's own layer (the naming rules, no import read) leaves out:", ""]
    folder = [(r["robot"], w) for r in imported for w in r.get("layer_warnings", [])]
    lines += [
        f"- {robot}: {w.split(' the physics layer')[0]} ({cause_of_missing(w.split('left out: ', 1)[-1])})"
        for robot, w in folder
    ]
    lines += [] if folder else ["- nothing"]
    lines += ["", "PhysX differences on the layer route, by quantity:", ""]
    diffs = Counter(cause_of_diff(d) for r in imported for d in r.get("layer_diffs", []))
    lines += [f"- {k}: {v}" for k, v in diffs.most_common()] or ["- none"]
    lines += ["", "Behaviour differences (layer route; importer_settings.json route), by scenario and quantity:", ""]
    for label, key in (("layer", "layer_behaviour_diffs"), ("importer_settings.json", "settings_behaviour_diffs")):
        counted = Counter(cause_of_behaviour(d) for r in behaved for d in r.get(key, []))
        who = {
            c: sorted({r["robot"] for r in behaved for d in r.get(key, []) if cause_of_behaviour(d) == c})
            for c in counted
        }
        lines += [f"- {label}: {c}: {n} ({', '.join(who[c])})" for c, n in counted.most_common()] or [
            f"- {label}: none"
        ]
    lines += [
        "",
        "## Per robot",
        "",
        "Hold: the largest joint drift after 1 s (rad); drop: the settled base height (m); R = robodesc's USD,",
        "S = import + importer_settings.json, L = import + layer; peak: the run's largest drive effort as a share",
        "of its limit (1.00: saturated). Structure S: how many PhysX quantities differ.",
        "",
        "| robot | links / DOF | import s | compile s | layer s | not addressed | structure L | structure S | hold R / S / L | hold peak R / S / L | drop R / S / L | drop peak R / S / L | behaves L | behaves S |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if "error" in r or r.get("import") != "pass":
            lines.append(f"| {r['robot']} | {r.get('error') or r.get('import')} |" + " |" * 13)
            continue
        hold = " / ".join(_num(_route(r, x, "hold-fixed", "drift"), 4) for x in ROUTES)
        drop = " / ".join(_num(_route(r, x, "drop", "height"), 4) for x in ROUTES)
        peak = {
            scenario: " / ".join(
                _num(p[1] if p else None, 2) for p in (_route(r, x, scenario, "worst_saturation") for x in ROUTES)
            )
            for scenario in ("hold-fixed", "drop")
        }
        settings = len(r.get("importer_settings_diffs", []))
        behaves_s = "–" if "behaves" not in r else "same" if not r.get("settings_behaviour_diffs") else "differs"
        lines.append(
            f"| {r['robot']} | {r.get('links')} / {r.get('joints')} | {r.get('import_s')} | {r.get('compile_s')} "
            f"| {r.get('layer_s')} | {len(r.get('prims_missing', []))} | {r.get('physx')} "
            f"| {settings or 'equal'} | {hold} | {peak['hold-fixed']} | {drop} | {peak['drop']} | {r.get('behaves', '–')} | {behaves_s} |"
        )
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("inputs", nargs="+", help="isaac6_layer.py's --log (JSON lines) or --out (JSON) files")
    ap.add_argument("--json", help="write the merged rows here")
    ap.add_argument("--md", help="write the Markdown report here")
    args = ap.parse_args(argv)
    rows = load(args.inputs)
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1) + "\n", encoding="utf-8")
    text = markdown(rows)
    if args.md:
        Path(args.md).write_text(text, encoding="utf-8")
    else:
        print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
