"""Quad-SDK's five worlds with Spirit and Go2 (issue 33): compile time per target, the heightfield's
error against the terrain mesh, where the robot is spawned, and how it stands on each world in
every engine that reads the terrain.

    python benchmarks/worlds.py [--robots spirit,go2] [--worlds flat,...] [--engines mujoco,physx,newton]
                                [--json F] [--md F]

Each robot is compiled from its xacro with ``--world WORLD --contact-sensors`` for -t mjcf, usd and
sdf (one process, timed around ``robodesc.compile_to``; MJCF and USD with the USD drives' gains, kp
100 and kd 1, as ``validate --dynamics -t usd`` runs them). Then the stand of ``validate --dynamics
--world`` (docs/dynamics.md, "On a world") runs in MuJoCo (scene.xml's hfield), PhysX and Newton
(the USD world stage; Newton with the terrain as a heightfield): the root's height over the ground
under each foot, tilt, slip of the soles, the contact sensors against the weight, and the
engines' agreement. Drake has no heightfield: not run. Results: benchmarks/results/worlds.md and .json.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import tempfile
import time
from typing import Any

import robodesc
from robodesc.check_dynamics import default_stance
from robodesc.check_world import world_stand
from robodesc.frontends.load import load_source
from robodesc.ir.diagnostics import Findings
from robodesc.options import build_options
from robodesc.validation.dynamics import DynamicsOptions
from robodesc.validation.dynamics.result import DynamicsReport
from robodesc.validation.dynamics.run import _stand
from robodesc.validation.dynamics.scenarios import Thresholds, make_setup
from robodesc.validation.dynamics.verdict import judge

HERE = os.path.dirname(os.path.abspath(__file__))
QUADSDK = os.path.join(HERE, "..", "..", "shared", "corpus", "quadsdk")
ROBOTS = {
    "spirit": os.path.join(QUADSDK, "spirit_description/models/spirit/urdf/spirit.urdf.xacro"),
    "go2": os.path.join(QUADSDK, "go2_description/models/go2/urdf/go2.urdf.xacro"),
}
WORLDS = ["flat", "step_20cm", "gap_40cm", "slope_20", "rough_25cm"]
TARGETS = {"mjcf": "robot.xml", "usd": "robot.usda", "sdf": "robot.sdf"}
GAINS = {"stiffness": 100.0, "damping": 1.0}  # the USD target's drives, given to MJCF too


def measure(robot_key: str, world: str, engines: tuple[str, ...]) -> dict[str, Any]:
    world_file = os.path.join(QUADSDK, "worlds", world, f"{world}.world")
    row: dict[str, Any] = {"robot": robot_key, "world": world}
    with tempfile.TemporaryDirectory() as tmp:
        results = {}
        for target, name in TARGETS.items():
            out = os.path.join(tmp, target, name)
            extra = GAINS if target == "mjcf" else {}
            t0 = time.perf_counter()
            results[target] = robodesc.compile_to(
                ROBOTS[robot_key], target, out, world=world_file, contact_sensors=True, **extra
            )
            row[f"{target}_s"] = round(time.perf_counter() - t0, 2)
        findings = results["mjcf"].findings
        notes = [f.message for f in findings if f.code == "world-heightfield"]
        row["heightfield"] = notes[0] if notes else "a box (flat)"
        moved = [f.message for f in findings if f.code.startswith("world-spawn")]
        row["spawn_note"] = moved[0] if moved else ""
        robot = load_source(ROBOTS[robot_key], build_options({}).load, Findings())
        opts = default_stance(robot, DynamicsOptions(engines=engines, **GAINS))
        sensors = tuple(s.parent for s in results["usd"].robot.sensors if s.type.value == "contact")
        files = {"mjcf": results["mjcf"].files["scene"], "usd": results["usd"].files["world"]}
        opts.world = world_stand(robot, opts, {"world": world_file}, files, sensors, tmp)
        row["spawn"] = [round(v, 3) for v in opts.world.spawn[:2]]
        setup = make_setup(robot, opts)
        report = DynamicsReport(robot=robot.name)
        _stand(robot, setup, opts, report, set(engines))
        judge(report, setup, opts.thresholds)
        for run in report.runs:
            row[run.engine] = {
                "ok": run.ok,
                "error": run.error,
                "height": round(sum(run.feet_height.values()) / len(run.feet_height), 4) if run.feet_height else None,
                "feet_height": {k: round(v, 4) for k, v in run.feet_height.items()},
                "tilt_deg": None if run.tilt is None else round(math.degrees(run.tilt), 2),
                "slip": None if run.slip is None else round(run.slip, 4),
                "sole_gap": None if run.sole_gap is None else round(run.sole_gap, 4),
                "contact_sum": None if run.contact_sum is None else round(run.contact_sum, 2),
                "weight": None if run.weight is None else round(run.weight, 2),
                "seconds": round(run.seconds, 1),
            }
        row["checks"] = [
            {"name": c.name, "status": c.status.value, "element": c.element, "message": c.message}
            for c in report.checks
        ]
    return row


def _cell(run: dict[str, Any] | None) -> str:
    if run is None:
        return "-"
    if not run["ok"]:
        return f"failed: {run['error'][:60]}"
    out = f"{run['height']:.3f} m, {run['tilt_deg']:.1f}°, slip {run['slip'] * 100:.1f} cm"
    if run["contact_sum"] is not None:
        out += f"; sensors {run['contact_sum'] / run['weight']:.1%} of the weight"
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--robots", default=",".join(ROBOTS))
    parser.add_argument("--worlds", default=",".join(WORLDS))
    parser.add_argument("--engines", default="mujoco,physx,newton")
    parser.add_argument("--json", default=os.path.join(HERE, "results", "worlds.json"))
    parser.add_argument("--md", default=os.path.join(HERE, "results", "worlds.md"))
    parser.add_argument("--md-only", action="store_true", help="write the table from the --json file, run nothing")
    args = parser.parse_args()
    engines = tuple(args.engines.split(","))
    rows: list[dict[str, Any]] = []
    if args.md_only:
        with open(args.json) as handle:
            rows = json.load(handle)
    else:
        for robot in args.robots.split(","):
            for world in args.worlds.split(","):
                rows.append(measure(robot, world, engines))
                print(json.dumps(rows[-1]), flush=True)
        with open(args.json, "w") as handle:
            json.dump(rows, handle, indent=2)
    write_table(rows, engines, args.md)


def agree(row: dict[str, Any], engines: tuple[str, ...]) -> str:
    """Every pair of engines within agree:stand's thresholds (mean height over the ground, tilt)."""
    th = Thresholds()
    runs = [row[e] for e in engines if row.get(e) and row[e]["ok"] and row[e]["height"] is not None]
    if len(runs) < 2:
        return "-"
    worst_h = max(abs(a["height"] - b["height"]) for a in runs for b in runs)
    worst_t = max(abs(a["tilt_deg"] - b["tilt_deg"]) for a in runs for b in runs)
    ok = worst_h <= th.drop_height_agree and math.radians(worst_t) <= th.drop_tilt_agree
    return f"{'yes' if ok else 'no'} ({worst_h * 1000:.0f} mm, {worst_t:.1f}°)"


