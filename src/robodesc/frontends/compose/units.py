"""Units a composition may be written in, and the small helpers that state them in code.

The IR is SI (m, kg, rad). Compositions let authors write angles in degrees and lengths in
millimetres; these helpers convert once, at the edge, so nothing downstream has to know.

>>> deg(-90, 90)
Range(lower=-1.5707963267948966, upper=1.5707963267948966)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

AngleUnit = Literal["rad", "deg"]
LengthUnit = Literal["m", "cm", "mm"]

ANGLE_UNITS: dict[str, float] = {"rad": 1.0, "deg": math.pi / 180.0}
LENGTH_UNITS: dict[str, float] = {"m": 1.0, "cm": 0.01, "mm": 0.001}


@dataclass(frozen=True, slots=True)
class Range:
    """A lower/upper pair already in SI (rad for angular joints, m for prismatic ones)."""

    lower: float
    upper: float


def angle_factor(unit: str) -> float:
    try:
        return ANGLE_UNITS[unit]
    except KeyError:
        raise ValueError(f"unknown angle unit {unit!r} (one of {', '.join(ANGLE_UNITS)})") from None


def length_factor(unit: str) -> float:
    try:
        return LENGTH_UNITS[unit]
    except KeyError:
        raise ValueError(f"unknown length unit {unit!r} (one of {', '.join(LENGTH_UNITS)})") from None


def deg(lower: float, upper: float) -> Range:
    """Joint limits written in degrees."""
    return Range(math.radians(lower), math.radians(upper))


def rad(lower: float, upper: float) -> Range:
    """Joint limits written in radians."""
    return Range(float(lower), float(upper))


def m(lower: float, upper: float) -> Range:
    """Prismatic limits written in metres."""
    return Range(float(lower), float(upper))


def mm(lower: float, upper: float) -> Range:
    """Prismatic limits written in millimetres."""
    return Range(lower / 1000.0, upper / 1000.0)
