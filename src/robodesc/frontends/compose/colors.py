"""Colour spellings compositions use: ``#rgb``, ``#rgba``, ``#rrggbb``, ``#rrggbbaa``, names, tuples."""

from __future__ import annotations

from collections.abc import Sequence

from robodesc.ir.geometry import RGBA

# CSS basic colours plus the few extra names robot files use.
NAMED: dict[str, str] = {
    "black": "#000000",
    "white": "#ffffff",
    "red": "#ff0000",
    "green": "#008000",
    "lime": "#00ff00",
    "blue": "#0000ff",
    "yellow": "#ffff00",
    "cyan": "#00ffff",
    "aqua": "#00ffff",
    "magenta": "#ff00ff",
    "fuchsia": "#ff00ff",
    "gray": "#808080",
    "grey": "#808080",
    "darkgray": "#a9a9a9",
    "darkgrey": "#a9a9a9",
    "lightgray": "#d3d3d3",
    "lightgrey": "#d3d3d3",
    "silver": "#c0c0c0",
    "maroon": "#800000",
    "olive": "#808000",
    "navy": "#000080",
    "purple": "#800080",
    "teal": "#008080",
    "orange": "#ffa500",
    "brown": "#a52a2a",
    "pink": "#ffc0cb",
    "gold": "#ffd700",
    "steelblue": "#4682b4",
}


class ColorError(ValueError):
    """The text is not a colour; the message says what is accepted."""


def parse_color(value: str | Sequence[float]) -> RGBA:
    """An RGBA tuple in [0, 1] from any accepted spelling.

    >>> parse_color("#f00")
    (1.0, 0.0, 0.0, 1.0)
    """
    if not isinstance(value, str):
        comps = [float(c) for c in value]
        if len(comps) not in (3, 4) or any(not 0.0 <= c <= 1.0 for c in comps):
            raise ColorError("a colour list needs 3 or 4 components in [0, 1]")
        if len(comps) == 3:
            comps.append(1.0)
        return (comps[0], comps[1], comps[2], comps[3])
    text = value.strip().lower()
    if not text.startswith("#"):
        if text not in NAMED:
            raise ColorError(f"unknown colour {value!r} (use #rgb, #rrggbb, #rrggbbaa or a name like 'red')")
        text = NAMED[text]
    digits = text[1:]
    if len(digits) in (3, 4):
        digits = "".join(ch * 2 for ch in digits)
    if len(digits) not in (6, 8) or any(ch not in "0123456789abcdef" for ch in digits):
        raise ColorError(f"bad colour {value!r} (use #rgb, #rgba, #rrggbb or #rrggbbaa)")
    if len(digits) == 6:
        digits += "ff"
    r, g, b, a = (int(digits[i : i + 2], 16) / 255.0 for i in range(0, 8, 2))
    return (r, g, b, a)


def color_hex(rgba: RGBA) -> str:
    """``rrggbb`` (and ``aa`` when not opaque), for stable material names."""
    parts = [round(c * 255) for c in rgba]
    text = "".join(f"{p:02x}" for p in parts[:3])
    return text if parts[3] == 255 else text + f"{parts[3]:02x}"
