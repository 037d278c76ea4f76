"""Convex decomposition of a mesh through CoACD (``pip install 'robodesc[decompose]'``), cached by
content.

MuJoCo collides every mesh as its convex hull and Gazebo as its triangles; neither decomposes on
load, so for them robodesc computes the parts itself (USD asks PhysX to do it, emit/usd). CoACD
(Wei et al., SIGGRAPH 2022) is maintained, on PyPI as a wheel, and deterministic for a given seed.

The cache: one ``.npz`` per key under :func:`cache_dir` (``$ROBODESC_DECOMPOSITION_CACHE``, else
``$XDG_CACHE_HOME/robodesc/decomposition``, else ``~/.cache/robodesc/decomposition``). The key hashes
the triangles CoACD is given (after scaling, so one file at two scales is two entries), every
parameter that changes the result, and CoACD's version. Entries are written to a temporary file and
renamed into place, so batch workers that decompose the same mesh at once never read half a file.

CoACD runs in a child process: its C++ loop cannot be interrupted from Python, and the child can be
killed at the time limit; it keeps CoACD's log off robodesc's output; and CoACD's shared library,
once loaded, breaks Drake's parser in the same process (see :func:`coacd_version`).
"""

from __future__ import annotations

import hashlib
import importlib.util
import io
import json
import os
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass
from importlib import metadata

import numpy as np
import numpy.typing as npt

from robodesc._files import write_atomic

CACHE_ENV = "ROBODESC_DECOMPOSITION_CACHE"
INSTALL_HINT = "pip install 'robodesc[decompose]'"
# Bumped when the cache entry's layout or the way the input is prepared changes.
_FORMAT = "robodesc-coacd-1"

Points = npt.NDArray[np.float64]
Triangles = npt.NDArray[np.int32]


@dataclass(frozen=True, slots=True)
class DecompositionSettings:
    """CoACD's parameters robodesc sets. ``max_parts``: CoACD merges hulls until at most this many
    are left (PhysX's own default for ``maxConvexHulls`` is 32); ``threshold``: CoACD's concavity
    threshold (smaller: more, tighter parts); ``timeout``: seconds per mesh before the convex hull
    is used instead (not part of the cache key); ``seed``: CoACD's random seed, fixed so the same
    mesh always gives the same parts. The rest are CoACD's search budget (its defaults)."""

    max_parts: int = 32
    threshold: float = 0.05
    timeout: float = 300.0
    seed: int = 0
    resolution: int = 2000
    preprocess_resolution: int = 50
    mcts_iterations: int = 150
    mcts_nodes: int = 20

    def coacd_arguments(self) -> dict[str, float | int]:
        return {
            "threshold": self.threshold,
            "max_convex_hull": self.max_parts,
            "seed": self.seed,
            "resolution": self.resolution,
            "preprocess_resolution": self.preprocess_resolution,
            "mcts_iterations": self.mcts_iterations,
            "mcts_nodes": self.mcts_nodes,
        }


@dataclass(frozen=True, slots=True)
class Decomposition:
    parts: list[tuple[Points, Triangles]]
    cached: bool  # read from the cache: CoACD did not run
    seconds: float  # how long CoACD took when the entry was made
    capped: bool  # as many parts as max_parts: CoACD merged hulls to stay within the cap
    key: str


class DecompositionUnavailable(Exception):
    """CoACD is not installed, failed, or ran out of time; the message says which."""


def coacd_version() -> str | None:
    """The installed CoACD's version, None when it is not installed. Never imported here: its
    shared library, loaded into robodesc's process, makes Drake's SDF parser throw ("Caught an
    unknown exception!"), and the child process is where it runs anyway."""
    if importlib.util.find_spec("coacd") is None:
        return None
    try:
        return metadata.version("coacd")
    except metadata.PackageNotFoundError:  # pragma: no cover - on the path from a source tree
        return "unknown"


def cache_dir(override: str | None = None) -> str:
    """Where entries live: the option, else ``$ROBODESC_DECOMPOSITION_CACHE``, else the user's cache."""
    if override:
        return os.path.abspath(os.path.expanduser(override))
    env = os.environ.get(CACHE_ENV)
    if env:
        return os.path.abspath(os.path.expanduser(env))
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "robodesc", "decomposition")


def cache_key(points: Points, triangles: Triangles, settings: DecompositionSettings, version: str) -> str:
    h = hashlib.sha256()
    params = {k: v for k, v in asdict(settings).items() if k != "timeout"}
    h.update(json.dumps([_FORMAT, version, params], sort_keys=True).encode())
    h.update(np.ascontiguousarray(points, dtype="<f8").tobytes())
    h.update(np.ascontiguousarray(triangles, dtype="<i4").tobytes())
    return h.hexdigest()[:32]


