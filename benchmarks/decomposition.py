"""Convex decomposition (``--collision-approximation convexDecomposition``) on real robots: the first
compile (CoACD runs on every collision mesh) against a second one (every mesh from the cache), and
the parts per mesh.

    python benchmarks/decomposition.py                       # Go2, Spirit, panda, solo12, ur5
    python benchmarks/decomposition.py --robot go2 --json out.json

Each robot is compiled to MJCF (validation off: only writing is timed) with an empty cache folder,
then again with the same folder, then to SDF from that cache. Default decomposition settings (at
most 32 parts, CoACD's threshold 0.05, seed 0). Results: benchmarks/results/decomposition.md/json.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from typing import Any

import robodesc
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions
from robodesc.ir.geometry import Mesh
from robodesc.meshes.data import build_mesh
from robodesc.meshes.decompose import DecompositionSettings, coacd_version, decompose
from robodesc.validation.corpora import CorpusRobot, example_robot_data_robots, quadsdk_robots

SHARED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "corpus")
ROBOTS = {
    "go2": "go2",
    "spirit": "spirit",
    "panda": "panda_description/urdf/panda",
    "solo12": "solo_description/robots/solo12",
    "ur5": "ur_description/urdf/ur5_robot",
}


def _entries(names: list[str]) -> list[CorpusRobot]:
    known = {r.name: r for r in quadsdk_robots(os.path.abspath(SHARED)) + example_robot_data_robots()}
    return [known[ROBOTS[n]] for n in names if ROBOTS[n] in known]


def run(entry: CorpusRobot) -> dict[str, Any]:
    opts: dict[str, Any] = {"package_paths": entry.packages, "xacro_args": entry.xacro_args, "validate": False}
    robot = load_path(entry.path, LoadOptions(package_paths=entry.packages, xacro_args=entry.xacro_args)).robot
    meshes: dict[tuple[str, Any], Mesh] = {}
    for link in robot.links:
        for c in link.collisions:
            if isinstance(c.geometry, Mesh) and c.geometry.path is not None:
                meshes.setdefault((c.geometry.path, c.geometry.scale), c.geometry)
    with tempfile.TemporaryDirectory() as tmp:
        cache = os.path.join(tmp, "cache")
        approx = {"collision_approximation": "convexDecomposition", "decomposition_cache": cache}
        times = {}
        for label, target, out in (
            ("mjcf_first", "mjcf", "a/robot.xml"),
            ("mjcf_cached", "mjcf", "b/robot.xml"),
            ("sdf_cached", "sdf", "c/robot.sdf"),
        ):
            start = time.perf_counter()
            result = robodesc.compile_to(entry.path, target, os.path.join(tmp, out), **opts, **approx)
            times[label] = round(time.perf_counter() - start, 3)
            codes = [f.code for f in result.findings if f.code.startswith("decomposition-")]
            times[label + "_warnings"] = sorted(set(codes))  # type: ignore[assignment]
        start = time.perf_counter()
        robodesc.compile_to(entry.path, "mjcf", os.path.join(tmp, "d/robot.xml"), **opts)
        times["mjcf_hull"] = round(time.perf_counter() - start, 3)
        collision_meshes = len(meshes)
        role = "collision"
        if not meshes:
            # Go2 and Spirit collide with primitives only: their visual meshes stand in, as they
            # would for a user who collides with them (first run and cached run, per mesh).
            role = "visual"
            for link in robot.links:
                for v in link.visuals:
                    if isinstance(v.geometry, Mesh) and v.geometry.path is not None:
                        meshes.setdefault((v.geometry.path, v.geometry.scale), v.geometry)
        rows = [_one_mesh(path, mesh, cache, role) for (path, _scale), mesh in meshes.items()]
    return {"robot": entry.name, "meshes": collision_meshes, "times_s": times, "per_mesh": rows}


def _one_mesh(path: str, mesh: Mesh, cache: str, role: str) -> dict[str, Any]:
    """CoACD's time on the mesh (recorded in the cache entry when it was made) and a cached run's."""
    import numpy as np

    data = build_mesh(path, mesh.scale)
    pts = np.frombuffer(data.points, dtype=np.float32).reshape(-1, 3).astype(np.float64)
    tris = np.frombuffer(data.face_vertex_indices, dtype=np.int32).reshape(-1, 3)
    row: dict[str, Any] = {"mesh": os.path.basename(path), "role": role, "triangles": len(tris)}
    settings = DecompositionSettings()
    try:
        decompose(pts, tris, settings, cache)  # collision meshes: already cached by the first compile
        start = time.perf_counter()
        found = decompose(pts, tris, settings, cache)
        cached_s = time.perf_counter() - start
    except Exception as exc:  # a mesh CoACD gave up on (time limit): reported, not fatal
        row["error"] = str(exc)
        return row
    row.update(
        parts=len(found.parts),
        capped=found.capped,
        coacd_s=round(found.seconds, 2),
        cached_read_s=round(cached_s, 4),
    )
    return row


def markdown(results: list[dict[str, Any]], version: str | None) -> str:
    lines = [
        "# Convex decomposition: first compile vs cached (benchmarks/decomposition.py)",
        "",
        f"CoACD {version}, default settings (max 32 parts, threshold 0.05, seed 0); MJCF and SDF compiles "
        "with validation off; 2-core machine shared with other jobs.",
        "",
        "| robot | collision meshes | MJCF, first (CoACD) | MJCF, cached | SDF, cached | MJCF, convexHull (no decomposition) |",
        "|---|---|---|---|---|---|",
    ]
    for r in results:
        t = r["times_s"]
        lines.append(
            f"| {r['robot']} | {r['meshes']} | {t['mjcf_first']:.2f} s | {t['mjcf_cached']:.2f} s | "
            f"{t['sdf_cached']:.2f} s | {t['mjcf_hull']:.2f} s |"
        )
    lines += [
        "",
        "Go2 and Spirit collide with boxes, cylinders and spheres only (no mesh collider): their compiles",
        "decompose nothing, and their visual meshes are decomposed below instead, as they would be for a",
        "user who collides with them.",
        "",
        "## Parts per mesh",
        "",
        "| robot | mesh (role) | triangles | parts | CoACD, first run | cached run |",
        "|---|---|---|---|---|---|",
    ]
    for r in results:
        for m in r["per_mesh"]:
            label = f"{m['mesh']} ({m.get('role', 'collision')})"
            if "error" in m:
                lines.append(f"| {r['robot']} | {label} | {m['triangles']} | – | {m['error']} | – |")
            else:
                capped = " (cap)" if m.get("capped") else ""
                lines.append(
                    f"| {r['robot']} | {label} | {m['triangles']} | {m['parts']}{capped} | {m['coacd_s']:.2f} s | "
                    f"{m['cached_read_s'] * 1000:.1f} ms |"
                )
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robot", action="append", choices=sorted(ROBOTS), help="default: all")
    parser.add_argument("--json", help="write the results here")
    parser.add_argument("--markdown", help="write the markdown table here")
    args = parser.parse_args(argv)
    version = coacd_version()
    if version is None:
        print("CoACD is not installed: pip install 'robodesc[decompose]'", file=sys.stderr)
        return 2
    results: list[dict[str, Any]] = []
    if args.json and os.path.isfile(args.json):
        # Robots measured earlier stay; the ones measured now replace theirs.
        with open(args.json, encoding="utf-8") as handle:
            results = json.load(handle)["results"]
    for entry in _entries(args.robot or list(ROBOTS)):
        results = [r for r in results if r["robot"] != entry.name]
        print(f"{entry.name} ...", file=sys.stderr, flush=True)
        results.append(run(entry))
        print(json.dumps(results[-1]["times_s"]), file=sys.stderr, flush=True)
    order = list(ROBOTS.values())
    results.sort(key=lambda r: order.index(r["robot"]) if r["robot"] in order else len(order))
    text = markdown(results, version)
    print(text)
    if args.json:
        with open(args.json, "w", encoding="utf-8") as handle:
            json.dump({"coacd": version, "results": results}, handle, indent=2)
            handle.write("\n")
    if args.markdown:
        with open(args.markdown, "w", encoding="utf-8") as handle:
            handle.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
