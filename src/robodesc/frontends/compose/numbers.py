"""The one check every number a composition reads passes (YAML and HoloScript alike).

A file may spell a number the float range cannot hold (``1e999``, ``.inf``, ``.nan``): it is
refused here, where the element and its ``file:line:col`` are known, and never reaches the
geometry and rotation maths (where ``inf`` ends in a ``math domain error``). Finite values that no
target represents faithfully (``1e300`` kg) are the verifier's to refuse, with their unit.
"""

from __future__ import annotations

import math
import sys

from robodesc.ir.diagnostics import ParseError, SourceLoc

_LARGEST = sys.float_info.max


def finite(value: float, element: str, loc: SourceLoc | None, *, path: str = "", written: str | None = None) -> float:
    """``value`` when it is finite; else a :class:`ParseError` naming ``element`` (and ``path`` within it).

    ``written`` is the number as the file spells it, when the reader still has it.
    """
    if math.isfinite(value):
        return value
    if written is not None:
        shown = written
    elif math.isinf(value):
        shown = f"{value:g} (beyond the float range, ±{_LARGEST:.4g})"
    else:
        shown = f"{value:g}"
    where = f"{path}: " if path else ""
    raise ParseError(f"{where}expected a finite number, got {shown}", element=element, loc=loc)


__all__ = ["finite"]
