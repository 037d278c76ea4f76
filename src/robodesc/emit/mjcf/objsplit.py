"""A multi-material OBJ split into one OBJ per material, so each part keeps its colour.

MuJoCo reads an OBJ as one mesh with one colour and ignores ``usemtl``. For a visual that uses
several materials, each material's faces are written as their own OBJ (only the vertices they use,
indices renumbered; texture coordinates and normals are left to MuJoCo) with the ``Kd`` colour and
``d`` opacity of the ``.mtl`` file, as mujoco_menagerie's obj2mjcf does.
"""

from __future__ import annotations

import os
from dataclasses import dataclass


@dataclass(slots=True, frozen=True)
class ObjPart:
    material: str
    rgba: tuple[float, float, float, float] | None
    text: bytes


def split_by_material(path: str) -> list[ObjPart] | None:
    """The parts of ``path``, or None when it uses fewer than two materials (or is not readable)."""
    try:
        with open(path, encoding="utf-8", errors="replace") as handle:
            lines = handle.read().splitlines()
    except OSError:
        return None
    if sum(1 for line in lines if line.startswith("usemtl")) < 2:
        return None
    vertices: list[str] = []
    faces: dict[str, list[list[int]]] = {}
    current = ""
    libraries: list[str] = []
    for line in lines:
        parts = line.split()
        if not parts:
            continue
        key = parts[0]
        if key == "v" and len(parts) >= 4:
            vertices.append(" ".join(parts[1:4]))
        elif key == "usemtl":
            current = " ".join(parts[1:])
        elif key == "mtllib":
            libraries.extend(parts[1:])
        elif key == "f" and len(parts) >= 4:
            corners = []
            for corner in parts[1:]:
                index = int(corner.split("/")[0])
                corners.append(index - 1 if index > 0 else len(vertices) + index)
            for i in range(1, len(corners) - 1):  # fan triangulation
                faces.setdefault(current, []).append([corners[0], corners[i], corners[i + 1]])
    if len(faces) < 2:
        return None
    colours = _materials(os.path.dirname(path), libraries)
    out = []
    for material, tris in faces.items():
        used = sorted({i for tri in tris for i in tri})
        renumber = {old: new + 1 for new, old in enumerate(used)}
        body = [f"v {vertices[i]}" for i in used]
        body += [f"f {renumber[a]} {renumber[b]} {renumber[c]}" for a, b, c in tris]
        text = ("# written by robodesc: material " + material + "\n" + "\n".join(body) + "\n").encode()
        out.append(ObjPart(material, colours.get(material), text))
    return out


def _materials(folder: str, libraries: list[str]) -> dict[str, tuple[float, float, float, float]]:
    """``Kd`` and ``d`` (or ``Tr``) of each material in the OBJ's ``.mtl`` files."""
    out: dict[str, tuple[float, float, float, float]] = {}
    for lib in libraries:
        try:
            with open(os.path.join(folder, lib), encoding="utf-8", errors="replace") as handle:
                lines = handle.read().splitlines()
        except OSError:
            continue
        name = None
        rgb = (0.8, 0.8, 0.8)
        alpha = 1.0
        for line in [*lines, "newmtl"]:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "newmtl":
                if name is not None:
                    out[name] = (*rgb, alpha)
                name, rgb, alpha = " ".join(parts[1:]) or None, (0.8, 0.8, 0.8), 1.0
            elif parts[0] == "Kd" and len(parts) >= 4:
                rgb = (float(parts[1]), float(parts[2]), float(parts[3]))
            elif parts[0] == "d" and len(parts) >= 2:
                alpha = float(parts[1])
            elif parts[0] == "Tr" and len(parts) >= 2:
                alpha = 1.0 - float(parts[1])
    return out
