"""Mesh files as MuJoCo needs them: absolute paths, in a format it decodes.

MuJoCo opens neither ``package://`` nor ``file://`` URIs and decodes only STL, OBJ and its own MSH;
everything else is converted to STL into a cache keyed by the source file's path, size and
modification time, so a corpus run converts each file once. COLLADA (and ASCII STL) go through
robodesc's own readers (``meshes.data.build_mesh``), the ones the USD writer uses, so the same
limits apply wherever a mesh is read (an instance fan-out is refused in seconds instead of hanging
trimesh's DAE loader); other formats (PLY ...) through trimesh, as for the USD writer.
"""

from __future__ import annotations

import hashlib
import os
import tempfile
from collections.abc import Iterable, Mapping
from urllib.parse import unquote

from robodesc._files import write_atomic
from robodesc.ir.geometry import Mesh
from robodesc.ir.model import Robot
from robodesc.meshes.trimesh_io import load_trimesh

MUJOCO_FORMATS = (".stl", ".obj", ".msh")
# Formats robodesc reads itself (meshes/), with its size and instancing limits.
OWN_READERS = (".dae", ".stl", ".obj")


class MeshProblem(Exception):
    """A mesh file that cannot be found or converted; the message says why."""


def ir_meshes(robot: Robot) -> Iterable[Mesh]:
    for link in robot.links:
        for geom in [v.geometry for v in link.visuals] + [c.geometry for c in link.collisions]:
            if isinstance(geom, Mesh):
                yield geom


def resolve_mesh_file(ref: str, robot: Robot, base_dir: str | None, package_paths: Mapping[str, str]) -> str:
    """The absolute file a mesh reference in emitted text points to.

    ``package://`` goes through the IR first (the frontend recorded which file each package path
    resolved to), then through ``package_paths``.
    """
    if ref.startswith("file://"):
        return os.path.abspath(unquote(ref[len("file://") :]))
    if ref.startswith("package://"):
        rest = ref[len("package://") :]
        name, _, inner = rest.partition("/")
        for mesh in ir_meshes(robot):
            if mesh.package == (name, inner) and mesh.path is not None:
                return mesh.path
            if mesh.uri == ref and mesh.path is not None:
                return mesh.path
        if name in package_paths:
            return os.path.abspath(os.path.join(package_paths[name], inner))
        raise MeshProblem(f"package {name!r} is unknown (pass its folder with --package {name}=DIR)")
    if os.path.isabs(ref):
        return ref
    if base_dir is None:
        raise MeshProblem("relative mesh path but no base folder to resolve it against")
    return os.path.abspath(os.path.join(base_dir, ref))


def _ascii_stl(path: str) -> bool:
    """MuJoCo decodes binary STL only. A binary file's size is 84 + 50 per triangle."""
    if not path.lower().endswith(".stl"):
        return False
    size = os.path.getsize(path)
    with open(path, "rb") as handle:
        head = handle.read(84)
    if len(head) < 84:
        return head.lstrip().startswith(b"solid")
    count = int.from_bytes(head[80:84], "little")
    return 84 + 50 * count != size and head.lstrip().startswith(b"solid")


def default_cache_dir() -> str:
    return os.path.join(tempfile.gettempdir(), f"robodesc-mesh-cache-{os.getuid() if hasattr(os, 'getuid') else 0}")


def _stl_bytes(path: str) -> bytes:
    """A binary STL of the mesh robodesc's reader makes of ``path`` (MeshProblem when it refuses it)."""
    import numpy as np

    from robodesc.meshes.buffers import MeshReadError
    from robodesc.meshes.data import build_mesh

    try:
        data = build_mesh(path, None)
    except MeshReadError as exc:
        raise MeshProblem(f"cannot convert {path} for MuJoCo: {exc}") from None
    points = np.frombuffer(data.points, dtype=np.float32).reshape(-1, 3)
    faces = np.frombuffer(data.face_vertex_indices, dtype=np.int32).reshape(-1, 3)
    normals = np.frombuffer(data.normals, dtype=np.float32).reshape(-1, 3)
    if len(faces) == 0:
        raise MeshProblem(f"mesh file {path} has no triangles")
    record = np.dtype([("normal", "<f4", 3), ("vertices", "<f4", (3, 3)), ("attr", "<u2")])
    body = np.zeros(len(faces), dtype=record)
    body["normal"] = normals
    body["vertices"] = points[faces]
    header = b"robodesc: converted for MuJoCo".ljust(80, b" ") + len(faces).to_bytes(4, "little")
    return header + body.tobytes()


def mujoco_readable(path: str, cache_dir: str | None) -> str:
    """``path`` itself when MuJoCo decodes it, else a converted STL in the cache."""
    if not os.path.isfile(path):
        raise MeshProblem(f"mesh file {path} does not exist")
    if path.lower().endswith(MUJOCO_FORMATS) and not _ascii_stl(path):
        return path
    st = os.stat(path)
    key = hashlib.sha1(f"{os.path.abspath(path)}\0{st.st_size}\0{st.st_mtime_ns}".encode()).hexdigest()[:20]
    folder = cache_dir or default_cache_dir()
    out = os.path.join(folder, f"{key}.stl")
    if os.path.isfile(out):
        return out
    if path.lower().endswith(OWN_READERS):
        write_atomic(out, _stl_bytes(path))
        return out
    try:
        loaded = load_trimesh(path, process=False)
        if len(loaded.faces) == 0:
            raise MeshProblem(f"mesh file {path} has no triangles")
        data = loaded.export(file_type="stl")
    except MeshProblem:
        raise
    except Exception as exc:  # trimesh raises many types for unreadable files
        raise MeshProblem(f"cannot convert {path} for MuJoCo: {exc}") from exc
    write_atomic(out, data if isinstance(data, bytes) else str(data).encode())
    return out
