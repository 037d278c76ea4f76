"""The Isaac Sim 6 route, proven: robodesc's physics layer over Isaac Sim 6.2's own URDF import, read in PhysX.

    python tests/consumers/isaac6_layer.py --envs ~/.cache/robodesc-consumers [--robots quadruped,panda,...]
        [--out benchmarks/results/isaac6_layer.json]

For every robot (the bundled examples, then corpus robots from ``robodesc.validation.corpora``):

1. ``--isaac-sim`` (floating robots ``--no-fix-base``, as run_tier.py decides) with
   ``--physics-scene`` into a work folder; the time ``<robot>_physics.usda`` took is measured inside
   the compile (``folder.importer_physics_layer``);
2. Isaac Sim 6.2's importer (``isaac_import.py``, the ``isaacsim`` venv) imports the folder's URDF
   with the folder's ``importer_settings.json``;
3. the layer is made again from that import (``layout_from_usd``: what ``robodesc layer --onto`` does)
   and must equal the folder's (the naming rules predicted every path) and find every prim;
4. PhysX (ovphysx, its own venv; ``isaac6_physx_read.py``) reads three stages: robodesc's own USD,
   the import with ``importer_settings.json`` alone, and the import with the layer sublayered over it
   (its ``physx`` variant selected, as the importer leaves it unselected). Each link's mass,
   inertia and shapes' friction (the distinct values) and each joint's stiffness, damping, limits, effort and velocity bounds, armature and
   friction must equal robodesc's own USD (relative 1e-5, absolute 1e-9: float32 USD values).

Results: one JSON object per robot; ``--out`` keeps them all.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "src"))

EXAMPLES = {"quadruped": "examples/quadruped.yaml", "arm6_gripper": "examples/arm6_gripper.yaml"}
REL, ABS = 1e-5, 1e-9
PER_SHAPE = ("staticFriction", "dynamicFriction")


def _close(a: list[float], b: list[float]) -> bool:
    if len(a) != len(b):
        return False
    # FLT_MAX (PhysX's "free") equals itself; anything else within float32 rounding.
    return all(x == y or math.isclose(x, y, rel_tol=REL, abs_tol=ABS) for x, y in zip(a, b, strict=True))


def compare(reference: dict[str, Any], other: dict[str, Any], names: dict[str, str]) -> list[str]:
    """Every link, joint and articulation quantity of ``other`` that differs from ``reference`` (or
    is missing). ``names``: the importer's prim name -> the IR name, where the importer renamed
    (a child link named like a sibling visual becomes ``base_2``)."""
    diffs: list[str] = []
    for kind in ("links", "joints"):
        theirs_by_name = {names.get(leaf, leaf): values for leaf, values in other[kind].items()}
        for name, values in reference[kind].items():
            theirs = theirs_by_name.get(name)
            if theirs is None:
                diffs.append(f"{kind[:-1]} {name}: missing")
                continue
            for attr, ours in values.items():
                got = theirs.get(attr, [])
                if attr in PER_SHAPE:  # the importer may split a mesh into several shapes
                    ours, got = sorted(set(ours)), sorted(set(got))
                if not _close(ours, got):
                    diffs.append(f"{kind[:-1]} {name} {attr}: {theirs.get(attr)} (robodesc USD {ours})")
    # One articulation each (keyed by the root API's prim, which differs between the layouts).
    ours_art = sorted(map(str, reference["articulations"].values()))
    theirs_art = sorted(map(str, other["articulations"].values()))
    if ours_art != theirs_art:
        diffs.append(f"articulations: {theirs_art} (robodesc USD {ours_art})")
    return diffs


def composed_stage(path: str, robot: str, sublayers: list[str], scene: bool) -> None:
    """A root layer sublayering ``sublayers`` (strongest first), with the importer's ``physx``
    variant selected (and a scene when no sublayer brings one)."""
    subs = ", ".join(f"@{os.path.abspath(s)}@" for s in sublayers)
    text = (
        f'#usda 1.0\n(\n    defaultPrim = "{robot}"\n    metersPerUnit = 1\n    kilogramsPerUnit = 1\n'
        f'    upAxis = "Z"\n    subLayers = [{subs}]\n)\n\n'
        f'over "{robot}" (\n    variants = {{\n        string Physics = "physx"\n    }}\n)\n{{\n}}\n'
    )
    if scene:
        text += '\ndef PhysicsScene "PhysicsScene"\n{\n}\n'
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(text)


def run_robot(name: str, source: str, extra: dict[str, Any], envs: str, work: str) -> dict[str, Any]:
    import robodesc
    import robodesc.emit.isaac.folder as folder
    from robodesc.emit.isaac.importer_layout import layout_from_rules, layout_from_usd
    from robodesc.emit.isaac.physics_layer import physics_layer
    from robodesc.ir.diagnostics import Findings
    from robodesc.validation.physx_python import physx_python

    out: dict[str, Any] = {"robot": name}
    here = os.path.join(work, name)
    isaac = os.path.join(here, "isaac")
    os.makedirs(here, exist_ok=True)
    timed: list[float] = []
    original = folder.importer_physics_layer

    def timing(*args: Any, **kwargs: Any) -> str:
        start = time.perf_counter()
        try:
            return original(*args, **kwargs)
        finally:
            timed.append(time.perf_counter() - start)

    folder.importer_physics_layer = timing  # type: ignore[assignment]
    start = time.perf_counter()
    try:
        result = robodesc.compile_for_isaac_sim(source, isaac, physics_scene=True, **extra)
    finally:
        folder.importer_physics_layer = original  # type: ignore[assignment]
    out["compile_s"] = round(time.perf_counter() - start, 2)
    out["layer_s"] = round(sum(timed), 3)
    out["layer_warnings"] = [f.message for f in result.findings if f.code == "isaac-layer-missing"]
    files = result.files
    imported = os.path.join(here, "import.json")
    python = os.path.join(envs, "isaacsim", "bin", "python")
    subprocess.run(
        [python, os.path.join(HERE, "isaac_import.py"), "--urdf", files["urdf"], "--settings",
         files["importer_settings"], "--out-dir", os.path.join(here, "imported"), "--out", imported],
        check=True, capture_output=True, text=True,
    )  # fmt: skip
    report = json.loads(Path(imported).read_text(encoding="utf-8"))
    out["import"] = report["status"]
    out["import_s"] = report["seconds"]
    if report["status"] != "pass":
        return out
    usd = report["usd"]
    # What `robodesc layer --onto` finds: the paths read from the import itself (the settings do
    # not change which prims are addressed).
    layout = layout_from_usd(usd, result.robot)
    settings = robodesc.emit.isaac.IsaacSettings(physics_scene=True)
    read = physics_layer(result.robot, folder.usd_options(settings), layout, Findings())
    out["prims_missing"] = read.missing
    # The naming rules are right when they predict every path the import has.
    rules = layout_from_rules(result.robot)
    out["rules_match_import"] = (rules.links, rules.joints, rules.colliders, rules.articulation_root) == (
        layout.links,
        layout.joints,
        layout.colliders,
        layout.articulation_root,
    )
    robot = layout.robot.lstrip("/")
    with_settings = os.path.join(here, "importer_settings_route.usda")
    with_layer = os.path.join(here, "layer_route.usda")
    composed_stage(with_settings, robot, [usd], scene=True)
    composed_stage(with_layer, robot, [files["physics_layer"], usd], scene=False)
    stages = os.path.join(here, "stages.json")
    with open(stages, "w", encoding="utf-8") as fh:
        json.dump([files["usd"], with_settings, with_layer], fh)
    physx = physx_python()
    if physx is None:
        out["physx"] = "skipped: no ovphysx"
        return out
    parsed = os.path.join(here, "physx.json")
    done = subprocess.run(
        [physx, os.path.join(HERE, "isaac6_physx_read.py"), stages, parsed], capture_output=True, text=True
    )
    if done.returncode != 0:
        out["physx"] = f"fail: {done.stderr.strip().splitlines()[-1:]}"
        return out
    own, settings_route, layer_route = json.loads(Path(parsed).read_text(encoding="utf-8"))["stages"]
    out["links"], out["joints"] = len(own["links"]), len(own["joints"])
    names = {path.rsplit("/", 1)[-1]: name for name, path in [*layout.links.items(), *layout.joints.items()]}
    out["importer_settings_diffs"] = compare(own, settings_route, names)
    out["layer_diffs"] = compare(own, layer_route, names)
    out["physx"] = "match" if not out["layer_diffs"] else f"{len(out['layer_diffs'])} differences"
    return out


def main(argv: list[str] | None = None) -> int:
    from run_tier import FLOATING

    from robodesc.validation.corpora import all_robots

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--envs", default=os.path.expanduser("~/.cache/robodesc-consumers"))
    ap.add_argument("--robots", default="quadruped,arm6_gripper", help="comma-separated names (examples, corpus)")
    ap.add_argument("--corpus", default=os.path.join(ROOT, "..", "shared", "corpus"))
    ap.add_argument("--work", default="/tmp/robodesc-isaac6")
    ap.add_argument("--out", help="write the results here (JSON)")
    args = ap.parse_args(argv)
    corpus = {r.name: r for r in all_robots(args.corpus)}
    results = []
    for name in args.robots.split(","):
        if name in EXAMPLES:
            source, extra = os.path.join(ROOT, EXAMPLES[name]), {}
        else:
            robot = corpus[name]
            source = robot.path
            extra = {"package_paths": robot.packages, "xacro_args": robot.xacro_args}
            extra["fix_base"] = not FLOATING.search(name)
        try:
            result = run_robot(name, source, extra, args.envs, args.work)
        except Exception as exc:  # one robot's failure is a row, not the end of the run
            result = {"robot": name, "error": f"{type(exc).__name__}: {str(exc)[:300]}"}
        print(json.dumps({k: v for k, v in result.items() if not k.endswith("diffs")}), flush=True)
        results.append(result)
    if args.out:
        with open(args.out, "w", encoding="utf-8") as fh:
            json.dump(results, fh, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
