"""Where mesh and texture files may be read from into an output: one rule for ``--copy-meshes``
(which copies the file) and the USD writer (which embeds its geometry).

A file is used when its real path (every symlink followed) lies inside the input's folder or the
root of a package the loader found: given with ``--package``, found for a ``package://`` reference
or for xacro's ``$(find pkg)``. A file outside them, however
it is reached (an absolute path, ``../``, a symlinked folder), is not read: the caller keeps the
reference (URDF, SDF) or leaves the shape out (USD), with a warning.
"""

from __future__ import annotations

import os

from robodesc.ir.geometry import Mesh
from robodesc.ir.model import Robot


def allowed_roots(robot: Robot) -> list[str]:
    """Real paths of the folders files may be read from: the input's folder, the root of every
    package a mesh or texture was found in, and of every package the loader found."""
    roots: list[str] = []
    if robot.source_file:
        roots.append(os.path.dirname(os.path.abspath(robot.source_file)))
    # Packages the loader found (--package, $(find), package://): a mesh under one is inside it
    # whatever path named it (moveit_resources' Panda reaches its meshes through $(find)).
    roots.extend(robot.package_roots)
    for link in robot.links:
        geometries = [v.geometry for v in link.visuals] + [c.geometry for c in link.collisions]
        for geom in geometries:
            if isinstance(geom, Mesh) and geom.package is not None and geom.path is not None:
                inner = os.path.normpath(geom.package[1]) if geom.package[1] else ""
                path = os.path.normpath(geom.path)
                if inner and inner != "." and path.endswith(os.sep + inner):
                    roots.append(path[: -len(inner) - 1])
    return list(dict.fromkeys(os.path.realpath(r) for r in roots))


def outside_roots(source: str, roots: list[str]) -> str | None:
    """Why ``source`` must not be read into an output (its real path is outside ``roots``), or None."""
    real = os.path.realpath(source)
    if any(real == r or real.startswith(r.rstrip(os.sep) + os.sep) for r in roots):
        return None
    where = f" (through a symlink to {real!r})" if real != os.path.abspath(source) else ""
    return f"{source!r}{where} is outside the input's folder and its packages' roots"
