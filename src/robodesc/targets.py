"""The target table: each target's name and the package that exports its ``TARGET``.

This is the one place the driver names targets. Packages are imported when something asks for
them, so a URDF compile does not load the USD writer. Adding a target is adding a package under
``robodesc/emit/`` that exports a :class:`~robodesc.emit.common.target.Target`, and a line here.
"""

from __future__ import annotations

import importlib

from robodesc.emit.common.target import Target
from robodesc.ir.diagnostics import ConfigError

TARGETS: dict[str, str] = {
    "urdf": "robodesc.emit.urdf",
    "sdf": "robodesc.emit.sdf",
    "usd": "robodesc.emit.usd",
    "ros2": "robodesc.emit.ros2",
    "isaac": "robodesc.emit.isaac",
    "mjcf": "robodesc.emit.mjcf",
}


# The target of a compile that names none: the table's first.
DEFAULT_TARGET = next(iter(TARGETS))


def target_spec(name: str) -> Target:
    if name not in TARGETS:
        raise ConfigError(f"unknown target {name!r} (one of {', '.join(TARGETS)})")
    spec = importlib.import_module(TARGETS[name]).TARGET
    if not isinstance(spec, Target) or spec.name != name:
        raise ConfigError(f"{TARGETS[name]} does not export TARGET = Target(name={name!r}, ...)")
    return spec
