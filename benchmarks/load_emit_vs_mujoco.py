"""URDF load + emit speed, as a ratio against MuJoCo's own URDF parser, on the same files in one run.

For every corpus URDF (Quad-SDK, example-robot-data, icub-models, stretch) this times:
- robodesc: parse into the IR (package resolution, mesh existence checks included) + verify + emit URDF;
- MuJoCo: ``mujoco.MjSpec.from_string`` on the same text (MuJoCo's parse; it does not open meshes,
  so compiling is left out on both sides).
Each measurement is the best of ``--repeat`` runs. Writes a markdown table to
benchmarks/results/load_emit_vs_mujoco.md and prints the summary.

    python benchmarks/load_emit_vs_mujoco.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import mujoco

from robodesc.emit.urdf import emit_urdf
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.frontends.packages import PackageResolver
from robodesc.frontends.xacro_expand import expand_xacro
from robodesc.ir.diagnostics import Findings, RobodescError
from robodesc.ir.verify import verify
from robodesc.validation.corpora import CorpusRobot, all_robots

ROOT = Path(__file__).resolve().parent.parent


def _best(fn, repeat: int) -> float:  # type: ignore[no-untyped-def]
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def _text(robot: CorpusRobot) -> str:
    if robot.path.endswith(".xacro"):
        return expand_xacro(robot.path, {}, PackageResolver(explicit=robot.packages, input_file=robot.path), Findings())
    return Path(robot.path).read_text()


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--corpus", default=str(ROOT.parent / "shared" / "corpus"))
    args = parser.parse_args()
    rows = []
    for robot in all_robots(args.corpus):
        opts = LoadOptions(package_paths=robot.packages, missing_mesh=MissingMesh.WARN)

        def ours(robot: CorpusRobot = robot, opts: LoadOptions = opts) -> None:
            ir = load_path(robot.path, opts).robot
            verify(ir)
            emit_urdf(ir)

        text = _text(robot)
        try:
            ours()
        except RobodescError as exc:
            rows.append((robot, None, None, f"robodesc: {exc}"))
            continue
        try:
            mujoco.MjSpec.from_string(text)
        except Exception as exc:
            rows.append((robot, _best(ours, args.repeat), None, f"mujoco: {exc}"))
            continue
        rows.append(
            (robot, _best(ours, args.repeat), _best(lambda text=text: mujoco.MjSpec.from_string(text), args.repeat), "")
        )

    both = [(r, a, b) for r, a, b, note in rows if a is not None and b is not None]
    ratios = [a / b for _, a, b in both]
    lines = [
        "# URDF load + emit: robodesc vs MuJoCo's URDF parser",
        "",
        f"mujoco {mujoco.__version__}; best of {args.repeat} runs per robot; ratio = robodesc time / MuJoCo time "
        "(robodesc also resolves packages, checks mesh files exist, verifies and writes URDF back).",
        "",
        f"- robots measured on both: {len(both)} of {len(rows)}",
        f"- total: robodesc {sum(a for _, a, _ in both) * 1e3:.1f} ms, MuJoCo {sum(b for _, _, b in both) * 1e3:.1f} ms, "
        f"ratio {sum(a for _, a, _ in both) / max(1e-12, sum(b for _, _, b in both)):.2f}",
        f"- median per-robot ratio {statistics.median(ratios):.2f} (min {min(ratios):.2f}, max {max(ratios):.2f})"
        if ratios
        else "",
        "",
        "| corpus | robot | robodesc ms | MuJoCo ms | ratio | note |",
        "|---|---|---:|---:|---:|---|",
    ]
    for robot, a, b, note in rows:
        ratio = f"{a / b:.2f}" if a and b else ""
        lines.append(
            f"| {robot.corpus} | {robot.name} | {a * 1e3:.2f} | {b * 1e3:.2f} | {ratio} | {note} |".replace(
                "| None", "| "
            )
            if a and b
            else f"| {robot.corpus} | {robot.name} | {'' if a is None else f'{a * 1e3:.2f}'} | | | {note[:120]} |"
        )
    out = ROOT / "benchmarks" / "results" / "load_emit_vs_mujoco.md"
    out.write_text("\n".join(lines) + "\n")
    print("\n".join(lines[:8]))
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
