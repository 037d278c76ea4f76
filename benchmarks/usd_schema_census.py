"""How many applied API schemas and physics attributes of robodesc's USD no registered schema defines
(issue 38): the Quad-SDK robots and a sample of example-robot-data, through ``-t usd`` and
``--isaac-sim``, counted by ``robodesc.validation.usd_schemas.census``.

    python benchmarks/usd_schema_census.py [--src DIR] [--every N] [--json out.json]

``--src`` compiles with another checkout's ``src`` (main's, for the count before a change); the
census always runs with this checkout's check, against physx-usd-schemas and newton-usd-schemas.
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "src"))

from robodesc.validation.corpora import CorpusRobot, example_robot_data_robots, quadsdk_robots  # noqa: E402
from robodesc.validation.usd_schemas import census, register_schemas  # noqa: E402

SHARED = os.path.join(HERE, "..", "..", "shared", "corpus")


def compile_usd(robot: CorpusRobot, src: str, out_dir: str, isaac: bool) -> str | None:
    args = [sys.executable, "-m", "robodesc", "compile", robot.path, "--no-validate"]
    for name, folder in robot.packages.items():
        args += ["--package", f"{name}={folder}"]
    for name, value in robot.xacro_args.items():
        args += ["--arg", f"{name}={value}"]
    if isaac:
        folder = os.path.join(out_dir, "isaac")
        args += ["--isaac-sim", "-o", folder]
    else:
        args += ["-t", "usd", "-o", os.path.join(out_dir, "robot.usda")]
    env = {**os.environ, "PYTHONPATH": src}
    done = subprocess.run(args, env=env, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        return None
    if not isaac:
        return os.path.join(out_dir, "robot.usda")
    usdas = [f for f in os.listdir(folder) if f.endswith(".usda")]
    return os.path.join(folder, usdas[0]) if usdas else None


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--src", default=os.path.join(HERE, "..", "src"))
    parser.add_argument("--every", type=int, default=7, help="every Nth example-robot-data robot")
    parser.add_argument("--json")
    args = parser.parse_args()
    register_schemas()
    from pxr import Usd

    robots = quadsdk_robots(SHARED) + example_robot_data_robots()[:: args.every]
    rows = []
    totals: collections.Counter[str] = collections.Counter()
    kinds: collections.Counter[str] = collections.Counter()
    for robot in robots:
        for isaac in (False, True):
            with tempfile.TemporaryDirectory() as tmp:
                path = compile_usd(robot, os.path.abspath(args.src), tmp, isaac)
                if path is None:
                    rows.append({"robot": robot.name, "isaac": isaac, "error": "compile failed"})
                    continue
                seen = census(Usd.Stage.Open(path))
            row = {
                "robot": robot.name,
                "isaac": isaac,
                "api_schemas": seen.api_schemas,
                "attributes": seen.attributes,
                "unknown_schemas": len(seen.unknown_schemas),
                "unknown_attributes": len(seen.unknown_attributes),
            }
            rows.append(row)
            totals.update({k: v for k, v in row.items() if isinstance(v, int) and not isinstance(v, bool)})
            kinds.update(name for _, name, _ in seen.unknown_schemas)
            kinds.update(name for _, name, _ in seen.unknown_attributes)
            print(json.dumps(row), flush=True)
    summary = {"robots": len(robots), "totals": dict(totals), "unknown_by_name": dict(kinds.most_common())}
    print(json.dumps(summary, indent=1))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump({"rows": rows, "summary": summary}, fh, indent=1)


if __name__ == "__main__":
    main()
