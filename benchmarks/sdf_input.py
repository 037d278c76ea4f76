"""SDF models as robodesc inputs (issue 36, SDF part): URDF -> SDF -> IR -> URDF on the fixtures and
Quad-SDK's Spirit and Go2, Drake against the frontend's IR, and the time the frontend takes.

For each robot, in one process:

- ``sdf``: ``robodesc.compile_to`` the URDF/xacro to SDF (robodesc's SDF target);
- ``read``: the SDF frontend builds the IR from it (median of five reads, after one to warm up);
- ``SDF -> IR`` and ``-> URDF``: the IR against the source's (tests/sdf_in/compare.py: masses,
  inertias, COMs, joint types and limits, FK at five random joint values), and again after compiling
  the SDF to URDF and reading that;
- ``Drake``: Drake parses the SDF; every body's mass, COM and inertia about it in the root's frame at
  four random joint values against the IR (tests/sdf_in/drake_check.py).

    PYTHONPATH=src:. python benchmarks/sdf_input.py

Writes benchmarks/results/sdf_input.json and .md.
"""

from __future__ import annotations

import json
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.conftest import GO2_XACRO, SPIRIT_XACRO  # noqa: E402
from tests.sdf_in.compare import differences  # noqa: E402
from tests.sdf_in.drake_check import compare_in_drake  # noqa: E402

import robodesc  # noqa: E402
from robodesc.frontends.load import load_path  # noqa: E402

DATA = ROOT / "tests" / "sdf" / "data"
SOURCES = {
    "arm": DATA / "arm.urdf",
    "gripper": DATA / "gripper.urdf",
    "sensor_bot": DATA / "sensor_bot.urdf",
    "spirit": SPIRIT_XACRO,
    "go2": GO2_XACRO,
}


def run(name: str, source: Path, folder: str) -> dict[str, object]:
    original = load_path(str(source)).robot
    sdf = os.path.join(folder, f"{name}.sdf")
    robodesc.compile_to(str(source), "sdf", sdf)
    load_path(sdf)
    times = []
    for _ in range(5):
        start = time.perf_counter()
        read = load_path(sdf).robot
        times.append(time.perf_counter() - start)
    problems, fk = differences(original, read)
    urdf = os.path.join(folder, f"{name}.urdf")
    robodesc.compile_to(sdf, "urdf", urdf)
    back_problems, back_fk = differences(original, load_path(urdf).robot)
    drake = compare_in_drake(sdf, read)
    return {
        "robot": name,
        "links": len(read.links),
        "joints": len(read.joints),
        "read_ms": statistics.median(times) * 1000,
        "sdf_ir": problems or "same",
        "sdf_ir_fk": fk,
        "urdf": back_problems or "same",
        "urdf_fk": back_fk,
        "drake": drake.problems or "same",
        "drake_com": drake.max_com_error,
        "drake_inertia": drake.max_inertia_error,
    }


def main() -> None:
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for name, source in SOURCES.items():
            if source.exists():
                rows.append(run(name, source, folder))
    out = ROOT / "benchmarks" / "results"
    (out / "sdf_input.json").write_text(json.dumps(rows, indent=1, default=str) + "\n")
    lines = [
        "# SDF as input: URDF -> SDF -> IR -> URDF, and Drake against the IR",
        "",
        "`PYTHONPATH=src:. python benchmarks/sdf_input.py` (2 shared cores). FK: largest difference of any",
        "link's pose relative to the root at five random joint values; Drake: largest COM (m) and inertia",
        "(kg·m²) difference of any body at four.",
        "",
        "| robot | links | joints | read (ms) | SDF → IR | FK | → URDF | FK | Drake | COM | inertia |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['robot']} | {r['links']} | {r['joints']} | {r['read_ms']:.1f} | {r['sdf_ir']} | {r['sdf_ir_fk']:.1e} "
            f"| {r['urdf']} | {r['urdf_fk']:.1e} | {r['drake']} | {r['drake_com']:.1e} | {r['drake_inertia']:.1e} |"
        )
    (out / "sdf_input.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
