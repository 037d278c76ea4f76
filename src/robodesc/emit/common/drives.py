"""Checks of the drive options the targets that write drives share (USD, the Isaac folder, MJCF):
the same names and the same rules, so one --stiffness means the same thing everywhere."""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

from robodesc.ir.diagnostics import ConfigError

DRIVE_TYPES = ("force", "acceleration")
TARGET_TYPES = ("none", "position", "velocity")


def one_of(name: str, value: str, allowed: tuple[str, ...]) -> None:
    if value not in allowed:
        raise ConfigError(f"{name} must be one of {', '.join(allowed)}; got {value!r}")


def non_negative(name: str, value: object) -> None:
    if not isinstance(value, int | float) or isinstance(value, bool) or not value >= 0:
        raise ConfigError(f"{name} must be a number >= 0, got {value!r}")


def check_drives(options: Any) -> None:
    """``drive_type``, ``target_type``, and ``stiffness``/``damping``: a number >= 0, or ordered
    ``{regex: number >= 0}`` rules."""
    one_of("drive_type", options.drive_type, DRIVE_TYPES)
    one_of("target_type", options.target_type, TARGET_TYPES)
    for name in ("stiffness", "damping"):
        gain = getattr(options, name)
        if isinstance(gain, Mapping):
            for pattern, value in gain.items():
                try:
                    re.compile(pattern)
                except re.error as exc:
                    raise ConfigError(f"{name}: bad regular expression {pattern!r}: {exc}") from None
                non_negative(f"{name}[{pattern!r}]", value)
        else:
            non_negative(name, gain)
