"""``robodesc batch`` against a loop of single runs and against NVIDIA's ``urdf-usd-converter``.

The 100-robot corpus (``robodesc.validation.corpora``) to USD, validation off, each robot with the
peer's shape of output (layered asset + physics scene), in one run of this script:

- peer loop: ``urdf_usd_converter IN OUT_DIR --package ...``, one process per robot (URDF only: the
  peer does not read xacro, so it gets the 98 URDF robots and the 2 xacro ones are not counted for it);
- robodesc loop: ``robodesc compile IN -t usd -o OUT.usda --layered --physics-scene --no-validate ...``,
  one process per robot, as a shell loop would;
- ``robodesc batch MANIFEST -t usd ... --jobs 1``, ``--jobs 2``, and ``--executor ray --jobs 2``
  (a local Ray started by the command: its start-up is in the time), each with ``--force`` into a
  fresh folder, at each size in ``--sizes`` (the first N robots of the corpus).

Every time is wall time of the whole command (interpreter start, planning, workers, summary), the
best of ``--repeat`` runs (default 3; runs of different tools alternate): other work on the machine
only ever adds time. The loops run over the largest size; the smaller sizes' loop times are the
sums over their first N robots in that same run. Setup (each tool in its own venv, as a user installs it:
pip compiles both to bytecode at install, which an editable install under PYTHONDONTWRITEBYTECODE never
has, costing every robodesc process about 0.07 s of compiling)::

    python -m venv /tmp/venv-peer && /tmp/venv-peer/bin/pip install urdf-usd-converter
    python -m venv /tmp/venv-robodesc && /tmp/venv-robodesc/bin/pip install '.[ray]'
    python benchmarks/batch_speed.py --peer /tmp/venv-peer/bin/urdf_usd_converter \
        --robodesc /tmp/venv-robodesc/bin/robodesc

Writes benchmarks/results/batch_speed.md (and .json).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from typing import Any

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SHARED_CORPUS = os.path.join(ROOT, "..", "shared", "corpus")
# Default flags except three: the peer's shape of output (a layered asset with a physics scene) and
# no validation, which the benchmark leaves out (the peer validates nothing).
OPTIONS = ["-t", "usd", "--layered", "--physics-scene", "--no-validate"]


def _exe() -> str:
    beside = os.path.join(os.path.dirname(sys.executable), "robodesc")
    found = beside if os.path.isfile(beside) else shutil.which("robodesc")
    if found is None:
        raise SystemExit("no robodesc console script: pip install -e . first")
    return found


def _run(cmd: list[str], timeout: float = 1800) -> tuple[bool, float, str]:
    start = time.perf_counter()
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return False, time.perf_counter() - start, "timeout"
    err = (done.stderr.strip().splitlines() or [""])[-1][:160]
    return done.returncode == 0, time.perf_counter() - start, err


def _slug(text: str) -> str:
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in text)


def _manifest(robots: list[Any], path: str) -> None:
    import yaml

    jobs = [
        {
            "input": os.path.abspath(r.path),
            "id": _slug(f"{r.corpus}/{r.name}"),
            "packages": {k: os.path.abspath(v) for k, v in r.packages.items()},
            "args": dict(r.xacro_args),
        }
        for r in robots
    ]
    with open(path, "w", encoding="utf-8") as handle:
        yaml.safe_dump({"jobs": jobs}, handle, sort_keys=False)


def _pkg_args(robot: Any) -> list[str]:
    return [a for name, path in robot.packages.items() for a in ("--package", f"{name}={path}")]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", default="10,100", help="robot counts to time the batch modes at (default 10,100)")
    parser.add_argument("--peer", default="/tmp/venv-peer/bin/urdf_usd_converter")
    parser.add_argument("--robodesc", help="robodesc's console script (default: the one beside this Python)")
    parser.add_argument("--no-ray", action="store_true")
    parser.add_argument("--repeat", type=int, default=3, help="runs of each command; the fastest counts")
    parser.add_argument("--out", default=os.path.join(HERE, "results", "batch_speed.md"))
    args = parser.parse_args()

    sys.path.insert(0, os.path.join(ROOT, "src"))
    from robodesc.validation.corpora import all_robots

    sizes = sorted({int(s) for s in args.sizes.split(",") if s})
    robots = all_robots(SHARED_CORPUS)[: max(sizes)]
    exe = args.robodesc or _exe()
    if not os.path.exists(args.peer):
        raise SystemExit(f"peer not installed at {args.peer} (see the module docstring)")
    load_before = os.getloadavg()[0]
    work = tempfile.mkdtemp(prefix="batch-bench-")
    rows: list[dict[str, Any]] = []
    modes: dict[str, dict[int, float]] = {}
    try:
        # ---- the two loops, robot by robot ------------------------------------------------
        for index, robot in enumerate(robots):
            row: dict[str, Any] = {"robot": f"{robot.corpus}/{robot.name}"}
            out = os.path.join(work, f"cli{index}", "robot.usda")
            for _ in range(args.repeat):
                if robot.path.endswith(".urdf"):
                    peer_dir = os.path.join(work, f"peer{index}")
                    shutil.rmtree(peer_dir, ignore_errors=True)
                    ok, secs, err = _run([args.peer, robot.path, peer_dir, *_pkg_args(robot)])
                    if secs < row.get("peer_s", float("inf")):
                        row.update(peer_ok=ok, peer_s=secs, peer_err=err)
                ok, secs, err = _run([exe, "compile", robot.path, "-o", out, *OPTIONS, "-q", *_pkg_args(robot)])
                if secs < row.get("cli_s", float("inf")):
                    row.update(cli_ok=ok, cli_s=secs, cli_err=err)
            secs = row["cli_s"]
            rows.append(row)
            print(
                f"{row['robot'][:60]:60s} peer {row.get('peer_s', float('nan')):6.2f}s  robodesc compile {secs:5.2f}s",
                flush=True,
            )
        # ---- batch modes --------------------------------------------------------------------
        batch_modes = [("batch --jobs 1", ["-j", "1"]), ("batch --jobs 2", ["-j", "2"])]
        if not args.no_ray:
            batch_modes.append(("batch --executor ray --jobs 2", ["-j", "2", "--executor", "ray"]))
        for size, _round, (name, extra) in (
            (size, r, mode) for size in sizes for r in range(args.repeat) for mode in batch_modes
        ):
            manifest = os.path.join(work, f"manifest{size}.yaml")
            _manifest(robots[:size], manifest)
            out = os.path.join(work, f"batch-{_slug(name)}-{size}")
            cmd = [exe, "batch", manifest, "-o", out, *OPTIONS, *extra, "--force", "-q"]
            ok, secs, err = _run(cmd)
            with open(os.path.join(out, "summary.json"), encoding="utf-8") as handle:
                summary = json.load(handle)
            best = modes.setdefault(name, {}).get(size)
            if best is not None and best <= secs:
                print(f"{name:32s} {size:4d} robots {secs:7.2f}s (best so far {best:.2f}s)", flush=True)
                continue
            modes[name][size] = secs
            by_outcome = {k: v for k, v in summary["totals"]["by_outcome"].items() if v}
            print(f"{name:32s} {size:4d} robots {secs:7.2f}s  {by_outcome}", flush=True)
            if size == max(sizes):
                for row, job in zip(rows, summary["jobs"], strict=True):
                    row[f"{name} job_s"] = job["seconds"]
                    row[f"{name} status"] = job["status"]
        for size in sizes:
            modes.setdefault("robodesc compile loop", {})[size] = sum(r["cli_s"] for r in rows[:size])
            modes.setdefault("peer loop (URDF robots)", {})[size] = sum(r.get("peer_s", 0.0) for r in rows[:size])
    finally:
        shutil.rmtree(work, ignore_errors=True)
    # Other work on the machine takes cores from the parallel modes: say how busy it was.
    env_note = (
        f"{os.cpu_count()} cores, Python {sys.version.split()[0]}; "
        f"load average {load_before:.1f} at the start, {os.getloadavg()[0]:.1f} at the end"
    )
    report = _report(rows, modes, sizes, env_note)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w", encoding="utf-8") as handle:
        handle.write(report)
    with open(os.path.splitext(args.out)[0] + ".json", "w", encoding="utf-8") as handle:
        json.dump({"modes": modes, "robots": rows}, handle, indent=1)
    print(report.split("\n## Robots")[0])
    return 0


def _report(rows: list[dict[str, Any]], modes: dict[str, dict[int, float]], sizes: list[int], env: str) -> str:
    peer = modes["peer loop (URDF robots)"]
    big, small = max(sizes), min(sizes)
    peer_robots = {n: sum(1 for r in rows[:n] if "peer_s" in r) for n in sizes}
    lines = [
        "# robodesc batch: speed",
        "",
        f"Generated by `benchmarks/batch_speed.py` ({env}). The corpus to USD, validation off, the peer's",
        "output shape (layered + physics scene). Wall time of whole commands, the best of several runs.",
        f"The peer (NVIDIA's urdf-usd-converter) reads URDF only: its loop covers the {peer_robots[big]} URDF robots",
        f"of the {big}, the others' modes all {big} (so the ratios understate robodesc slightly).",
        "",
        "| mode | "
        + " | ".join(f"{n} robots: s | robots/s | x peer loop" for n in sizes)
        + f" | growth {small}->{big} |",
        "|---|" + "---|---|---|" * len(sizes) + "---|",
    ]
    for name, times in modes.items():
        cells = []
        for n in sizes:
            t = times[n]
            ratio = f"x{peer[n] / t:.1f}" if peer[n] else "–"
            cells.append(f"{t:.1f} | {n / t:.2f} | {ratio}")
        growth = times[big] / times[small] if times.get(small) else float("nan")
        lines.append(f"| {name} | " + " | ".join(cells) + f" | x{growth:.1f} |")
    j1, j2 = modes["batch --jobs 1"][big], modes["batch --jobs 2"][big]
    lines += [
        "",
        f"- batch --jobs 2 against the peer's loop, {big} robots: x{peer[big] / j2:.1f} (target x20)",
        f"- batch --jobs 2 against batch --jobs 1: x{j1 / j2:.2f} (target x1.7)",
        f"- batch --jobs 2 against the loop of `robodesc compile`: x{modes['robodesc compile loop'][big] / j2:.1f}",
        "",
        "## Robots",
        "",
        "Per robot: the peer's process, robodesc compile's process, and the job's own time inside a batch",
        "worker (imports already paid).",
        "",
        "| robot | peer s | robodesc compile s | batch --jobs 1 job s | status |",
        "|---|---|---|---|---|",
    ]
    for r in rows:
        peer_cell = f"{r['peer_s']:.2f}" + ("" if r.get("peer_ok") else " FAIL") if "peer_s" in r else "n/a (xacro)"
        cli = f"{r['cli_s']:.2f}" + ("" if r["cli_ok"] else " FAIL")
        job = r.get("batch --jobs 1 job_s")
        lines.append(
            f"| {r['robot']} | {peer_cell} | {cli} | {job if job is not None else '–'} | {r.get('batch --jobs 1 status', '–')} |"
        )
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    sys.exit(main())