def decompose(
    points: Points, triangles: Triangles, settings: DecompositionSettings, cache: str | None = None
) -> Decomposition:
    """The convex parts of the mesh, from the cache when an entry exists (CoACD need not even be
    installed then), else computed and stored. Raises :class:`DecompositionUnavailable`."""
    points = np.ascontiguousarray(points, dtype=np.float64).reshape(-1, 3)
    triangles = np.ascontiguousarray(triangles, dtype=np.int32).reshape(-1, 3)
    folder = cache_dir(cache)
    version = coacd_version()
    # The entry of the version that made it is looked for first; without CoACD, any version's.
    if version is not None:
        key = cache_key(points, triangles, settings, version)
        found = _read(os.path.join(folder, key + ".npz"), key)
        if found is not None:
            return found
    else:
        found = _any_version(folder, points, triangles, settings)
        if found is not None:
            return found
        raise DecompositionUnavailable(f"CoACD is not installed ({INSTALL_HINT})")
    start = time.monotonic()
    parts = _run_coacd(points, triangles, settings)
    seconds = time.monotonic() - start
    if not parts:
        raise DecompositionUnavailable("CoACD returned no parts")
    capped = len(parts) >= settings.max_parts
    _store(os.path.join(folder, key + ".npz"), parts, seconds, capped, version)
    return Decomposition(parts, False, seconds, capped, key)


def _any_version(
    folder: str, points: Points, triangles: Triangles, settings: DecompositionSettings
) -> Decomposition | None:
    index = os.path.join(folder, "versions.txt")
    try:
        with open(index, encoding="utf-8") as handle:
            versions = [line.strip() for line in handle if line.strip()]
    except OSError:
        return None
    for version in versions:
        key = cache_key(points, triangles, settings, version)
        found = _read(os.path.join(folder, key + ".npz"), key)
        if found is not None:
            return found
    return None


def _read(path: str, key: str) -> Decomposition | None:
    try:
        with np.load(path, allow_pickle=False) as data:
            count = int(data["count"])
            parts = [(data[f"v{i}"].astype(np.float64), data[f"f{i}"].astype(np.int32)) for i in range(count)]
            return Decomposition(parts, True, float(data["seconds"]), bool(data["capped"]), key)
    except (OSError, KeyError, ValueError):
        return None  # absent, or unreadable: computed again and replaced


def _store(path: str, parts: list[tuple[Points, Triangles]], seconds: float, capped: bool, version: str) -> None:
    arrays: dict[str, npt.NDArray[np.generic]] = {
        "count": np.array(len(parts)),
        "seconds": np.array(seconds),
        "capped": np.array(capped),
    }
    for i, (v, f) in enumerate(parts):
        arrays[f"v{i}"] = np.asarray(v, dtype=np.float64)
        arrays[f"f{i}"] = np.asarray(f, dtype=np.int32)
    buffer = io.BytesIO()
    np.savez(buffer, **arrays)  # type: ignore[arg-type]
    try:
        write_atomic(path, buffer.getvalue())
        _remember_version(os.path.dirname(path), version)
    except OSError:
        pass  # a read-only cache: the parts are still used, computed again next time


def _remember_version(folder: str, version: str) -> None:
    """versions.txt lists the CoACD versions entries were made with (read when CoACD is absent)."""
    index = os.path.join(folder, "versions.txt")
    try:
        with open(index, encoding="utf-8") as handle:
            known = [line.strip() for line in handle if line.strip()]
    except OSError:
        known = []
    if version not in known:
        write_atomic(index, "".join(f"{v}\n" for v in [*known, version]))


# The child process: reads the mesh and CoACD's arguments, writes the parts.
_WORKER = """
import json, sys
import numpy as np
import coacd
coacd.set_log_level("error")
with np.load(sys.argv[1]) as data:
    mesh = coacd.Mesh(data["points"], data["triangles"])
    args = json.loads(str(data["args"]))
parts = coacd.run_coacd(mesh, **args)
out = {"count": np.array(len(parts))}
for i, (v, f) in enumerate(parts):
    out[f"v{i}"] = np.asarray(v, dtype=np.float64)
    out[f"f{i}"] = np.asarray(f, dtype=np.int32)
np.savez(sys.argv[2], **out)
"""


def _run_coacd(points: Points, triangles: Triangles, settings: DecompositionSettings) -> list[tuple[Points, Triangles]]:
    with tempfile.TemporaryDirectory(prefix="robodesc-coacd-") as tmp:
        src, dst = os.path.join(tmp, "in.npz"), os.path.join(tmp, "out.npz")
        np.savez(src, points=points, triangles=triangles, args=np.array(json.dumps(settings.coacd_arguments())))
        try:
            done = subprocess.run(
                [sys.executable, "-c", _WORKER, src, dst],
                capture_output=True,
                timeout=settings.timeout,
                check=False,
            )
        except subprocess.TimeoutExpired:
            raise DecompositionUnavailable(f"CoACD took longer than {settings.timeout:g} s") from None
        if done.returncode != 0 or not os.path.isfile(dst):
            tail = done.stderr.decode(errors="replace").strip().splitlines()[-1:] or [f"exit {done.returncode}"]
            raise DecompositionUnavailable(f"CoACD failed ({tail[0]})")
        with np.load(dst) as data:
            return [
                (data[f"v{i}"].astype(np.float64), data[f"f{i}"].astype(np.int32)) for i in range(int(data["count"]))
            ]
