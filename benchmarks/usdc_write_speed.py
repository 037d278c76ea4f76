"""Time robodesc's pure-Python crate writer against usd-core writing the same mesh layer.

    PYTHONPATH=src python benchmarks/usdc_write_speed.py [--points 400000] [--indices 2300000] [--repeat 5]

The layer: one Mesh with float3 points and normals, int face vertex counts and indices (a 400k-point,
2.3M-index triangle mesh by default), from numpy arrays. robodesc builds its layer model and calls
``usdc_bytes`` then writes the file; usd-core builds the same specs through Sdf, fills them with
``Vt.*Array.FromNumpy`` and ``Export``s to ``.usdc``. Best of ``--repeat`` runs each, plus the one-off
cost of importing pxr that robodesc's CLI avoids. Prints timings only; nothing is asserted.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from typing import Any

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "src"))

from robodesc.usdfile.spec import Layer  # noqa: E402
from robodesc.usdfile.usdc import usdc_bytes  # noqa: E402


def mesh_arrays(points: int, indices: int) -> dict[str, Any]:
    rng = np.random.default_rng(0)
    faces = indices // 3
    return {
        "points": rng.standard_normal((points, 3)).astype(np.float32),
        "normals": rng.standard_normal((points, 3)).astype(np.float32),
        "faceVertexCounts": np.full(faces, 3, dtype=np.int32),
        "faceVertexIndices": rng.integers(0, points, faces * 3, dtype=np.int32),
    }


def write_robodesc(arrays: dict[str, Any], path: str) -> None:
    layer = Layer(default_prim="Geometry", meters_per_unit=1.0, up_axis="Z")
    mesh = layer.prim("/Geometry/mesh", "Mesh")
    mesh.attr("points", "point3f[]", arrays["points"])
    mesh.attr("normals", "normal3f[]", arrays["normals"], interpolation="vertex")
    mesh.attr("faceVertexCounts", "int[]", arrays["faceVertexCounts"])
    mesh.attr("faceVertexIndices", "int[]", arrays["faceVertexIndices"])
    with open(path, "wb") as f:
        f.write(usdc_bytes(layer))


def write_pxr(arrays: dict[str, Any], path: str) -> None:
    from pxr import Sdf, Vt

    layer = Sdf.Layer.CreateAnonymous(".usdc")
    layer.defaultPrim = "Geometry"
    layer.pseudoRoot.SetInfo("metersPerUnit", 1.0)
    layer.pseudoRoot.SetInfo("upAxis", "Z")
    Sdf.CreatePrimInLayer(layer, "/Geometry").specifier = Sdf.SpecifierDef
    mesh = Sdf.CreatePrimInLayer(layer, "/Geometry/mesh")
    mesh.specifier = Sdf.SpecifierDef
    mesh.typeName = "Mesh"
    names = Sdf.ValueTypeNames
    Sdf.AttributeSpec(mesh, "points", names.Point3fArray).default = Vt.Vec3fArray.FromNumpy(arrays["points"])
    normals = Sdf.AttributeSpec(mesh, "normals", names.Normal3fArray)
    normals.default = Vt.Vec3fArray.FromNumpy(arrays["normals"])
    normals.SetInfo("interpolation", "vertex")
    counts = Sdf.AttributeSpec(mesh, "faceVertexCounts", names.IntArray)
    counts.default = Vt.IntArray.FromNumpy(arrays["faceVertexCounts"])
    indices = Sdf.AttributeSpec(mesh, "faceVertexIndices", names.IntArray)
    indices.default = Vt.IntArray.FromNumpy(arrays["faceVertexIndices"])
    layer.Export(path)


def best_of(repeat: int, fn: Callable[[], None]) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def pxr_import_seconds() -> float:
    code = "import time; t = time.perf_counter(); from pxr import Sdf, Vt; print(time.perf_counter() - t)"
    return float(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--points", type=int, default=400_000)
    parser.add_argument("--indices", type=int, default=2_300_000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    arrays = mesh_arrays(args.points, args.indices)
    payload_mb = sum(a.nbytes for a in arrays.values()) / 1e6
    with tempfile.TemporaryDirectory() as tmp:
        ours, theirs = os.path.join(tmp, "robodesc.usdc"), os.path.join(tmp, "pxr.usdc")
        t_ours = best_of(args.repeat, lambda: write_robodesc(arrays, ours))
        t_import = pxr_import_seconds()
        t_theirs = best_of(args.repeat, lambda: write_pxr(arrays, theirs))
        size_ours, size_theirs = os.path.getsize(ours), os.path.getsize(theirs)
    print(f"mesh: {args.points} points, {args.indices // 3 * 3} indices, {payload_mb:.1f} MB of array data")
    print(f"{'writer':<28}{'seconds':>10}{'file MB':>10}")
    print(f"{'robodesc usdc_bytes + write':<28}{t_ours:>10.3f}{size_ours / 1e6:>10.1f}")
    print(f"{'usd-core Sdf + Export':<28}{t_theirs:>10.3f}{size_theirs / 1e6:>10.1f}")
    print(f"{'usd-core import (once)':<28}{t_import:>10.3f}")


if __name__ == "__main__":
    main()
