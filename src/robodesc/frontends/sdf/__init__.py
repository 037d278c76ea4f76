"""SDF models as an input: an ``.sdf`` (or ``.xml``) whose ``<sdf>`` holds a ``<model>``, or a model
folder with its ``model.config`` (docs/sdf.md, "SDF as input"). A file holding a ``<world>`` is the
world frontend's (``--world``).

Light to import: the reader loads when a file is read.
"""

from __future__ import annotations

import re

from robodesc.frontends.contract import Frontend, head_of, xml_root
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot

_COMMENT = re.compile(r"<!--.*?-->", re.S)


def read(path: str, options: LoadOptions, findings: Findings) -> Robot:
    from robodesc.frontends.sdf.build import read_sdf_model

    return read_sdf_model(path, options, findings)


def sniff(head: str) -> bool:
    return xml_root(head) == "sdf"


def discover(path: str) -> tuple[bool, list[str]]:
    """A file with a ``<model>`` and no ``<world>`` is a robot; included models are found by URI, not
    by file name, so none are listed."""
    if path.endswith("model.config"):
        return False, []
    text = _COMMENT.sub("", head_of(path, 1 << 22))
    return xml_root(text) == "sdf" and "<model" in text and "<world" not in text, []


FRONTEND = Frontend(
    name="sdf",
    label="SDF model (.sdf, model.config)",
    suffixes=(".sdf", ".world", "model.config", ".xml"),
    read=read,
    sniff=sniff,
    discover=discover,
)
