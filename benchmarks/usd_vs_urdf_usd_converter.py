"""robodesc's USD emitter against NVIDIA's ``urdf-usd-converter`` on the same URDF files.

Setup: each tool in its own fresh venv, as a user installs it (the peer bundles its own pxr; robodesc's
console script then starts without the development environment's extra ``.pth`` imports)::

    python -m venv /tmp/venv-peer && /tmp/venv-peer/bin/pip install urdf-usd-converter
    python -m venv /tmp/venv-robodesc && /tmp/venv-robodesc/bin/pip install .
    PYTHONPATH=src python benchmarks/usd_vs_urdf_usd_converter.py --robodesc /tmp/venv-robodesc/bin/robodesc

Each robot is converted ``--repeat`` times (default 5) by each tool, alternating, and the fastest run
of each counts: the machine's noise only ever adds time.

Per robot, one subprocess each (process start included, as a user runs them):
- peer: ``urdf_usd_converter IN OUT_DIR --package name=path`` (its default: layered asset + physics scene);
- robodesc: ``robodesc compile IN -t usd -o OUT.usda --layered --physics-scene --no-validate`` (the
  same shape of output as the peer).
Then robodesc in-process over the batch (imports paid once). Writes benchmarks/results/usd_vs_peer.md.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SRC = os.path.join(ROOT, "src")
PEER = "/tmp/venv-peer/bin/urdf_usd_converter"
SHARED_CORPUS = os.path.join(ROOT, "..", "shared", "corpus")


def _prepare(robot: object, passes: str) -> None:
    from robodesc.passes.options import PassOptions
    from robodesc.passes.pipeline import run_passes

    if passes == "sanitize":
        # What USD strictly needs (the peer repairs nothing either).
        run_passes(robot, options=PassOptions(sanitize_names=True, unique_materials=True))  # type: ignore[arg-type]
    else:
        run_passes(robot, preset=passes)  # type: ignore[arg-type]


def _robodesc_exe() -> str | None:
    """The console script itself: a version manager's shim (pyenv) adds ~0.1 s per call that is
    not robodesc's (the peer is called through its own venv's script too)."""
    beside = os.path.join(os.path.dirname(sys.executable), "robodesc")
    return beside if os.path.isfile(beside) else shutil.which("robodesc")


@dataclass
class Row:
    name: str
    peer_ok: bool
    peer_s: float
    peer_err: str
    ours_ok: bool
    ours_s: float
    ours_err: str
    inproc_s: float | None = None


def _best(cmd: list[str], repeat: int) -> tuple[bool, float, str]:
    runs = [_run(cmd) for _ in range(repeat)]
    ok = all(r[0] for r in runs)
    return ok, min(r[1] for r in runs), next((r[2] for r in runs if not r[0]), "")


def _run(cmd: list[str]) -> tuple[bool, float, str]:
    start = time.perf_counter()
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    except subprocess.TimeoutExpired:
        return False, time.perf_counter() - start, "timeout"
    seconds = time.perf_counter() - start
    err = (done.stderr.strip().splitlines() or [""])[-1][:120]
    return done.returncode == 0, seconds, err


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--corpus", action="append", help="corpus names (default: example-robot-data)")
    parser.add_argument("--limit", type=int, default=0)
    parser.add_argument("--peer", default=PEER)
    parser.add_argument("--robodesc", help="robodesc console script (default: the one beside this Python)")
    parser.add_argument("--repeat", type=int, default=5, help="runs per robot and tool; the fastest counts")
    parser.add_argument("--out", default=os.path.join(HERE, "results", "usd_vs_peer.md"))
    parser.add_argument(
        "--passes",
        default="isaac_sim",
        help="pass preset of the in-process batch, or 'sanitize' (names/materials only)",
    )
    args = parser.parse_args()

    sys.path.insert(0, SRC)
    from robodesc.validation.corpora import all_robots

    corpora = set(args.corpus or ["example-robot-data"])
    robots = [r for r in all_robots(SHARED_CORPUS) if r.corpus in corpora and r.path.endswith(".urdf")]
    if args.limit:
        robots = robots[: args.limit]
    if not os.path.exists(args.peer):
        print(f"peer not installed at {args.peer} (see the module docstring)", file=sys.stderr)
        return 2
    exe = args.robodesc or _robodesc_exe()
    if exe is None:
        print("no robodesc console script found: pass --robodesc (see the module docstring)", file=sys.stderr)
        return 2
    work = tempfile.mkdtemp(prefix="usd-bench-")
    rows: list[Row] = []
    try:
        for index, entry in enumerate(robots):
            pkg_args = [a for name, path in entry.packages.items() for a in ("--package", f"{name}={path}")]
            peer_dir = os.path.join(work, f"peer{index}")
            peer_ok, peer_s, peer_err = _best([args.peer, entry.path, peer_dir, *pkg_args], args.repeat)
            ours_dir = os.path.join(work, f"ours{index}")
            os.makedirs(ours_dir)
            out = os.path.join(ours_dir, "robot.usda")
            # The peer's output shape (layered asset + physics scene), no repairs, no validation:
            # sanitize_names and unique_materials run anyway (USD needs them). Default severity: a
            # missing mesh or an invalid inertia is a warning, as the peer treats them.
            cmd = [
                exe,
                "compile",
                entry.path,
                "-t",
                "usd",
                "-o",
                out,
                "--layered",
                "--physics-scene",
                "--no-validate",
                "-q",
                *pkg_args,
            ]
            ours_ok, ours_s, ours_err = _best(cmd, args.repeat)
            rows.append(Row(entry.name, peer_ok, peer_s, peer_err, ours_ok, ours_s, ours_err))
            print(
                f"{entry.name:60s} peer {peer_s:6.2f}s {'ok' if peer_ok else 'FAIL'}  robodesc {ours_s:6.2f}s {'ok' if ours_ok else 'FAIL'}",
                flush=True,
            )
        _in_process(robots, rows, work, args.passes)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    report = _report(
        rows, f"robodesc compile -t usd --layered --physics-scene --no-validate (best of {args.repeat} runs)"
    )
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w", encoding="utf-8") as handle:
        handle.write(report)
    print(report.split("\n\n| robot")[0])
    return 0


def _in_process(robots: list, rows: list[Row], work: str, passes: str) -> None:  # type: ignore[type-arg]
    from robodesc.emit.usd import UsdOptions, emit_usd
    from robodesc.frontends.load import load_path
    from robodesc.frontends.options import LoadOptions, MissingMesh
    from robodesc.ir.diagnostics import RobodescError

    for index, (entry, row) in enumerate(zip(robots, rows, strict=True)):
        start = time.perf_counter()
        try:
            robot = load_path(
                entry.path, LoadOptions(package_paths=entry.packages, missing_mesh=MissingMesh.WARN)
            ).robot
            _prepare(robot, passes)
            floating = any(j.type.dof == 6 for j in robot.joints)
            out = os.path.join(work, f"batch{index}", "robot.usda")
            emit_usd(robot, out, UsdOptions(fix_base=not floating, layered=True, physics_scene=True))
        except RobodescError:
            continue
        row.inproc_s = time.perf_counter() - start


def _report(rows: list[Row], how: str) -> str:
    both = [r for r in rows if r.peer_ok and r.ours_ok]
    ratios = [r.peer_s / r.ours_s for r in both]
    peer_total = sum(r.peer_s for r in both)
    ours_total = sum(r.ours_s for r in both)
    inproc = [r.inproc_s for r in rows if r.inproc_s is not None]
    lines = [
        "# robodesc USD emitter vs urdf-usd-converter",
        "",
        f"robodesc run as: {how}. Both write a layered asset with a physics scene; one process per robot.",
        "",
        f"- robots: {len(rows)}; converted with default flags: peer {sum(r.peer_ok for r in rows)}, "
        f"robodesc {sum(r.ours_ok for r in rows)}",
        f"- both converted: {len(both)}; total wall time on those: peer {peer_total:.1f} s, robodesc {ours_total:.1f} s"
        + (f" (x{peer_total / ours_total:.2f})" if ours_total else ""),
        f"- per-robot speed-up (peer time / robodesc time): median x{statistics.median(ratios):.2f}, "
        f"min x{min(ratios):.2f}, max x{max(ratios):.2f}"
        if ratios
        else "- no robot converted by both",
        f"- robodesc in-process batch (imports paid once): {sum(inproc):.1f} s for {len(inproc)} robots"
        + (
            f", x{sum(r.peer_s for r in both if r.inproc_s) / sum(r.inproc_s for r in both if r.inproc_s):.1f} against the peer's runs on the same robots"
            if inproc
            else ""
        ),
        "",
        "| robot | peer | peer s | robodesc | robodesc s | speed-up | in-process s | failure reason |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        ratio = f"x{r.peer_s / r.ours_s:.2f}" if r.peer_ok and r.ours_ok else "-"
        reason = "; ".join(
            x
            for x in (
                ("peer: " + r.peer_err) if not r.peer_ok else "",
                ("robodesc: " + r.ours_err) if not r.ours_ok else "",
            )
            if x
        )
        inproc = f"{r.inproc_s:.2f}" if r.inproc_s is not None else "-"
        lines.append(
            f"| {r.name} | {'ok' if r.peer_ok else 'FAIL'} | {r.peer_s:.2f} | {'ok' if r.ours_ok else 'FAIL'} | "
            f"{r.ours_s:.2f} | {ratio} | {inproc} | {reason.replace('|', '/')} |"
        )
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    sys.exit(main())