def write_table(rows: list[dict[str, Any]], engines: tuple[str, ...], md: str) -> None:
    lines = [
        "# Quad-SDK's worlds (benchmarks/worlds.py)",
        "",
        "`--world WORLD --contact-sensors`, MJCF and USD drives kp 100 / kd 1. The stand of `validate --dynamics",
        "--world`, 2 s: the root's height over the ground under the feet (their mean), tilt, the soles' slip, and",
        "the feet's contact sensors (MuJoCo touch, PhysX contact report) against the weight. Drake: not run (no",
        "heightfield). Compile times measured while other jobs shared the machine's two cores (load average 25 to",
        "31 during this run): upper bounds that do not compare between runs; the placement alone, timed apart, went",
        "from 2.26 s to 0.55 s on rough_25cm (docs/worlds.md). At the origin flat, step_20cm, gap_40cm and slope_20",
        "are all level ground (their step, gap and slope lie metres ahead): those four rows stand on the same ground.",
        "",
        "| robot | world | mjcf s | usd s | sdf s | spawn | "
        + " | ".join(engines)
        + " | engines agree (largest difference) |",
        "|---|---|---|---|---|---|" + "---|" * len(engines) + "---|",
    ]
    for r in rows:
        verdict = agree(r, engines)
        cells = " | ".join(_cell(r.get(e)) for e in engines)
        lines.append(
            f"| {r['robot']} | {r['world']} | {r['mjcf_s']} | {r['usd_s']} | {r['sdf_s']} | "
            f"({r['spawn'][0]:g}, {r['spawn'][1]:g}) | {cells} | {verdict} |"
        )
    lines += ["", "Spawn and heightfield notes:", ""]
    for r in rows:
        if r["spawn_note"]:
            lines.append(f"- {r['robot']} on {r['world']}: {r['spawn_note']}")
    for r in rows:
        lines.append(f"- {r['robot']} on {r['world']}: {r['heightfield']}")
    before = os.path.join(os.path.dirname(md), "worlds_before.json")
    if os.path.isfile(before):
        with open(before) as handle:
            old = json.load(handle)
        lines += [
            "",
            "## Before (commit d957372: every target rasterized every terrain; no level spawn)",
            "",
            "The same machine, an hour earlier, under the same kind of load; MuJoCo ran scene.xml from `home`",
            "for 3 s at the origin (the robot's derived gains), no other engine.",
            "",
            "| robot | world | mjcf s | usd s | sdf s | MuJoCo: base over the ground under it, tilt, slip |",
            "|---|---|---|---|---|---|",
        ]
        for r in old:
            lines.append(
                f"| {r['robot']} | {r['world']} | {r['mjcf_s']} | {r['usd_s']} | {r['sdf_s']} | "
                f"{r['height']:.3f} m, {r['tilt_deg']:.1f}°, {r['slip'] * 100:.1f} cm |"
            )
    with open(md, "w") as handle:
        handle.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
