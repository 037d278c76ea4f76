"""Mesh files as Drake needs them for contact: Drake computes the convex hull of a collision mesh
itself, but only from OBJ, VTK and glTF files (STL and DAE are refused with "MakeConvexHull only
applies to ..."). A copy of the file to simulate names OBJ conversions instead, cached by the
source file's path, size and modification time. An engine's format gap, not the file's defect."""

from __future__ import annotations

import hashlib
import os
import tempfile
from collections.abc import Mapping

import numpy as np
from lxml import etree

from robodesc._files import write_atomic
from robodesc.ir.model import Robot
from robodesc.validation.meshes import ir_meshes, resolve_mesh_file

DRAKE_FORMATS = (".obj", ".vtk", ".gltf")


def drake_readable(
    robot: Robot, path: str, package_paths: Mapping[str, str], *, collisions: bool = True, shapes: bool = True
) -> str:
    """A copy of ``path`` without visuals, with meshes Drake hulls; without colliders when
    ``collisions`` is False (a run without contact: Drake then skips every convex hull); with each
    collider's shape a 1 cm box when ``shapes`` is False (only its surface is read: the slide's
    friction, without hulling every mesh of a 40-link robot)."""
    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=True)
    tree = etree.parse(path, parser)
    base = os.path.dirname(os.path.abspath(path))
    # Visuals play no part in a simulation, and their package:// URIs would need Drake's package map.
    visuals = list(tree.getroot().iter("visual")) + ([] if collisions else list(tree.getroot().iter("collision")))
    for visual in visuals:
        visual.getparent().remove(visual)
    changed = bool(visuals)
    if collisions and not shapes:
        for geometry in [g for c in tree.getroot().iter("collision") for g in c.findall("geometry")]:
            for child in list(geometry):
                geometry.remove(child)
            box = etree.SubElement(geometry, "box")
            if path.lower().endswith(".urdf"):
                box.set("size", "0.01 0.01 0.01")
            else:
                etree.SubElement(box, "size").text = "0.01 0.01 0.01"
            changed = True
    resolved = {g.uri: g.path for g in ir_meshes(robot) if g.path is not None}
    for mesh in tree.getroot().iter("mesh"):
        uri_el = mesh.find("uri")
        ref = (uri_el.text if uri_el is not None else mesh.get("filename")) or ""
        ref = ref.strip()
        if not ref:
            continue
        try:
            found = resolved.get(ref) or resolve_mesh_file(ref, robot, base, package_paths)
            obj = found if found.lower().endswith(DRAKE_FORMATS) else _as_obj(found)
        except Exception:  # Drake reports the file it cannot read; nothing better to give it
            continue
        if uri_el is not None:
            uri_el.text = "file://" + obj
        else:
            mesh.set("filename", obj)
        changed = True
    if not changed:
        return path
    prefix = "drake-" if collisions and shapes else "drake-boxes-" if collisions else "drake-nocontact-"
    out = os.path.join(base, prefix + os.path.basename(path))
    write_atomic(out, etree.tostring(tree, xml_declaration=True, encoding="utf-8"))
    return out


def _as_obj(path: str) -> str:
    from robodesc.meshes.data import build_mesh

    st = os.stat(path)
    key = hashlib.sha256(f"{os.path.abspath(path)}|{st.st_size}|{st.st_mtime_ns}".encode()).hexdigest()[:24]
    folder = os.path.join(tempfile.gettempdir(), "robodesc-drake-meshes")
    out = os.path.join(folder, key + ".obj")
    if os.path.exists(out):
        return out
    data = build_mesh(path, None)
    points = np.frombuffer(data.points, dtype=np.float32).reshape(-1, 3)
    faces = np.frombuffer(data.face_vertex_indices, dtype=np.int32).reshape(-1, 3) + 1
    lines = [f"v {x:.9g} {y:.9g} {z:.9g}" for x, y, z in points.tolist()]
    lines += [f"f {a} {b} {c}" for a, b, c in faces.tolist()]
    os.makedirs(folder, exist_ok=True)
    write_atomic(out, "\n".join(lines) + "\n")
    return out
