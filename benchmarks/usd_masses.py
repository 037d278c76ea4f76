"""The total mass each USD reader takes from robodesc's USD, against the URDF's.

    PYTHONPATH=src python benchmarks/usd_masses.py [--robots a1,go1] [--out FILE.json]

For every example-robot-data robot, compiled ``-t usd`` and ``--isaac-sim`` (validation off: the
numbers are the point), the total of the bodies' masses as read by:
- usd-core: ``UsdPhysics.RigidBodyAPI.ComputeMassProperties`` (the authored ``physics:mass``, else
  the colliders' volume at 1000 kg/m³, the schema's default density, from closed forms and meshes);
- Newton 1.8 (``add_usd``; its own environment, ``newton_masses.py``), with the number of bodies
  whose inertia its validation "corrected";
- PhysX (ovphysx 0.7 on CPU, ``physx_masses.py``).
The URDF's total is the sum of its ``<inertial>`` masses. Prints a markdown table (robots more than
1% off are counted per reader) and writes the numbers as JSON.
"""

from __future__ import annotations

import argparse
import glob
import json
import math
import os
import subprocess
import tempfile
from typing import Any

import numpy as np

import robodesc
from robodesc.validation.corpora import example_robot_data_robots
from robodesc.validation.physx_python import physx_python

HERE = os.path.dirname(os.path.abspath(__file__))
NEWTON = os.path.expanduser("~/.cache/robodesc-consumers/newton/bin/python")
DENSITY = 1000.0  # UsdPhysics' default when neither the body nor a material gives one


def _volume(prim: Any, to_body: Any) -> tuple[float, Any]:
    """Volume (m³) and centre (body frame) of one collider, scaled as the body sees it."""
    from pxr import Gf, UsdGeom

    m = np.array(to_body, dtype=float).T  # Gf matrices are row-vector: transpose to column form
    scale = abs(float(np.linalg.det(m[:3, :3])))
    centre = m[:3, 3]
    if prim.IsA(UsdGeom.Cube):
        size = float(UsdGeom.Cube(prim).GetSizeAttr().Get())
        return size**3 * scale, centre
    if prim.IsA(UsdGeom.Sphere):
        r = float(UsdGeom.Sphere(prim).GetRadiusAttr().Get())
        return 4.0 / 3.0 * math.pi * r**3 * scale, centre
    if prim.IsA(UsdGeom.Cylinder):
        c = UsdGeom.Cylinder(prim)
        r, h = float(c.GetRadiusAttr().Get()), float(c.GetHeightAttr().Get())
        return math.pi * r * r * h * scale, centre
    if prim.IsA(UsdGeom.Capsule):
        c = UsdGeom.Capsule(prim)
        r, h = float(c.GetRadiusAttr().Get()), float(c.GetHeightAttr().Get())
        return (math.pi * r * r * h + 4.0 / 3.0 * math.pi * r**3) * scale, centre
    if prim.IsA(UsdGeom.Mesh):
        from robodesc.meshes.mass import solid

        mesh = UsdGeom.Mesh(prim)
        points = np.array(mesh.GetPointsAttr().Get(), dtype=float)
        counts = list(mesh.GetFaceVertexCountsAttr().Get())
        indices = list(mesh.GetFaceVertexIndicesAttr().Get())
        tris: list[tuple[int, int, int]] = []
        at = 0
        for n in counts:
            tris.extend((indices[at], indices[at + k], indices[at + k + 1]) for k in range(1, n - 1))
            at += n
        body = points @ m[:3, :3].T + centre
        s = solid(body, np.array(tris, dtype=np.int64))
        return abs(s.volume), np.asarray(s.com, dtype=float)
    del Gf
    return 0.0, centre


def usd_core_masses(path: str) -> dict[str, float]:
    from pxr import Gf, Usd, UsdGeom, UsdPhysics

    stage = Usd.Stage.Open(path)
    cache = UsdGeom.XformCache()
    out: dict[str, float] = {}
    for prim in stage.Traverse():
        if not prim.HasAPI(UsdPhysics.RigidBodyAPI):
            continue
        body_inv = cache.GetLocalToWorldTransform(prim).GetInverse()

        def info(collider: Any, body_inv: Any = body_inv) -> Any:
            mi = UsdPhysics.RigidBodyAPI.MassInformation()
            volume, centre = _volume(collider, cache.GetLocalToWorldTransform(collider) * body_inv)
            mi.volume = volume
            mi.centerOfMass = Gf.Vec3f(0.0, 0.0, 0.0)
            mi.localPos = Gf.Vec3f(*map(float, centre))
            mi.localRot = Gf.Quatf(1.0)
            mi.inertia = Gf.Matrix3f(1.0) * float(volume) * 1e-3
            return mi

        result = UsdPhysics.RigidBodyAPI(prim).ComputeMassProperties(info)
        out[str(prim.GetPath())] = float(result[0])
    return out


def _consumer(python: str | None, script: str, paths: list[str]) -> dict[str, Any]:
    if python is None or not os.path.exists(python) or not paths:
        return {}
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as f:
        out = f.name
    subprocess.run(
        [python, os.path.join(HERE, script), out],
        input="\n".join(paths),
        text=True,
        capture_output=True,
        check=False,
        timeout=3600,
    )
    try:
        with open(out, encoding="utf-8") as f:
            data: dict[str, Any] = json.load(f)
        return data
    except (OSError, json.JSONDecodeError):
        return {}
    finally:
        os.unlink(out)


