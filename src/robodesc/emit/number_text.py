"""Whitespace-separated numbers in mesh text (COLLADA arrays, OBJ lines) as numpy arrays.

The C extension ``robodesc._numtext`` parses them about seven times faster than numpy's own parser,
to the same bits (see its source). It is built at install time and optional: without a C compiler
numpy parses instead, more slowly, with the same results.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
from numpy.typing import NDArray

try:
    from robodesc import _numtext
except ImportError:  # installed without a C compiler
    _numtext = None  # type: ignore[assignment]


def native() -> bool:
    """Whether the C parser is in use."""
    return _numtext is not None


def parse_floats(text: str | bytes | None) -> NDArray[np.float64] | None:
    """The numbers in ``text`` as a 1-D float64 array, or None if any token is not a number."""
    out: NDArray[np.float64] | None = _parse(text, np.float64)
    return out


def parse_ints(text: str | bytes | None) -> NDArray[np.int64] | None:
    """The integers in ``text`` as a 1-D int64 array, or None if any token is not an integer."""
    out: NDArray[np.int64] | None = _parse(text, np.int64)
    return out


def _parse(text: str | bytes | None, dtype: type[np.float64] | type[np.int64]) -> Any:
    if not text:
        return np.zeros(0, dtype=dtype)
    if _numtext is not None:
        try:
            raw = _numtext.parse(text, dtype is np.int64)
        except ValueError:
            return None
        return np.frombuffer(raw, dtype=dtype)
    if text.isspace():  # fromstring reads an all-blank text as [-1]
        return np.zeros(0, dtype=dtype)
    # fromstring signals trailing junk with a warning on numpy 1.x and a ValueError on 2.x.
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", DeprecationWarning)
            return np.fromstring(text, dtype=dtype, sep=" ")
    except (ValueError, DeprecationWarning):
        return None
