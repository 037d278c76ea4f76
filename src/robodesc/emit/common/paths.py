"""How emitters write file references (meshes, textures)."""

from __future__ import annotations

import enum
import os

from robodesc.ir.geometry import Mesh


class PathMode(enum.Enum):
    RELATIVE = "relative"  # relative to the output file (portable; the default)
    ABSOLUTE = "absolute"
    PACKAGE = "package"  # package://name/... where the input used a package, else relative
    KEEP = "keep"  # exactly as the input wrote it


def mesh_reference(mesh: Mesh, mode: PathMode, out_dir: str | None) -> str:
    return file_reference(mesh.uri, mesh.path, mesh.package, mode, out_dir)


def file_reference(
    uri: str, path: str | None, package: tuple[str, str] | None, mode: PathMode, out_dir: str | None
) -> str:
    if mode is PathMode.KEEP or path is None:
        return uri
    if mode is PathMode.PACKAGE and package is not None:
        return f"package://{package[0]}/{package[1]}"
    if mode is PathMode.ABSOLUTE or out_dir is None:
        return path
    return os.path.relpath(path, os.path.abspath(out_dir)).replace(os.sep, "/")
