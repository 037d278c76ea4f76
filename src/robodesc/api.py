"""The Python API: everything the CLI does, as functions.

>>> import robodesc
>>> result = robodesc.compile_to_urdf("robot.urdf.xacro", "out/robot.urdf",
...                                   package_paths={"my_pkg": "src/my_pkg"})
>>> [f.render() for f in result.findings]

``source`` is a path (URDF, xacro, YAML, ``.holo``), a string of URDF XML, an IR :class:`Robot`,
or any object with a ``build() -> Robot`` method (the composition builder). Options are keyword
arguments; an unknown one raises :class:`ConfigError` naming the closest valid option.
"""

from __future__ import annotations

import os
from typing import Any

from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot
from robodesc.options import build_options
from robodesc.pipeline import CompileResult, Progress, Source, compile_robot, load_source, verify_source

__all__ = ["CompileResult", "compile_to_urdf", "load"]


def _out(path: str | os.PathLike[str] | None) -> str | None:
    return os.fspath(path) if path is not None else None


def load(source: Source, **options: Any) -> Robot:
    """Read ``source`` into the IR and verify it (warnings are dropped; use :func:`inspect` to see them)."""
    opts = build_options(options)
    findings = Findings()
    robot = load_source(source, opts, findings)
    verify_source(robot, opts, findings)
    return robot


def compile_to_urdf(
    source: Source, out: str | os.PathLike[str] | None = None, *, progress: Progress | None = None, **options: Any
) -> CompileResult:
    """Compile to URDF. With ``out`` the file is written atomically; ``result.text`` always holds it."""
    opts = build_options(options)
    return compile_robot(source, "urdf", _out(out), opts, **({"progress": progress} if progress else {}))
