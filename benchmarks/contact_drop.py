"""Spirit with its Gazebo contact parameters, dropped onto a plane: MuJoCo reading robodesc's MJCF
against Newton reading robodesc's USD, with and without ``--preset gazebo_parity`` (issues 25, 28).

    python benchmarks/contact_drop.py [--robot spirit|go2] [--json out.json]

Each robot stands in Quad-SDK's stand pose (hips 0.76, knees 1.52 rad), drives holding it with the
same SI gains in both engines, dropped from 5 cm above its standing height; after 1 s the base
height and tilt of each engine are printed, with the difference. Also the slide scenario's friction
each engine read. Newton runs in the consumer tier's venv (tests/consumers/run.sh builds it).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys

import robodesc

SHARED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "corpus", "quadsdk")
ROBOTS = {
    "spirit": (
        os.path.join(SHARED, "spirit_description/models/spirit/urdf/spirit.urdf.xacro"),
        {"0|2|4|6": 0.76, "1|3|5|7": 1.52},
    ),
    # Quad-SDK's Go2 names its joints as Spirit does (hip 0/2/4/6, knee 1/3/5/7; abduction 8-11).
    "go2": (
        os.path.join(SHARED, "go2_description/models/go2/urdf/go2.urdf.xacro"),
        {"0|2|4|6": 0.8, "1|3|5|7": -1.5},
    ),
}


def run(robot: str, preset: str | None) -> dict[str, object]:
    path, pose = ROBOTS[robot]
    options = {"fix_base": False, "stiffness": 100.0, "damping": 2.0}
    if preset:
        options["preset"] = preset
    result = robodesc.check(path, "mjcf", dynamics={"engines": ("mujoco", "newton"), "pose": pose}, **options)
    dyn = result.dynamics
    rows = {f"{r.engine}/{r.file}/{r.scenario}": r for r in dyn.runs} if dyn is not None else {}
    out: dict[str, object] = {"robot": robot, "preset": preset or "-", "ok": bool(dyn and dyn.ok)}
    for key, r in rows.items():
        out[key] = {
            "height": r.height,
            "tilt_deg": None if r.tilt is None else math.degrees(r.tilt),
            "mu": r.mu,
            "error": r.error,
        }
    drops = [r for r in rows.values() if r.scenario == "drop" and r.height is not None]
    if len(drops) == 2:
        a, b = drops
        out["height_difference_m"] = abs(a.height - b.height)  # type: ignore[operator]
        out["tilt_difference_deg"] = abs(math.degrees((a.tilt or 0) - (b.tilt or 0)))
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--robot", action="append", choices=sorted(ROBOTS))
    parser.add_argument("--json")
    args = parser.parse_args()
    results = [run(robot, preset) for robot in (args.robot or ["spirit"]) for preset in (None, "gazebo_parity")]
    for r in results:
        print(json.dumps(r))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as handle:
            json.dump(results, handle, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
