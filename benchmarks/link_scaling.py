"""Compile time and peak memory against the number of links: chains and wide trees (issue 17).

    PYTHONPATH=src python benchmarks/link_scaling.py [--sizes 1000,10000,100000] [--target urdf]

Each robot is generated (a revolute chain: every link the child of the previous one; a wide tree:
every link a child of the root), written to a temporary URDF, and compiled in a fresh process with
``robodesc compile -t TARGET --no-validate -q`` (validation loads MuJoCo, which refuses trees deeper
than 1,024 bodies, so it is left out). The table gives wall time, peak RSS, and time per link
relative to the smallest size: 1.0 means linear growth. Before issue 17 the verifier's cycle walk
was cubic on chains: 1,000 links took 3.8 s, 5,000 links 474 s.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time

LINK = (
    '<link name="l{i}"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" '
    'iyz="0"/></inertial><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>'
)
JOINT = (
    '<joint name="j{i}" type="revolute"><parent link="l{p}"/><child link="l{i}"/><origin xyz="0 0 0.1"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
)
# Runs the CLI in a fresh interpreter and prints its own peak RSS (KiB) afterwards.
RUNNER = (
    "import resource, sys\n"
    "from robodesc.cli import main, tune_gc\n"
    "tune_gc()  # as the robodesc console script does\n"
    "code = main(sys.argv[1:])\n"
    "print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, file=sys.stderr)\n"
    "sys.exit(code)\n"
)


def robot(n: int, shape: str) -> str:
    parts = ['<robot name="scaling">']
    parts += [LINK.format(i=i) for i in range(n)]
    parts += [JOINT.format(i=i, p=i - 1 if shape == "chain" else 0) for i in range(1, n)]
    parts.append("</robot>")
    return "\n".join(parts)


def measure(n: int, shape: str, target: str, tmp: str) -> tuple[float, int]:
    src = os.path.join(tmp, f"{shape}{n}.urdf")
    with open(src, "w", encoding="utf-8") as handle:
        handle.write(robot(n, shape))
    ext = {"usd": "usdc"}.get(target, target)
    argv = ["compile", src, "-t", target, "-o", os.path.join(tmp, f"out.{ext}"), "--no-validate", "-q"]
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", RUNNER, *argv], capture_output=True, text=True, check=False)
    seconds = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"{shape} {n}: exit {done.returncode}: {done.stderr[-500:]}")
    return seconds, int(done.stderr.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--sizes", default="1000,10000,100000")
    parser.add_argument("--target", default="urdf", choices=["urdf", "sdf", "usd"])
    args = parser.parse_args()
    sizes = [int(s) for s in args.sizes.split(",")]
    print(f"| shape | links | time (s) | peak RSS (MiB) | time per link vs {sizes[0]} |")
    print("|---|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory(prefix="robodesc-scaling-") as tmp:
        for shape in ("chain", "wide"):
            base: float | None = None
            for n in sizes:
                seconds, rss = measure(n, shape, args.target, tmp)
                per_link = seconds / n
                base = base or per_link
                print(f"| {shape} | {n} | {seconds:.2f} | {rss / 1024:.0f} | {per_link / base:.2f} |", flush=True)


if __name__ == "__main__":
    main()
