"""mujoco_menagerie's models as robodesc inputs (issue 36): each through every file target.

For each model (every ``scene*.xml`` under a menagerie checkout, or the files given), in one process:

- ``read``: the MJCF frontend builds the IR (time, and every warning code it gives);
- ``mjcf``, ``urdf``, ``sdf``, ``usd``: ``robodesc.compile_to`` with the target's own consumer check
  (MuJoCo for MJCF and URDF, Drake for SDF, usd-core's UsdPhysics parser for USD): passed, or the
  first failure; wall time per target;
- ``round trip``: the source and robodesc's MJCF of it in MuJoCo (tests/mjcf_in/compare.py: total
  mass, centre and inertia, every joint's world anchor and axis at five random joint positions,
  mesh geoms' places), 1e-6.

    PYTHONPATH=src python benchmarks/menagerie_input.py --menagerie PATH [--models 'go1|panda']
    PYTHONPATH=src python benchmarks/menagerie_input.py FILE.xml ...

Writes benchmarks/results/menagerie_input.json and .md (``--out`` elsewhere). Models whose mesh
files are missing compile with robodesc's ``missing-mesh`` policy and cannot be compared in MuJoCo
(the source does not load): their round trip says so.
"""

from __future__ import annotations

import argparse
import glob
import json
import os
import re
import sys
import tempfile
import time
from collections import defaultdict
from typing import Any

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)  # tests.mjcf_in.compare
TARGETS = (("mjcf", "robot.xml"), ("urdf", "robot.urdf"), ("sdf", "robot.sdf"), ("usd", "robot.usda"))


def models(menagerie: str | None, files: list[str], pattern: str | None) -> list[str]:
    found = list(files)
    if menagerie:
        found += sorted(glob.glob(os.path.join(menagerie, "*", "scene*.xml")))
    return [f for f in found if pattern is None or re.search(pattern, f)]


def run_model(path: str) -> dict[str, Any]:
    import mujoco
    from tests.mjcf_in.compare import _root_shift, compare, unmatched_meshes

    import robodesc
    from robodesc.frontends.load import load_path

    row: dict[str, Any] = {"model": path}
    start = time.perf_counter()
    try:
        loaded = load_path(path)
    except Exception as exc:  # a refused model is a result of this table
        row["read"] = f"refused: {exc}"
        return row
    row["read_s"] = round(time.perf_counter() - start, 3)
    row["read"] = "ok"
    row["links"] = len(loaded.robot.links)
    row["warnings"] = sorted({f.code for f in loaded.findings if f.severity.value == "warning"})
    with tempfile.TemporaryDirectory() as tmp:
        for target, name in TARGETS:
            out = os.path.join(tmp, target, name)
            start = time.perf_counter()
            try:
                result = robodesc.compile_to(path, target, out)
                report = result.validation
                row[target] = "passed" if report is None or report.ok else "failed"
            except Exception as exc:
                row[target] = f"failed: {str(exc).splitlines()[0][:160]}"
            row[f"{target}_s"] = round(time.perf_counter() - start, 2)
        written = os.path.join(tmp, "mjcf", "robot.xml")
        try:
            source = mujoco.MjModel.from_xml_path(path)
        except ValueError as exc:
            row["round_trip"] = f"source does not load in MuJoCo: {str(exc).splitlines()[0][:100]}"
            return row
        if not os.path.exists(written):
            row["round_trip"] = "no MJCF written"
            return row
        model = mujoco.MjModel.from_xml_path(written)
        problems = compare(source, model)
        meshes = unmatched_meshes(source, model, _root_shift(source, model))
        row["round_trip"] = "same" if not problems and not meshes else "; ".join(problems[:2]) + f" {meshes} meshes"
    return row


def markdown(rows: list[dict[str, Any]]) -> str:
    lines = [
        "# menagerie models as robodesc inputs",
        "",
        "`PYTHONPATH=src python benchmarks/menagerie_input.py` (docs/mjcf-input.md). Each target's cell: its "
        "consumer's check (MuJoCo, MuJoCo, Drake, usd-core) and wall time, validation included.",
        "",
        "| model | links | read (s) | mjcf | urdf | sdf | usd | MJCF→IR→MJCF in MuJoCo |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for row in rows:
        name = os.path.relpath(row["model"], os.path.dirname(os.path.dirname(row["model"])))
        cells = [f"{row.get(t, '-')} ({row.get(t + '_s', '-')} s)" for t, _ in TARGETS]
        lines.append(
            f"| {name} | {row.get('links', '-')} | {row.get('read_s', row.get('read'))} | {' | '.join(cells)} | "
            f"{row.get('round_trip', '-')} |"
        )
    by_code: dict[str, list[str]] = defaultdict(list)
    for row in rows:
        for code in row.get("warnings", []):
            by_code[code].append(os.path.basename(os.path.dirname(row["model"])))
    lines += ["", "| warning class | models |", "|---|---|"]
    lines += [f"| `{code}` | {', '.join(sorted(set(names)))} |" for code, names in sorted(by_code.items())]
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("files", nargs="*")
    parser.add_argument("--menagerie")
    parser.add_argument("--models")
    parser.add_argument("--out", default=os.path.join(HERE, "results", "menagerie_input"))
    args = parser.parse_args()
    rows = []
    for path in models(args.menagerie, args.files, args.models):
        row = run_model(path)
        rows.append(row)
        print(json.dumps(row), flush=True)
    with open(args.out + ".json", "w") as handle:
        json.dump(rows, handle, indent=1)
    with open(args.out + ".md", "w") as handle:
        handle.write(markdown(rows))


if __name__ == "__main__":
    main()
