"""URDF files as an input: ``.urdf``, and ``.xml`` whose root element is ``<robot>``."""

from __future__ import annotations

from robodesc.frontends.contract import Frontend, named_robot, xml_root
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot


def read_urdf(path: str, options: LoadOptions, findings: Findings) -> Robot:
    from robodesc.frontends.urdf import read_urdf_string
    from robodesc.frontends.xml_safety import read_file

    return read_urdf_string(read_file(path), file=path, options=options, findings=findings)


FRONTEND = Frontend(
    name="urdf",
    label="URDF (.urdf, .xml)",
    suffixes=(".urdf", ".xml"),
    read=read_urdf,
    sniff=lambda head: xml_root(head) == "robot",
    discover=named_robot,
)
