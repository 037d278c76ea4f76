"""Ordered ``{regex: value}`` tables: "first matching rule wins", as Isaac Lab and Quad-SDK write them.

Used for per-joint gains, armature and renames. A plain number applies to every name.

The tables robodesc derives itself name every joint (``{re.escape(name): value, ..., ".*": default}``),
so a robot of n joints asks n questions of a table of n rules. Each table is compiled once (cached
by identity: option tables are replaced, never edited in place), and a run of literal patterns is
one dictionary lookup: a 50,000-joint chain's gains are then linear instead of 2.5e9 regex matches.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any, TypeVar

from robodesc.ir.diagnostics import ConfigError

T = TypeVar("T")

Table = Mapping[str, T]

# A pattern that matches exactly one string: no metacharacter, only escaped punctuation.
_LITERAL = re.compile(r"(?:[^\\.^$*+?{}\[\]|()]|\\[^A-Za-z0-9])*")
_UNESCAPE = re.compile(r"\\(.)", re.S)


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


class _Compiled:
    """A table as segments: a run of literal patterns is a dict (the first of equal literals wins),
    any other pattern a compiled regex; searched in the table's order."""

    __slots__ = ("segments",)

    def __init__(self, table: Mapping[str, Any], what: str) -> None:
        self.segments: list[dict[str, Any] | tuple[re.Pattern[str], Any]] = []
        run: dict[str, Any] | None = None
        for (pattern, value), (compiled, _) in zip(table.items(), compile_table(table, what), strict=True):
            if _LITERAL.fullmatch(pattern):
                if run is None:
                    run = {}
                    self.segments.append(run)
                run.setdefault(_UNESCAPE.sub(r"\1", pattern), value)
            else:
                run = None
                self.segments.append((compiled, value))

    def find(self, name: str) -> Any:
        for segment in self.segments:
            if isinstance(segment, dict):
                if name in segment:
                    return segment[name]
            elif segment[0].fullmatch(name):
                return segment[1]
        return None


# id(table) -> (table, its size when compiled, compiled). The table itself is held, so its id is
# not reused while cached; a few tables are live at a time.
_CACHE: dict[int, tuple[Mapping[str, Any], int, _Compiled]] = {}
_CACHE_SIZE = 16


def _compiled(table: Mapping[str, Any], what: str) -> _Compiled:
    hit = _CACHE.get(id(table))
    if hit is not None and hit[0] is table and hit[1] == len(table):
        return hit[2]
    compiled = _Compiled(table, what)
    if len(_CACHE) >= _CACHE_SIZE:
        _CACHE.pop(next(iter(_CACHE)))
    _CACHE[id(table)] = (table, len(table), compiled)
    return compiled


def lookup(spec: float | Mapping[str, float] | None, name: str, what: str) -> float | None:
    """A number for ``name`` from a plain number or a regex table (``None`` when nothing matches)."""
    if spec is None:
        return None
    if isinstance(spec, int | float):
        return float(spec)
    found = _compiled(spec, what).find(name)
    return None if found is None else float(found)
