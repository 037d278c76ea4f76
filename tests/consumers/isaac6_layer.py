"""The Isaac Sim 6 route, proven: robodesc's physics layer over Isaac Sim 6.2's own URDF import, read in PhysX.

    python tests/consumers/isaac6_layer.py --envs ~/.cache/robodesc-consumers [--robots quadruped,panda,...]
        [--out benchmarks/results/isaac6_layer.json]

For every robot (the bundled examples, then corpus robots from ``robodesc.validation.corpora``):

1. ``--isaac-sim`` (floating robots ``--no-fix-base``, as run_tier.py decides) with
   ``--physics-scene`` into a work folder; the time ``<robot>_physics.usda`` took is measured inside
   the compile (``folder.importer_physics_layer``);
2. Isaac Sim 6.2's importer (``isaac_import.py``, the ``isaacsim`` venv) imports the folder's URDF
   with the folder's ``importer_settings.json``;
3. the layer is made again from that import (``layout_from_usd``: what ``robodesc layer --onto`` does,
   with the compile's settings), must find every prim, and is the one the layer route runs; the
   naming rules must predict every path the import has (``rules_match_import``), and
   ``folder_layer_is_import_layer`` says whether the folder's layer is that same text (not where
   an instanced mesh collider carries more than the importer wrote: only the import names its shapes);
4. PhysX (ovphysx, its own venv; ``isaac6_physx_read.py``) reads three stages: robodesc's own USD,
   the import with ``importer_settings.json`` alone, and the import with the layer sublayered over it
   (``emit/isaac/composed.py``: its ``physx`` variant selected, as the importer leaves it
   unselected). Each link's mass, inertia and shapes' friction (the distinct values) and each
   joint's stiffness, damping, limits, effort and velocity bounds, armature and friction must equal
   robodesc's own USD (relative 1e-5, absolute 1e-9: float32 USD values);
5. unless ``--no-behaviour``: hold, drop and slide in PhysX on the three stages
   (``check_dynamics.stage_dynamics``), each route against robodesc's USD
   (``validation/dynamics/routes.py``).

Results: one JSON object per robot; ``--out`` keeps them all, ``--log`` appends each as it ends;
``isaac6_report.py`` turns them into benchmarks/results/isaac6_layer.json and .md.
"""

from __future__ import annotations

import argparse
import dataclasses
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

EXAMPLES = {
    "quadruped": "examples/quadruped.yaml",
    "arm6_gripper": "examples/arm6_gripper.yaml",
    "four_bar": "examples/four_bar.yaml",
}
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


def run_robot(
    name: str, source: str, extra: dict[str, Any], envs: str, work: str, behaviour: dict[str, Any] | None = None
) -> dict[str, Any]:
    """One robot through the route; ``behaviour``: the dynamics options (``DynamicsOptions`` fields)
    to run hold, drop and slide with on the three stages, None to leave them out."""
    import robodesc
    import robodesc.emit.isaac.folder as folder
    from robodesc.emit.isaac.composed import write_composed_stage
    from robodesc.emit.isaac.importer_layout import layout_from_rules, layout_from_usd
    from robodesc.emit.isaac.physics_layer import physics_layer
    from robodesc.ir.diagnostics import Findings
    from robodesc.validation.physx_python import physx_python

    out: dict[str, Any] = {"robot": name}
    here = os.path.join(work, name)
    isaac = os.path.join(here, "isaac")
    os.makedirs(here, exist_ok=True)
    timed: list[float] = []
    called: list[tuple[Any, ...]] = []  # the compile's own arguments, to make the layer again from the import
    original = folder.importer_physics_layer

    def timing(*args: Any, **kwargs: Any) -> str:
        called.append(args)
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
    robot_ir, settings, _, *initial = called[0]
    read = physics_layer(result.robot, folder.usd_options(settings, *initial), layout, Findings())
    out["prims_missing"] = read.missing
    # The layer the route runs: made from the import as `robodesc layer --onto` makes it (it can
    # reach inside instanced colliders, which the naming rules cannot name), with the compile's
    # own settings and pose.
    from_import = os.path.join(here, "physics_from_import.usda")
    text = original(robot_ir, dataclasses.replace(settings, importer_usd=usd), Findings(), *initial)
    Path(from_import).write_text(text, encoding="utf-8")
    out["folder_layer_is_import_layer"] = Path(files["physics_layer"]).read_text(encoding="utf-8") == text
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
    write_composed_stage(with_settings, robot, [usd], scene=True)
    write_composed_stage(with_layer, robot, [from_import, usd])
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
    if behaviour is not None:
        stages = {"robodesc": files["usd"], "settings": with_settings, "layer": with_layer}
        out.update(behave(source, extra, stages, behaviour))
    return out


