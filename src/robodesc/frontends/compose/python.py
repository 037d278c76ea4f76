"""Python compositions: a file that defines ``build() -> Robot`` (docs/compositions.md).

It is a program, so reading it runs it: only for a file the user named (``compile FILE.py``, a
manifest entry, ``batch --run-python``), never one found by searching a folder."""

from __future__ import annotations

import os
import re
import sys

from robodesc.frontends.contract import Frontend
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings, ParseError, SourceLoc
from robodesc.ir.model import Robot


def read_python(path: str, options: LoadOptions, findings: Findings) -> Robot:
    import runpy

    if not os.path.isfile(path):
        raise ParseError("input file not found", loc=SourceLoc(path))
    here = os.path.dirname(os.path.abspath(path))
    sys.path.insert(0, here)  # its sibling modules, as `python file.py` sees them
    try:
        namespace = runpy.run_path(path, run_name="robodesc_composition")
        build = namespace.get("build")
        robot = build() if callable(build) else None
    except SystemExit as exc:
        # A program's exit() ends a compile or a batch job, not robodesc.
        raise ParseError(
            f"the composition called exit({exc.code!r}) instead of returning a Robot", loc=SourceLoc(path)
        ) from None
    finally:
        sys.path.remove(here)
    if not callable(build):
        raise ParseError(
            "a Python composition defines build() returning a Robot; this file does not", loc=SourceLoc(path)
        )
    if not isinstance(robot, Robot):
        raise ParseError(f"build() returned {type(robot).__name__}, not a Robot", loc=SourceLoc(path))
    if robot.source_file is None:
        robot.source_file = path
    return robot


def python_robot(path: str) -> tuple[bool, list[str]]:
    """Discovery (only with ``batch --run-python``): a file that uses robodesc and defines build()."""
    from robodesc.frontends.contract import head_of

    text = head_of(path, 65536)
    return "robodesc" in text and re.search(r"^def build\(", text, re.M) is not None, []


FRONTEND = Frontend(
    name="python",
    label="Python compositions (.py, they run)",
    suffixes=(".py",),
    read=read_python,
    runs_code=True,
    discover=python_robot,
)
