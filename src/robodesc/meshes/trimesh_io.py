"""Any mesh format trimesh knows (PLY, GLB, 3MF ...), for the readers that have no faster path.

One loader for the USD writer's fallback, the inertia passes and the MuJoCo validator, so that a
format robodesc learns to read is learnt everywhere at once. Importing trimesh costs over a second:
it is imported here, on first use.
"""

from __future__ import annotations

from typing import Any

from robodesc.meshes.buffers import MeshReadError


def load_trimesh(path: str, *, process: bool = True) -> Any:
    """The file's triangles as one ``trimesh.Trimesh`` (a scene is concatenated).

    ``process=False`` keeps vertices as they are in the file (no merging or reordering).
    Raises :class:`MeshReadError` when trimesh cannot read it or it holds no triangle mesh.
    """
    import trimesh

    try:
        loaded = trimesh.load(path, force="mesh", process=process)
    except Exception as exc:  # trimesh raises many types for bad files
        raise MeshReadError(f"{type(exc).__name__}: {exc}") from None
    if not isinstance(loaded, trimesh.Trimesh):
        raise MeshReadError("file holds no triangle mesh")
    return loaded