def behave(source: str, extra: dict[str, Any], stages: dict[str, str], dynamics: dict[str, Any]) -> dict[str, Any]:
    """Hold, drop and slide in PhysX on each route's stage (``validate --dynamics``' scenarios, the
    same stance for all three), and each route against robodesc's own USD within the thresholds
    docs/dynamics.md documents."""
    from robodesc.check_dynamics import stage_dynamics
    from robodesc.validation.dynamics.routes import behaviour_differences

    start = time.perf_counter()
    reports = stage_dynamics(source, stages, extra, dynamics)
    out: dict[str, Any] = {"behaviour_s": round(time.perf_counter() - start, 1)}
    runs: dict[str, Any] = {}
    for label, report in reports.items():
        rows = {}
        for r in report.runs:
            row = {"ok": r.ok, "error": r.error, "drift": r.drift, "worst_joint": r.worst_joint}
            row.update(height=r.height, tilt=r.tilt, mass=r.mass, mu=r.mu, stick=r.stick, slide=r.slide)
            row["worst_saturation"] = r.worst_saturation()
            rows[r.scenario] = {k: v for k, v in row.items() if v not in (None, "")}
        rows["skipped"] = [f"{c.name} {c.element}: {c.message}" for c in report.checks if c.status.value == "skip"]
        rows["failed"] = [f"{c.name} {c.element}: {c.message}" for c in report.checks if c.status.value == "fail"]
        runs[label] = rows
    out["behaviour"] = runs
    reference = reports["robodesc"].runs
    out["settings_behaviour_diffs"] = behaviour_differences(reference, reports["settings"].runs)
    out["layer_behaviour_diffs"] = behaviour_differences(reference, reports["layer"].runs)
    ran = bool(reference)
    out["behaves"] = "not run" if not ran else "same" if not out["layer_behaviour_diffs"] else "differs"
    return out


def main(argv: list[str] | None = None) -> int:
    from run_tier import FLOATING

    from robodesc.validation.corpora import all_robots

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--envs", default=os.path.expanduser("~/.cache/robodesc-consumers"))
    ap.add_argument(
        "--robots", default="quadruped,arm6_gripper", help="comma-separated names (examples, corpus), or all"
    )
    ap.add_argument("--corpus", default=os.path.join(ROOT, "..", "shared", "corpus"))
    ap.add_argument("--work", default="/tmp/robodesc-isaac6")
    ap.add_argument("--out", help="write the results here (JSON)")
    ap.add_argument("--no-behaviour", action="store_true", help="skip the hold/drop/slide runs")
    ap.add_argument("--log", help="append each robot's result here as one JSON line (a cut run keeps its rows)")
    args = ap.parse_args(argv)
    robots = all_robots(args.corpus)
    # By full name, or by the file's stem where that is unique ("panda" for panda_description/urdf/panda).
    stems = [r.name.rsplit("/", 1)[-1] for r in robots]
    corpus = {stem: r for stem, r in zip(stems, robots, strict=True) if stems.count(stem) == 1}
    corpus.update({r.name: r for r in robots})
    names = [*EXAMPLES, *(r.name for r in robots)] if args.robots == "all" else args.robots.split(",")
    results = []
    for name in names:
        if name not in EXAMPLES and name not in corpus:
            results.append({"robot": name, "error": "no such robot (an example, or a corpus name or unique stem)"})
            print(json.dumps(results[-1]), flush=True)
            continue
        if name in EXAMPLES:
            source, extra = os.path.join(ROOT, EXAMPLES[name]), {}
        else:
            robot = corpus[name]
            source = robot.path
            extra = {"package_paths": robot.packages, "xacro_args": robot.xacro_args}
            extra["fix_base"] = not FLOATING.search(robot.name)
        try:
            behaviour = None if args.no_behaviour else {}
            result = run_robot(name, source, extra, args.envs, args.work, behaviour)
        except Exception as exc:  # one robot's failure is a row, not the end of the run
            result = {"robot": name, "error": f"{type(exc).__name__}: {str(exc)[:300]}"}
        print(json.dumps({k: v for k, v in result.items() if not k.endswith("diffs") and k != "behaviour"}), flush=True)
        results.append(result)
        if args.log:
            with open(args.log, "a", encoding="utf-8") as fh:
                fh.write(json.dumps(result) + "\n")
    if args.out:
        with open(args.out, "w", encoding="utf-8") as fh:
            json.dump(results, fh, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
