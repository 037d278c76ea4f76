"""Ordered ``{regex: value}`` tables: "first matching rule wins", as Isaac Lab and Quad-SDK write them.

Used for per-joint gains, armature and renames. A plain number applies to every name.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import TypeVar

from robodesc.ir.diagnostics import ConfigError

T = TypeVar("T")

Table = Mapping[str, T]


def compile_table(table: Mapping[str, T], what: str) -> list[tuple[re.Pattern[str], T]]:
    out = []
    for pattern, value in table.items():
        try:
            out.append((re.compile(pattern), value))
        except re.error as exc:
            raise ConfigError(f"{what}: bad regular expression {pattern!r}: {exc}") from None
    return out


def first_match(rules: list[tuple[re.Pattern[str], T]], name: str) -> T | None:
    """The value of the first rule whose pattern matches the whole ``name``."""
    for pattern, value in rules:
        if pattern.fullmatch(name):
            return value
    return None


def lookup(spec: float | Mapping[str, float] | None, name: str, what: str) -> float | None:
    """A number for ``name`` from a plain number or a regex table (``None`` when nothing matches)."""
    if spec is None:
        return None
    if isinstance(spec, int | float):
        return float(spec)
    found = first_match(compile_table(spec, what), name)
    return None if found is None else float(found)
