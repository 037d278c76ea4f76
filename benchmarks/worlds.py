"""Quad-SDK's five worlds with Spirit and Go2 (issue 33): compile time per target, the heightfield's
error against the terrain mesh, and how each robot stands on each world in MuJoCo.

    python benchmarks/worlds.py [--robots spirit,go2] [--worlds flat,...] [--json F] [--md F]

Each robot is compiled from its xacro with default flags and ``--world WORLD`` for -t mjcf, usd and
sdf (one process, timed around ``robodesc.compile_to``). MuJoCo then runs the MJCF's scene.xml
from its ``home`` keyframe for 3 s: the base's height over the terrain under it, its tilt, and how
far it slid. Results: benchmarks/results/worlds.md and .json.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import tempfile
import time
from typing import Any

import mujoco
import numpy as np

import robodesc

HERE = os.path.dirname(os.path.abspath(__file__))
QUADSDK = os.path.join(HERE, "..", "..", "shared", "corpus", "quadsdk")
ROBOTS = {
    "spirit": os.path.join(QUADSDK, "spirit_description/models/spirit/urdf/spirit.urdf.xacro"),
    "go2": os.path.join(QUADSDK, "go2_description/models/go2/urdf/go2.urdf.xacro"),
}
WORLDS = ["flat", "step_20cm", "gap_40cm", "slope_20", "rough_25cm"]
TARGETS = {"mjcf": "robot.xml", "usd": "robot.usda", "sdf": "robot.sdf"}


def ground(model: Any, data: Any, x: float, y: float) -> float:
    geomid = np.array([-1], dtype=np.int32)
    groups = np.array([1, 0, 0, 0, 0, 0], dtype=np.uint8)
    dist = mujoco.mj_ray(model, data, np.array([x, y, 10.0]), np.array([0.0, 0.0, -1.0]), groups, 1, -1, geomid)
    return 10.0 - dist if dist >= 0 else math.nan


def stand(scene: str, seconds: float = 3.0) -> dict[str, float]:
    model = mujoco.MjModel.from_xml_path(scene)
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    start = data.qpos[:3].copy()
    t0 = time.perf_counter()
    for _ in range(int(seconds / model.opt.timestep)):
        mujoco.mj_step(model, data)
    wall = time.perf_counter() - t0
    x, y, z = data.qpos[:3]
    up = float(data.xmat[1].reshape(3, 3)[2, 2])
    return {
        "height": float(z - ground(model, data, x, y)),
        "tilt_deg": math.degrees(math.acos(max(-1.0, min(1.0, up)))),
        "slip": float(math.hypot(x - start[0], y - start[1])),
        "realtime": seconds / wall,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--robots", default=",".join(ROBOTS))
    parser.add_argument("--worlds", default=",".join(WORLDS))
    parser.add_argument("--json", default=os.path.join(HERE, "results", "worlds.json"))
    parser.add_argument("--md", default=os.path.join(HERE, "results", "worlds.md"))
    args = parser.parse_args()
    rows: list[dict[str, Any]] = []
    for robot in args.robots.split(","):
        for world in args.worlds.split(","):
            world_file = os.path.join(QUADSDK, "worlds", world, f"{world}.world")
            row: dict[str, Any] = {"robot": robot, "world": world}
            with tempfile.TemporaryDirectory() as tmp:
                for target, name in TARGETS.items():
                    out = os.path.join(tmp, target, name)
                    t0 = time.perf_counter()
                    result = robodesc.compile_to(ROBOTS[robot], target, out, world=world_file)
                    row[f"{target}_s"] = round(time.perf_counter() - t0, 2)
                    if target == "mjcf":
                        notes = [f.message for f in result.findings if f.code == "world-heightfield"]
                        row["heightfield"] = notes[0] if notes else "a box (flat)"
                        row.update(stand(os.path.join(tmp, target, "scene.xml")))
            rows.append(row)
            print(json.dumps(row))
    with open(args.json, "w") as handle:
        json.dump(rows, handle, indent=2)
    lines = [
        "# Quad-SDK's worlds (benchmarks/worlds.py)",
        "",
        "Default flags and `--world WORLD`; MuJoCo runs scene.xml from `home` for 3 s.",
        "",
        "| robot | world | mjcf s | usd s | sdf s | height over terrain m | tilt ° | slip m | heightfield |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['robot']} | {r['world']} | {r['mjcf_s']} | {r['usd_s']} | {r['sdf_s']} | {r['height']:.3f} | "
            f"{r['tilt_deg']:.1f} | {r['slip']:.3f} | {r['heightfield']} |"
        )
    with open(args.md, "w") as handle:
        handle.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