def _total(masses: Any) -> float | str:
    if isinstance(masses, str):
        return str(masses)
    return float(sum(v for k, v in masses.items() if not k.startswith("#") and v > 0))


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--robots", default="", help="comma-separated name substrings (default: all)")
    parser.add_argument("--out", default=os.path.join(HERE, "results", "usd_masses.json"))
    parser.add_argument("--merge", nargs="*", help="only print the table of these result files, merged")
    args = parser.parse_args()
    if args.merge:
        print(table(merge(args.merge)))
        return
    wanted = [w for w in args.robots.split(",") if w]
    robots = [r for r in example_robot_data_robots() if not wanted or any(w in r.name for w in wanted)]
    work = tempfile.mkdtemp(prefix="usd-masses-")
    rows: dict[str, dict[str, Any]] = {}
    files: list[str] = []
    for robot in robots:
        row: dict[str, Any] = {}
        try:
            ir = robodesc.load(robot.path, package_paths=robot.packages)
        except Exception as exc:  # a robot robodesc cannot read is a row, not the end of the run
            rows[robot.name] = {"error": str(exc)[:200]}
            continue
        row["urdf"] = sum(link.inertial.mass or 0.0 for link in ir.links if link.inertial is not None)
        stem = robot.name.replace("/", "_")
        for mode in ("usd", "isaac"):
            try:
                if mode == "usd":
                    path = os.path.join(work, f"{stem}.usda")
                    robodesc.compile_to_usd(robot.path, path, package_paths=robot.packages, validate=False)
                else:
                    folder = os.path.join(work, f"{stem}_isaac")
                    robodesc.compile_for_isaac_sim(robot.path, folder, package_paths=robot.packages, validate=False)
                    path = sorted(glob.glob(os.path.join(folder, "*.usd*")))[0]
            except Exception as exc:
                row[mode] = {"error": str(exc)[:200]}
                continue
            core = usd_core_masses(path)
            # ComputeMassProperties answers -1 for a body with neither a mass nor a collider.
            row[mode] = {"path": path, "usd_core": _total(core), "usd_core_no_mass": sum(v < 0 for v in core.values())}
            files.append(path)
        rows[robot.name] = row
    newton = _consumer(NEWTON, "newton_masses.py", files)
    physx = _consumer(physx_python(), "physx_masses.py", files)
    for row in rows.values():
        for mode in ("usd", "isaac"):
            cell = row.get(mode)
            if not isinstance(cell, dict) or "path" not in cell:
                continue
            path = cell.pop("path")
            if path in newton:
                cell["newton"] = _total(newton[path])
                if isinstance(newton[path], dict):
                    cell["newton_corrected"] = int(newton[path].get("#corrected", 0))
            if path in physx:
                cell["physx"] = _total(physx[path])
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(rows, f, indent=1, sort_keys=True)
    print(table(rows))


def merge(paths: list[str]) -> dict[str, dict[str, Any]]:
    """Rows of several runs (``--robots`` chunks), later files winning."""
    rows: dict[str, dict[str, Any]] = {}
    for path in paths:
        with open(path, encoding="utf-8") as f:
            rows.update(json.load(f))
    return rows


def _off(got: Any, want: float) -> bool:
    """More than 1% away, or an error instead of a number."""
    return not isinstance(got, float | int) or abs(got - want) > 0.01 * max(want, 1e-9)


def table(rows: dict[str, dict[str, Any]]) -> str:
    readers = ("usd_core", "newton", "physx")
    lines = ["| robot | URDF kg | " + " | ".join(f"{m} {r}" for m in ("usd", "isaac") for r in readers) + " |"]
    lines.append("|---" * (2 + 2 * len(readers)) + "|")
    counts = {(m, r): 0 for m in ("usd", "isaac") for r in readers}
    measured = {(m, r): 0 for m in ("usd", "isaac") for r in readers}
    corrected = {"usd": 0, "isaac": 0}
    for name, row in sorted(rows.items()):
        if "urdf" not in row:
            lines.append(f"| {name} | {row.get('error', '?')} |")
            continue
        want = row["urdf"]
        cells = []
        for m in ("usd", "isaac"):
            cell = row.get(m, {})
            corrected[m] += int(bool(cell.get("newton_corrected")))
            for r in readers:
                got = cell.get(r, "-")
                if got != "-":
                    measured[(m, r)] += 1
                    counts[(m, r)] += int(_off(got, want))
                cells.append(f"{got:.2f}" if isinstance(got, float | int) else str(got)[:30])
        lines.append(f"| {name} | {want:.2f} | " + " | ".join(cells) + " |")
    lines.append("")
    lines.append(f"robots: {len(rows)}; more than 1% off the URDF's total (of those the reader measured):")
    for (m, r), n in counts.items():
        lines.append(f"- {m} / {r}: {n} of {measured[(m, r)]}")
    for m, n in corrected.items():
        lines.append(f"- {m}: robots with a body whose inertia Newton corrected: {n}")
    return "\n".join(lines)


if __name__ == "__main__":
    main()
