"""One float format for every emitter, so golden files never churn.

``repr`` gives the shortest text that parses back to the same double; integral values drop the
trailing ``.0`` and negative zero is written as ``0``.
"""

from __future__ import annotations

from collections.abc import Iterable


def fmt(value: float) -> str:
    if value == 0:
        return "0"
    text = repr(float(value))
    if text.endswith(".0"):
        text = text[:-2]
    return text


def fmt_vec(values: Iterable[float]) -> str:
    return " ".join(fmt(v) for v in values)
