"""MuJoCo compiles the checked tree: the numbers every other module reads.

Why MuJoCo's compiler rather than robodesc's own reading of the attributes: the model *is* what
MuJoCo makes of the file. Defaults and ``childclass``, ``angle="degree"``, ``eulerseq``,
``axisangle``/``xyaxes``/``zaxis``, ``fromto``, ``<frame>``, ``autolimits`` and, above all,
``inertiafromgeom`` (a body's mass and inertia from its geoms' volumes and densities, meshes
included, with MuJoCo's shell and convex-hull rules) are read exactly as MuJoCo reads them, and the
round-trip tests compare with the same engine. :mod:`.source` has already made the tree safe to
hand over (no includes left, confined absolute asset paths, no plugins).

A mesh whose file is missing is compiled as a tiny placeholder tetrahedron, so the geom keeps its
place (the IR then keeps the reference as written); its mass, if it had to come from the mesh, is
wrong, and that is a warning.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from lxml import etree

from robodesc.frontends.mjcf.source import STAGE, MjcfSource, tag
from robodesc.ir.diagnostics import Findings, ParseError

if TYPE_CHECKING:
    import mujoco

_NAMED = re.compile(r"Element name '([^']+)'")
_LINE = re.compile(r",? line \d+")
_PLACEHOLDER = "0 0 0  0.001 0 0  0 0.001 0  0 0 0.001"


def compile_model(source: MjcfSource, findings: Findings) -> mujoco.MjModel:
    import mujoco

    root = _placeholders(source, findings)
    xml = etree.tostring(root, encoding="unicode")
    try:
        return mujoco.MjModel.from_xml_string(xml)
    except ValueError as exc:
        # MuJoCo's message ends "Element name 'knee', id 3, line 7": the line is in the expanded text
        # MuJoCo was given, so the element is found by its name in the files it was written in.
        message = str(exc).strip().replace("\n", "; ")
        named = _NAMED.search(message)
        where = source.root
        if named is not None:
            where = next((el for el in source.root.iter() if el.get("name") == named.group(1)), source.root)
        message = _LINE.sub("", message)
        raise ParseError(f"MuJoCo cannot compile this model: {message}", loc=source.loc(where)) from None


def _placeholders(source: MjcfSource, findings: Findings) -> etree._Element:
    if not source.missing_meshes:
        return source.root
    root = etree.fromstring(etree.tostring(source.root))  # the IR keeps the original tree
    inertia_from_mesh = all(c.get("inertiafromgeom") != "false" for c in root.iter("compiler"))
    for el in root.iter("mesh"):
        parent = el.getparent()
        if parent is None or tag(parent) != "asset" or el.get("file") is None:
            continue
        name = el.get("name") or _stem(el.get("file", ""))
        if name in source.missing_meshes:
            del el.attrib["file"]
            el.set("name", name)
            el.set("vertex", _PLACEHOLDER)
            for attr in ("scale", "refpos", "refquat"):
                if attr in el.attrib:
                    del el.attrib[attr]
    if inertia_from_mesh:
        findings.warn(
            "mjcf-mass-from-missing-mesh",
            f"{len(source.missing_meshes)} mesh file(s) are missing: a body whose inertia comes from its geoms "
            "(no <inertial>) gets a placeholder mass for those meshes",
            element="compiler",
            loc=source.loc(source.root),
            stage=STAGE,
        )
    return root


def _stem(file: str) -> str:
    import os

    return os.path.splitext(os.path.basename(file))[0]
