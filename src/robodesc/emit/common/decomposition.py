"""Mesh colliders under ``convexDecomposition`` for targets that cannot decompose on load (MJCF, SDF):
each convex part written as its own OBJ under ``meshes/`` beside the output, named after its content.

The options (``--decomposition-max-parts``, ``--decomposition-timeout``, ``--decomposition-threshold``,
``--decomposition-cache``) are fields of both targets' options, declared once here. When CoACD is
missing, fails or runs out of time, a warning says so and the caller writes the whole mesh, which
both engines collide as its convex hull (MuJoCo) or as asked (Gazebo).
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from robodesc._files import write_atomic
from robodesc.emit.common.flags import flag
from robodesc.ir.diagnostics import ConfigError
from robodesc.ir.geometry import Mesh
from robodesc.meshes.buffers import MeshReadError, obj_bytes

if TYPE_CHECKING:
    from robodesc.meshes.decompose import Points, Triangles

MESH_DIR = "meshes"

MAX_PARTS = flag(
    "convexDecomposition: at most N convex parts per mesh (CoACD merges down to it; default 32, PhysX's)",
    type=int,
    metavar="N",
)
TIMEOUT = flag(
    "convexDecomposition: seconds CoACD may spend on one mesh before its convex hull is used (default 300)",
    type=float,
    metavar="S",
)
THRESHOLD = flag(
    "convexDecomposition: CoACD's concavity threshold, smaller gives more and tighter parts (default 0.05)",
    type=float,
    metavar="X",
)
CACHE = flag(
    "folder of the convex decomposition cache (default $ROBODESC_DECOMPOSITION_CACHE, else "
    "~/.cache/robodesc/decomposition)",
    metavar="DIR",
)


def check_settings(options: object) -> None:
    """The decomposition fields of a target's options (``decomposition_max_parts`` ...)."""
    parts = getattr(options, "decomposition_max_parts", 32)
    if not isinstance(parts, int) or isinstance(parts, bool) or parts < 1:
        raise ConfigError(f"decomposition_max_parts must be an integer >= 1, got {parts!r}")
    for name in ("decomposition_timeout", "decomposition_threshold"):
        value = getattr(options, name, 1.0)
        if not isinstance(value, int | float) or isinstance(value, bool) or not value > 0:
            raise ConfigError(f"{name} must be a number > 0, got {value!r}")


def decomposer(options: object, out_dir: str) -> Decomposer:
    return Decomposer(
        out_dir,
        max_parts=getattr(options, "decomposition_max_parts", 32),
        timeout=float(getattr(options, "decomposition_timeout", 300.0)),
        threshold=float(getattr(options, "decomposition_threshold", 0.05)),
        cache=getattr(options, "decomposition_cache", None),
    )


# Warn(code, message): the caller's finding, with its element and source location.
Warn = Callable[[str, str], None]


@dataclass(slots=True)
class PartFile:
    rel: str  # as the output refers to it: meshes/<stem>_part<i>_<digest>.obj
    path: str  # where it was written


@dataclass(slots=True)
class Decomposer:
    """One per written robot: decomposes each (file, scale) once and remembers the parts."""

    out_dir: str
    max_parts: int = 32
    timeout: float = 300.0
    threshold: float = 0.05
    cache: str | None = None
    written: dict[str, str] = field(default_factory=dict)
    _done: dict[tuple[str, tuple[float, float, float] | None], list[PartFile] | None] = field(default_factory=dict)
    _said_missing: bool = False

    def parts(self, mesh: Mesh, warn: Warn, info: Warn) -> list[PartFile] | None:
        """The part files of ``mesh``; None (with a warning) when the whole mesh is to be written."""
        from robodesc.meshes.decompose import (
            INSTALL_HINT,
            DecompositionSettings,
            DecompositionUnavailable,
            coacd_version,
            decompose,
        )

        if mesh.path is None or not os.path.isfile(mesh.path):
            return None  # the caller's own missing-mesh warning applies
        key = (mesh.path, mesh.scale)
        if key in self._done:
            return self._done[key]
        settings = DecompositionSettings(max_parts=self.max_parts, timeout=self.timeout, threshold=self.threshold)
        out: list[PartFile] | None = None
        try:
            points, triangles = _arrays(mesh)
            result = decompose(points, triangles, settings, self.cache)
        except MeshReadError as exc:
            warn("decomposition-bad-mesh", f"mesh {mesh.uri!r} cannot be read for decomposition ({exc})")
        except DecompositionUnavailable as exc:
            if coacd_version() is None:
                if not self._said_missing:
                    warn(
                        "decomposition-unavailable",
                        f"convexDecomposition needs CoACD, which is not installed ({INSTALL_HINT}); mesh "
                        "colliders are written whole and collide as their convex hull",
                    )
                    self._said_missing = True
            else:
                warn(
                    "decomposition-failed",
                    f"mesh {mesh.uri!r}: {exc}; written whole, colliding as its convex hull",
                )
        else:
            stem = os.path.splitext(os.path.basename(mesh.path))[0]
            out = [self._write(f"{stem}_part{i}", v, f) for i, (v, f) in enumerate(result.parts)]
            how = "from the cache" if result.cached else f"CoACD, {result.seconds:.1f} s"
            info("decomposition", f"mesh {mesh.uri!r}: {len(out)} convex part(s) ({how})")
            if result.capped:
                warn(
                    "decomposition-capped",
                    f"mesh {mesh.uri!r} reached the cap of {self.max_parts} convex parts: CoACD merged hulls "
                    "to stay within it, so the parts fit less tightly (raise --decomposition-max-parts)",
                )
        self._done[key] = out
        return out

    def _write(self, stem: str, points: object, triangles: object) -> PartFile:
        text = obj_text(points, triangles)
        digest = hashlib.sha256(text).hexdigest()[:12]
        name = f"{stem}_{digest}.obj"
        path = os.path.join(self.out_dir, MESH_DIR, name)
        if not os.path.isfile(path):
            write_atomic(path, text)
        rel = f"{MESH_DIR}/{name}"
        self.written[f"mesh:{rel}"] = path
        return PartFile(rel, path)


def _arrays(mesh: Mesh) -> tuple[Points, Triangles]:
    import numpy as np

    from robodesc.meshes.data import build_mesh

    assert mesh.path is not None
    data = build_mesh(mesh.path, mesh.scale)
    points = np.frombuffer(data.points, dtype=np.float32).reshape(-1, 3).astype(np.float64)
    triangles = np.frombuffer(data.face_vertex_indices, dtype=np.int32).reshape(-1, 3)
    return points, triangles


def obj_text(points: object, triangles: object) -> bytes:
    """A Wavefront OBJ of one part: the same parts always give the same bytes."""
    import numpy as np

    flat = np.asarray(points, dtype=np.float64).ravel().tolist()
    indices = np.asarray(triangles, dtype=np.int64).ravel().tolist()
    return obj_bytes(flat, indices, "convex part written by robodesc (CoACD)")
