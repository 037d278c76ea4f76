"""Python compositions: a file that defines ``build() -> Robot`` (docs/compositions.md).

It is a program, so reading it runs it: only for a file the user named (``compile FILE.py``, a
manifest entry, ``batch --run-python``), never one found by searching a folder."""

from __future__ import annotations

import os
import re
import sys

from robodesc.frontends.contract import Frontend
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings, ParseError, RobodescError, SourceLoc
from robodesc.ir.model import Robot

_PACKAGE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _raised_at(exc: BaseException, path: str) -> SourceLoc:
    """Where the composition's own code raised ``exc``: the innermost frame outside robodesc (a
    syntax error: its line), else the file itself."""
    import traceback

    if isinstance(exc, SyntaxError) and exc.filename:
        return SourceLoc(exc.filename, exc.lineno, exc.offset)
    frames = [f for f in traceback.extract_tb(exc.__traceback__) if not f.filename.startswith(_PACKAGE + os.sep)]
    frames = [f for f in frames if not f.filename.startswith("<frozen ")]
    if frames:
        return SourceLoc(frames[-1].filename, frames[-1].lineno)
    return SourceLoc(path)


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
    except RobodescError:
        raise  # the builder's own messages already name the place
    except Exception as exc:
        # The composition's code failed (its bug, a bad value): an input error at its own line, not
        # a robodesc bug. --debug is not needed to find it: the message says where.
        loc = _raised_at(exc, path)
        what = "has a syntax error" if isinstance(exc, SyntaxError) else f"raised {type(exc).__name__}"
        detail = exc.msg if isinstance(exc, SyntaxError) else str(exc)
        raise ParseError(f"the composition {what}: {detail}".rstrip(": "), loc=loc) from None
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
