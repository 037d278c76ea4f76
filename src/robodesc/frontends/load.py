"""The one door for input: pick the frontend for a source and build the IR.

Frontends are listed in :data:`FRONTENDS` (a name and the module that exports its ``FRONTEND``, a
:class:`~robodesc.frontends.contract.Frontend`). A file is matched by suffix, then, where several
frontends take that suffix, by content; a file with no known suffix by content alone. Adding an
input format is adding a module (or package) that exports ``FRONTEND`` and a line here.
"""

from __future__ import annotations

import copy
import importlib
import os
from dataclasses import dataclass
from typing import Protocol

from robodesc.frontends.contract import Frontend, head_of
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import ConfigError, Findings, ParseError, SourceLoc
from robodesc.ir.model import Robot

FRONTENDS: dict[str, str] = {
    "urdf": "robodesc.frontends.urdf_input",
    "xacro": "robodesc.frontends.xacro_input",
    "yaml": "robodesc.frontends.compose",
    "holo": "robodesc.frontends.holo",
    "python": "robodesc.frontends.compose.python",
    "mjcf": "robodesc.frontends.mjcf",
    "sdf": "robodesc.frontends.sdf",
}

# How much of a file the content checks see.
HEAD_BYTES = 4096


class Buildable(Protocol):
    def build(self) -> Robot: ...


# What every compile and load takes: a path, URDF text, an IR robot, or a builder.
Source = str | os.PathLike[str] | Robot | Buildable


@dataclass(slots=True)
class Loaded:
    robot: Robot
    findings: Findings


def frontends() -> list[Frontend]:
    """Every registered frontend, in table order."""
    out = []
    for name, module in FRONTENDS.items():
        frontend = importlib.import_module(module).FRONTEND
        if not isinstance(frontend, Frontend) or frontend.name != name:
            raise ConfigError(f"{module} does not export FRONTEND = Frontend(name={name!r}, ...)")
        out.append(frontend)
    return out


def describe_inputs() -> str:
    """What robodesc reads, for messages and --help."""
    return ", ".join(f.label for f in frontends())


def frontend_for(path: str, *, allow_code: bool = True) -> Frontend:
    """The frontend that reads the file ``path``: by suffix, then by content. ``allow_code`` False
    passes over frontends that run the file (a file found by searching a folder)."""
    if os.path.isdir(path) and os.path.isfile(os.path.join(path, "model.config")):
        # A Gazebo model folder: its model.config names the SDF file.
        return frontend_for(os.path.join(path, "model.config"), allow_code=allow_code)
    if os.path.isdir(path):
        raise ParseError(
            "is a folder; robodesc compile reads one robot file (robodesc batch compiles every robot in a folder)",
            loc=SourceLoc(path),
        )
    if not os.path.exists(path):
        raise ParseError("input file not found", loc=SourceLoc(path))
    lower = path.lower()
    known = [f for f in frontends() if allow_code or not f.runs_code]
    matches = sorted(
        (f for f in known if any(lower.endswith(s) for s in f.suffixes)),
        key=lambda f: -max(len(s) for s in f.suffixes if lower.endswith(s)),
    )
    if len(matches) == 1:
        return matches[0]
    candidates = matches or [f for f in known if f.sniff is not None]
    head = head_of(path, HEAD_BYTES)
    for frontend in candidates:
        if frontend.sniff is not None and frontend.sniff(head):
            return frontend
    if matches:
        raise ParseError(
            f"not a format robodesc reads with this suffix (one of: {', '.join(f.label for f in matches)})",
            loc=SourceLoc(path),
        )
    raise ParseError(f"unknown input type (robodesc reads {describe_inputs()})", loc=SourceLoc(path))


def load_path(path: str, options: LoadOptions | None = None) -> Loaded:
    findings = Findings()
    robot = frontend_for(path).read(path, options or LoadOptions(), findings)
    return Loaded(robot, findings)


def load_string(text: str, options: LoadOptions | None = None, *, base_dir: str | None = None) -> Loaded:
    """Load URDF given as a string (relative mesh paths resolve against ``base_dir``)."""
    from robodesc.frontends.urdf import read_urdf_string

    findings = Findings()
    robot = read_urdf_string(
        text, file="<string>", base_dir=base_dir, options=options or LoadOptions(), findings=findings
    )
    return Loaded(robot, findings)


def load_source(source: Source, options: LoadOptions, findings: Findings) -> Robot:
    """Any accepted source -> a fresh IR the caller may mutate."""
    if isinstance(source, Robot):
        return copy.deepcopy(source)
    build = getattr(source, "build", None)
    if callable(build):
        robot = build()
        if not isinstance(robot, Robot):
            raise ConfigError(f"{type(source).__name__}.build() returned {type(robot).__name__}, not a Robot")
        return robot
    text = os.fspath(source)  # type: ignore[arg-type]
    loaded = load_string(text, options) if text.lstrip().startswith("<") else load_path(text, options)
    findings.extend(loaded.findings)
    return loaded.robot
