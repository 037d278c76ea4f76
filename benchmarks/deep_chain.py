"""A very deep chain to every target, with default validation (issue 26).

    PYTHONPATH=src python benchmarks/deep_chain.py [--links 50000] [--targets urdf,sdf,usd,mjcf,ros2,isaac]
                                                   [--timeout 1800] [--out benchmarks/results/deep_chain]

Generates an N-link revolute chain URDF (every link the child of the previous one, a box visual and
collider, a unit inertia), then runs ``robodesc compile`` once per target in a fresh process with
default validation, and records the exit code, wall time, peak RSS (the process and its children)
and the first line robodesc printed. The promise: every target either writes and validates the
chain, or refuses it early (exit 2, nothing written) with a message naming the limit; never a
crash (exit 3, a signal) or a hang (the timeout). Results: ``--out`` + ``.json`` and ``.md``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

LINK = (
    '<link name="l{i}"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" '
    'iyz="0"/></inertial><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
    '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>'
)
JOINT = (
    '<joint name="j{i}" type="revolute"><parent link="l{p}"/><child link="l{i}"/><origin xyz="0 0 0.1"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
)
# The CLI in a fresh interpreter, as the console script runs it; then its peak RSS and its
# children's (KiB), for validation that runs a consumer in a subprocess.
RUNNER = (
    "import resource, sys\n"
    "from robodesc.cli import main, tune_gc\n"
    "tune_gc()\n"
    "code = main(sys.argv[1:])\n"
    "sys.stderr.flush()\n"
    "own = resource.getrusage(resource.RUSAGE_SELF)\n"
    "kids = resource.getrusage(resource.RUSAGE_CHILDREN)\n"
    "cpu = own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime\n"
    "print(f'@@rss {max(own.ru_maxrss, kids.ru_maxrss)} {cpu:.1f}', file=sys.stderr)\n"
    "sys.exit(code)\n"
)
# target -> (options, output relative to the run's folder)
TARGETS: dict[str, tuple[list[str], str]] = {
    "urdf": (["-t", "urdf"], "out.urdf"),
    "sdf": (["-t", "sdf"], "out.sdf"),
    "usd": (["-t", "usd"], "out.usdc"),
    "mjcf": (["-t", "mjcf"], "mjcf/robot.xml"),
    "ros2": (["--ros2"], "ros2"),
    "isaac": (["--isaac-sim"], "isaac"),
}


def chain_urdf(n: int) -> str:
    parts = [f'<robot name="chain{n}">']
    parts += [LINK.format(i=i) for i in range(n)]
    parts += [JOINT.format(i=i, p=i - 1) for i in range(1, n)]
    parts.append("</robot>")
    return "\n".join(parts)


def run_target(src: Path, target: str, work: Path, timeout: float) -> dict[str, object]:
    options, out_name = TARGETS[target]
    out = work / target / out_name
    out.parent.mkdir(parents=True, exist_ok=True)
    argv = ["compile", str(src), *options, "-o", str(out)]
    start = time.perf_counter()
    try:
        done = subprocess.run(
            [sys.executable, "-c", RUNNER, *argv], capture_output=True, text=True, check=False, timeout=timeout
        )
    except subprocess.TimeoutExpired:
        return {"target": target, "exit": None, "seconds": round(time.perf_counter() - start, 1),
                "peak_rss_mib": None, "written": out.exists(), "message": f"no answer within {timeout:.0f} s"}  # fmt: skip
    seconds = time.perf_counter() - start
    lines = done.stderr.strip().splitlines()
    usage = next((line.split()[1:] for line in reversed(lines) if line.startswith("@@rss ")), None)
    rss = int(usage[0]) if usage else None
    cpu = float(usage[1]) if usage and len(usage) > 1 else None
    said = [line for line in lines if not line.startswith("@@rss ")]
    first = next((line for line in said if line.startswith(("error", "robodesc"))), said[0] if said else "")
    return {
        "target": target,
        "exit": done.returncode,
        "seconds": round(seconds, 1),
        "cpu_seconds": cpu,
        "peak_rss_mib": round(rss / 1024) if rss else None,
        "written": out.exists(),
        "message": first[:400],
        "lines_printed": len(said),
    }


def to_markdown(rows: list[dict[str, object]], links: int, note: str) -> str:
    out = [
        f"# A {links:,}-link chain to every target (benchmarks/deep_chain.py)",
        "",
        note,
        "",
        "| target | links | exit | wall (s) | CPU (s) | peak RSS (MiB) | written | first line |",
        "|---|---:|---:|---:|---:|---:|---|---|",
    ]
    for r in rows:
        # The run's temporary folder says nothing: the output as the user named it.
        message = re.sub(r"/\S*robodesc-deep-chain-[^/]+/", "", str(r["message"])).replace("|", "\\|")
        n = int(r.get("links", links))  # type: ignore[call-overload]
        out.append(
            f"| {r['target']} | {n:,} | {r['exit']} | {r['seconds']} | {r.get('cpu_seconds')} "
            f"| {r['peak_rss_mib']} | {r['written']} | {message} |"
        )
    return "\n".join(out) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, default=50_000)
    parser.add_argument("--targets", default=",".join(TARGETS))
    parser.add_argument("--timeout", type=float, default=1800.0, help="seconds per target")
    parser.add_argument("--out", type=Path, help="write OUT.json and OUT.md")
    parser.add_argument(
        "--merge", type=Path, nargs="+", metavar="JSON", help="combine earlier runs' JSON files into --out (no run)"
    )
    args = parser.parse_args()
    if args.merge:
        runs = [json.loads(path.read_text(encoding="utf-8")) for path in args.merge]
        merged = [{"links": run["links"], **row} for run in runs for row in run["runs"]]
        note = runs[0]["note"]
        args.out.with_suffix(".json").write_text(
            json.dumps({"links": runs[0]["links"], "note": note, "runs": merged}, indent=2) + "\n", encoding="utf-8"
        )
        args.out.with_suffix(".md").write_text(to_markdown(merged, runs[0]["links"], note), encoding="utf-8")
        return
    rows = []
    with tempfile.TemporaryDirectory(prefix="robodesc-deep-chain-") as tmp:
        src = Path(tmp) / f"chain{args.links}.urdf"
        src.write_text(chain_urdf(args.links), encoding="utf-8")
        for target in args.targets.split(","):
            row = run_target(src, target, Path(tmp), args.timeout)
            rows.append(row)
            print(json.dumps(row), flush=True)
    note = (
        f"{time.strftime('%Y-%m-%d')}, {os.cpu_count()}-core machine shared with other jobs, Python "
        f"{platform.python_version()}; `robodesc compile chain.urdf TARGET -o OUT` with default validation, "
        "a fresh process per target."
    )
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.with_suffix(".json").write_text(
            json.dumps({"links": args.links, "note": note, "runs": rows}, indent=2) + "\n", encoding="utf-8"
        )
        args.out.with_suffix(".md").write_text(to_markdown(rows, args.links, note), encoding="utf-8")


if __name__ == "__main__":
    main()
