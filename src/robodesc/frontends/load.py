"""Pick the frontend for an input and build the IR.

Frontends register by file suffix in :data:`FRONTENDS`; composition formats add themselves there.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass

from robodesc.frontends.options import LoadOptions
from robodesc.frontends.packages import PackageResolver
from robodesc.frontends.urdf import read_urdf_string
from robodesc.frontends.xacro_expand import expand_xacro
from robodesc.frontends.xml_safety import read_file
from robodesc.ir.diagnostics import Findings, ParseError, SourceLoc
from robodesc.ir.model import Robot

Frontend = Callable[[str, LoadOptions, Findings], Robot]


@dataclass(slots=True)
class Loaded:
    robot: Robot
    findings: Findings


def _load_urdf(path: str, options: LoadOptions, findings: Findings) -> Robot:
    return read_urdf_string(read_file(path), file=path, options=options, findings=findings)


def _load_xacro(path: str, options: LoadOptions, findings: Findings) -> Robot:
    resolver = PackageResolver(explicit=dict(options.package_paths), input_file=path)
    text = expand_xacro(
        path, options.xacro_args, resolver, findings, trust=options.trust_xacro, allowed_env=options.allowed_env
    )
    return read_urdf_string(
        text,
        file=f"{path} (expanded)",
        base_dir=os.path.dirname(os.path.abspath(path)),
        options=options,
        resolver=resolver,
        findings=findings,
    )


FRONTENDS: dict[str, Frontend] = {
    ".urdf": _load_urdf,
    ".xml": _load_urdf,
    ".xacro": _load_xacro,
}


def _composition_frontends() -> None:
    """Register composition frontends lazily (they import optional parsers)."""
    try:
        from robodesc.frontends.compose import register
    except ImportError:
        return
    register(FRONTENDS)


def load_path(path: str, options: LoadOptions | None = None) -> Loaded:
    opts = options or LoadOptions()
    findings = Findings()
    if not os.path.exists(path):
        raise ParseError("input file not found", loc=SourceLoc(path))
    lower = path.lower()
    if not lower.endswith((".urdf", ".xml", ".xacro")):
        _composition_frontends()  # yaml and the .holo parser cost ~40 ms to import: only when needed
    for suffix, frontend in sorted(FRONTENDS.items(), key=lambda kv: -len(kv[0])):
        if lower.endswith(suffix):
            return Loaded(frontend(path, opts, findings), findings)
    known = ", ".join(sorted(FRONTENDS))
    raise ParseError(f"unknown input type (robodesc reads {known})", loc=SourceLoc(path))


def load_string(text: str, options: LoadOptions | None = None, *, base_dir: str | None = None) -> Loaded:
    """Load URDF given as a string (relative mesh paths resolve against ``base_dir``)."""
    opts = options or LoadOptions()
    findings = Findings()
    robot = read_urdf_string(text, file="<string>", base_dir=base_dir, options=opts, findings=findings)
    return Loaded(robot, findings)
