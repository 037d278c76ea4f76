"""The input itself, for engines that read it (MuJoCo and Drake read URDF): written to a scratch
file with every mesh reference replaced by the file the IR resolved it to, so that it loads from
anywhere (``package://`` and relative paths would otherwise resolve against the scratch folder)."""

from __future__ import annotations

import os

from lxml import etree

from robodesc.ir.geometry import Mesh
from robodesc.ir.model import Robot


def write_source(robot: Robot, text: str, folder: str) -> str | None:
    """The scratch file's path, or None when ``text`` is not a URDF robot."""
    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=True)
    try:
        root = etree.fromstring(text.encode("utf-8"), parser)
    except etree.XMLSyntaxError:
        return None
    if root.tag != "robot":
        return None
    resolved: dict[str, str] = {}
    for link in robot.links:
        for geom in [c.geometry for c in link.collisions] + [v.geometry for v in link.visuals]:
            if isinstance(geom, Mesh) and geom.path is not None:
                resolved[geom.uri] = geom.path
    for mesh in root.iter("mesh"):
        path = resolved.get(mesh.get("filename", ""))
        if path is not None:
            mesh.set("filename", path)
    out = os.path.join(folder, "source-input.urdf")
    with open(out, "wb") as fh:
        fh.write(etree.tostring(root, xml_declaration=True, encoding="utf-8"))
    return out
