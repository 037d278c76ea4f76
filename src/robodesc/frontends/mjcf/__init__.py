"""MuJoCo MJCF as an input: ``.xml`` whose root element is ``<mujoco>`` (docs/mjcf-input.md).

Light to import: the reader (and MuJoCo) load when a file is read.
"""

from __future__ import annotations

import re

from robodesc.frontends.contract import Frontend, head_of, xml_root
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot

_INCLUDE = re.compile(r"<include\b[^>]*\bfile\s*=\s*[\"']([^\"']+)[\"']", re.S)
_COMMENT = re.compile(r"<!--.*?-->", re.S)
_BODY = re.compile(r"<body\b")


def read(path: str, options: LoadOptions, findings: Findings) -> Robot:
    from robodesc.frontends.mjcf.reader import read_mjcf

    return read_mjcf(path, options, findings)


def discover(path: str) -> tuple[bool, list[str]]:
    """A model with a body is a robot; the files it includes are parts (a scene including its robot
    is a robot too: both are listed, as menagerie's folders hold them)."""
    text = _COMMENT.sub("", head_of(path, 1 << 22))
    is_model = xml_root(text) == "mujoco" and (_BODY.search(text) is not None or _INCLUDE.search(text) is not None)
    return is_model, [m.group(1) for m in _INCLUDE.finditer(text)]


FRONTEND = Frontend(
    name="mjcf",
    label="MJCF (.xml, .mjcf)",
    suffixes=(".mjcf", ".xml"),
    read=read,
    sniff=lambda head: xml_root(head) == "mujoco",
    discover=discover,
)
