"""ANYmal C dropped in PhysX, with and without its joint velocity limits (issue 38; docs/usd.md,
"Velocity limits, and ANYmal C dropped in PhysX").

    python benchmarks/physx_anymal_drop.py [--seconds 4] [--json out.json]

Compiles example-robot-data's ``anymal_c`` with ``-t usd --no-fix-base`` and ``--isaac-sim
--no-fix-base``, references each USD above a ground box in a scene with gravity, and steps it in
PhysX (ovphysx 0.7, CPU, 5 ms) through the interpreter ``robodesc.validation.physx_python`` finds.
Cases: the file as written; without its velocity limits (``newton:velocityLimit`` and
``physxJointAxis:*:maxJointVelocity`` removed); from a lower spawn height. Printed per case: the base
height every 0.5 s, the fastest joint speed (rad/s) and what PhysX read back as the limit (deg/s).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import runpy
import subprocess
import sys
import tempfile
from typing import Any

SCENE = """#usda 1.0
(
    defaultPrim = "World"
    metersPerUnit = 1
    kilogramsPerUnit = 1
    upAxis = "Z"
)
def Xform "World"
{{
    def PhysicsScene "PhysicsScene"
    {{
        vector3f physics:gravityDirection = (0, 0, -1)
        float physics:gravityMagnitude = 9.81
    }}
    def Cube "ground" (prepend apiSchemas = ["PhysicsCollisionAPI"])
    {{
        double size = 1
        double3 xformOp:translate = (0, 0, -0.5)
        float3 xformOp:scale = (20, 20, 1)
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:scale"]
    }}
    def "robot" (prepend references = @{robot}@)
    {{
        double3 xformOp:translate = (0, 0, {height})
        uniform token[] xformOpOrder = ["xformOp:translate"]
    }}
}}
"""


def worker(cases_path: str, out_path: str) -> None:
    """In PhysX's interpreter: step each scene, sample the base height and the joint speeds."""
    import numpy as np
    import ovphysx
    import ovstage
    from ovphysx import PhysX
    from ovphysx.samples.python_samples.schema_support import physx_schema_paths
    from ovphysx.types import ObjectScope, SimObjectType

    with open(cases_path, encoding="utf-8") as fh:
        cases = json.load(fh)
    ovstage.population.register_usd_schemas(
        [*[str(p) for p in physx_schema_paths()], str(ovphysx.newton_schema_root())]
    )
    physx = PhysX()

    def read(kind: Any, attr: str) -> tuple[Any, list[str]]:
        rows, names = [], []
        with physx.read_sync(kind, [attr], scope=ObjectScope.ALL) as result:
            for group in result.groups:
                if group.is_delete or not group.tensors:
                    continue
                arrays = [np.asarray(t.numpy(), dtype=float) for t in group.tensors]
                if len(arrays) == 1 and group.prim_count > 1:
                    rows.append(arrays[0].reshape(group.prim_count, -1))
                else:  # one tensor per prim (articulation joints)
                    rows.append(np.stack([a.ravel() for a in arrays]))
                names += list(result.dictionary.get_path_strings(group.prim_list))
        return np.concatenate(rows), names

    out = []
    for ordinal, case in enumerate(cases, start=1):
        stage = ovstage.Stage(f"case{ordinal}")
        ovstage.population.open_usd(stage, case["scene"], ordinal=ordinal, domains=ovstage.PopulationDomain.ALL)
        stage.advance_write_floor(ordinal=ordinal).wait()
        physx.wait_task(physx.attach_ovstage(stage, read_ordinal=ordinal))
        _, links = read(SimObjectType.ARTICULATION_LINK, "position")
        base = next(i for i, name in enumerate(links) if name.endswith("/base"))
        limits, _ = read(SimObjectType.ARTICULATION_JOINT, "jointMaxVelocity")
        dt, heights, fastest = 0.005, [], 0.0
        for step in range(1, round(case["seconds"] / dt) + 1):
            physx.step_sync(dt)
            speeds, _ = read(SimObjectType.ARTICULATION_JOINT, "jointVelocity")
            fastest = max(fastest, float(np.abs(speeds).max()))
            if step % 100 == 0:
                heights.append(round(float(read(SimObjectType.ARTICULATION_LINK, "position")[0][base][2]), 4))
        out.append({"heights": heights, "fastest_rad_s": math.radians(fastest), "limit_deg_s": float(limits.min())})
        physx.wait_task(physx.detach_ovstage())
        stage.destroy()
    physx.destroy()
    with open(out_path, "w", encoding="utf-8") as fh:
        json.dump(out, fh)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=4.0)
    parser.add_argument("--json")
    parser.add_argument("--worker", nargs=2, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:
        worker(*args.worker)
        return
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src"))
    import robodesc
    from robodesc.validation.corpora import example_robot_data_robots
    from robodesc.validation.physx_python import physx_python

    python = physx_python()
    if python is None:
        sys.exit("PhysX (ovphysx) is not installed: tests/consumers/run.sh builds it")
    source = next(r.path for r in example_robot_data_robots() if r.name.startswith("anymal_c"))
    tmp = tempfile.mkdtemp(prefix="anymal-physx-")
    usd = os.path.join(tmp, "anymal.usda")
    robodesc.compile_to(source, "usd", usd, fix_base=False, validate=False)
    isaac = robodesc.compile_for_isaac_sim(source, os.path.join(tmp, "isaac"), fix_base=False, validate=False)
    unlimited = os.path.join(tmp, "unlimited.usda")
    with open(usd, encoding="utf-8") as fh:
        text = fh.read()
    with open(unlimited, "w", encoding="utf-8") as fh:
        fh.write(re.sub(r"\n\s*float (newton:velocityLimit|physxJointAxis:\w+:maxJointVelocity) = [^\n]*", "", text))
    cases = {
        "-t usd, dropped from 0.75 m": (usd, 0.75),
        "-t usd without velocity limits, 0.75 m": (unlimited, 0.75),
        "-t usd, dropped from 0.64 m": (usd, 0.64),
        "-t usd without velocity limits, 0.64 m": (unlimited, 0.64),
        "--isaac-sim, 5 cm above its spawn height": (isaac.files["usd"], None),
    }
    specs = []
    for i, (robot, height) in enumerate(cases.values()):
        if height is None:
            module = runpy.run_path(isaac.files["isaaclab"])
            height = module["ROBOT"]["init_state"]["pos"][2] + 0.05
        scene = os.path.join(tmp, f"scene{i}.usda")
        with open(scene, "w", encoding="utf-8") as fh:
            fh.write(SCENE.format(robot=robot, height=height))
        specs.append({"scene": scene, "seconds": args.seconds})
    with open(os.path.join(tmp, "cases.json"), "w", encoding="utf-8") as fh:
        json.dump(specs, fh)
    out = os.path.join(tmp, "out.json")
    done = subprocess.run(
        [python, os.path.abspath(__file__), "--worker", os.path.join(tmp, "cases.json"), out], check=False
    )
    if done.returncode != 0:
        sys.exit(f"the PhysX worker failed (exit {done.returncode})")
    with open(out, encoding="utf-8") as fh:
        results = dict(zip(cases, json.load(fh), strict=True))
    for name, result in results.items():
        limit = result["limit_deg_s"]
        read = f"{limit:.3f} deg/s" if limit < 1e30 else "none"
        print(
            f"{name}: base z every 0.5 s {result['heights']}, fastest joint {result['fastest_rad_s']:.2f} rad/s, "
            f"limit PhysX read {read}"
        )
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump(results, fh, indent=1)


if __name__ == "__main__":
    main()
