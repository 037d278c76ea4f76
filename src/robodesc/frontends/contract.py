"""The contract between the loader and a frontend: which files it reads and how.

A frontend package exports one :class:`Frontend`; :mod:`robodesc.frontends.load` finds it through
its table and knows nothing else about it. Files are matched by suffix and then by content, so
``.xml`` can be URDF, MJCF or SDF: each frontend that claims a suffix others claim too says, from
the head of the file, whether the file is its format.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass

from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot

ReadFunction = Callable[[str, LoadOptions, Findings], Robot]
# For folder discovery (``robodesc batch FOLDER``): whether the file at this path is a whole robot
# rather than a fragment, and the file names it includes (fragments others include are no robots).
DiscoverFunction = Callable[[str], tuple[bool, list[str]]]
# The first few kilobytes of a file, decoded leniently -> is this file the frontend's format.
SniffFunction = Callable[[str], bool]


@dataclass(slots=True, frozen=True)
class Frontend:
    name: str
    # What the format is called in messages and --help ("URDF", "HoloScript .holo").
    label: str
    suffixes: tuple[str, ...]
    read: ReadFunction
    sniff: SniffFunction | None = None
    # None: every file with one of ``suffixes`` is a robot.
    discover: DiscoverFunction | None = None
    # Reading the file runs it (a Python composition): only ever for a file the user named.
    runs_code: bool = False


# An XML file's root element: after the declaration, comments, processing instructions and a DOCTYPE.
_PROLOGUE = re.compile(r"\A(?:\ufeff)?(?:\s+|<\?.*?\?>|<!--.*?-->|<!DOCTYPE[^>\[]*(?:\[.*?\])?\s*>)*", re.DOTALL)
_TAG = re.compile(r"<([A-Za-z_][\w.\-]*:)?([A-Za-z_][\w.\-]*)")


def xml_root(head: str) -> str | None:
    """The local name of the root element of the XML text that starts with ``head``, or None."""
    rest = head[_PROLOGUE.match(head).end() :]  # type: ignore[union-attr]  # the pattern matches the empty string
    tag = _TAG.match(rest)
    return tag.group(2) if tag else None


_INCLUDE = re.compile(r"<xacro:include\b[^>]*\bfilename\s*=\s*[\"']([^\"']+)[\"']", re.S)
_ROOT = re.compile(r"<(?:[\w-]+:)?robot\b([^>]*)>", re.S)
_COMMENT = re.compile(r"<!--.*?-->", re.S)


def head_of(path: str, size: int) -> str:
    """The first ``size`` bytes of the regular file ``path``, decoded leniently (a named pipe or a
    device is refused without blocking on it)."""
    from robodesc.frontends.xml_safety import read_file

    return read_file(path, limit=size)[:size].decode("utf-8", errors="replace")


def named_robot(path: str) -> tuple[bool, list[str]]:
    """Discovery for URDF and xacro: the root is a named ``<robot>``; the files it includes."""
    text = _COMMENT.sub("", head_of(path, 1 << 22))
    root = _ROOT.search(text)
    named = root is not None and re.search(r"\bname\s*=", root.group(1)) is not None
    return named, [m.group(1) for m in _INCLUDE.finditer(text)]
