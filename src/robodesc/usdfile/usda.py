"""The ``.usda`` text serialisation of a :class:`~robodesc.usdfile.spec.Layer`.

Written to match usd-core's own ``Sdf.Layer.ExportToString`` byte for byte on everything robodesc
writes (the tests hold it to that): properties sorted by name, children in authoring order, floats
as the shortest text that reads back to the same float32 or float64, in decimal notation for
scientific exponents from -6 to 14 and ``1e-7`` style outside.
"""

from __future__ import annotations

import math
import re
import struct
from array import array
from typing import Any

from robodesc.usdfile.spec import AssetPath, Attribute, Layer, Prim, Relationship, ValueType, value_type

INDENT = "    "
_F32 = struct.Struct("<f")
_F32_NORMAL = 1.1754943508222875e-38  # smallest normal float32


def usda_text(layer: Layer) -> str:
    out: list[str] = ["#usda 1.0\n"]
    meta = _layer_metadata(layer)
    if meta:
        out.append("(\n")
        out.extend(f"{INDENT}{line}\n" for line in meta)
        out.append(")\n")
    out.append("\n")
    texts: _Texts = {}
    for prim in layer.root.children.values():
        _prim(prim, 0, out, texts)
        out.append("\n")
    return "".join(out)


# The text of each array value written so far in one layer, by the array object's identity (the
# object is kept, so its id cannot be reused): 5,000 visuals of one mesh share its points, normals
# and indices, and were formatted 5,000 times (98.6 s). Arrays are never modified once in a layer.
_Texts = dict[int, tuple[Any, str]]
_SHARED_MIN = 16  # elements: shorter arrays cost less to format than to look up


def _layer_metadata(layer: Layer) -> list[str]:
    lines: list[str] = []
    if layer.default_prim is not None:
        lines.append(f"defaultPrim = {quote(layer.default_prim)}")
    if layer.kilograms_per_unit is not None:
        lines.append(f"kilogramsPerUnit = {format_double(layer.kilograms_per_unit)}")
    if layer.meters_per_unit is not None:
        lines.append(f"metersPerUnit = {format_double(layer.meters_per_unit)}")
    if layer.sublayers:
        inner = ",\n".join(f"{INDENT * 2}@{path}@" for path in layer.sublayers)
        lines.append(f"subLayers = [\n{inner}\n{INDENT}]")
    if layer.up_axis is not None:
        lines.append(f"upAxis = {quote(layer.up_axis)}")
    return lines


def _prim(prim: Prim, depth: int, out: list[str], texts: _Texts) -> None:
    pad = INDENT * depth
    head = f"{pad}{prim.specifier} "
    if prim.type_name:
        head += prim.type_name + " "
    head += quote(prim.name, allow_single=False)
    meta = _prim_metadata(prim, depth + 1)
    if meta:
        out.append(f"{head} (\n")
        out.extend(meta)
        out.append(f"{pad})\n")
    else:
        out.append(f"{head}\n")
    out.append(f"{pad}{{\n")
    inner = INDENT * (depth + 1)
    for name in sorted(prim.properties):
        prop = prim.properties[name]
        if isinstance(prop, Relationship):
            out.append(_relationship(prop, inner))
        else:
            out.append(_attribute(prop, inner, texts))
    first = not prim.properties
    for child in prim.children.values():
        if not first:
            out.append("\n")
        first = False
        _prim(child, depth + 1, out, texts)
    out.append(f"{pad}}}\n")


def _prim_metadata(prim: Prim, depth: int) -> list[str]:
    pad = INDENT * depth
    lines: list[str] = []
    if prim.deleted_api_schemas:
        lines.append(f"{pad}delete apiSchemas = [{', '.join(quote(s) for s in prim.deleted_api_schemas)}]\n")
    if prim.api_schemas:
        lines.append(f"{pad}prepend apiSchemas = [{', '.join(quote(s) for s in prim.api_schemas)}]\n")
    if prim.asset_name is not None:
        lines.append(f"{pad}assetInfo = {{\n{pad}{INDENT}string name = {quote(prim.asset_name)}\n{pad}}}\n")
    if prim.display_name is not None:
        lines.append(f"{pad}displayName = {quote(prim.display_name)}\n")
    if prim.instanceable is not None:
        lines.append(f"{pad}instanceable = {'true' if prim.instanceable else 'false'}\n")
    if prim.kind is not None:
        lines.append(f"{pad}kind = {quote(prim.kind)}\n")
    if prim.payloads:
        items = [f"@{p.asset_path}@" + (f"<{p.prim_path}>" if p.prim_path else "") for p in prim.payloads]
        lines.append(f"{pad}prepend payload = {_one_or_list(items)}\n")
    if prim.variant_selections:
        inner = "".join(
            f"{pad}{INDENT}string {name} = {quote(prim.variant_selections[name])}\n"
            for name in sorted(prim.variant_selections)
        )
        lines.append(f"{pad}variants = {{\n{inner}{pad}}}\n")
    return lines


def _relationship(rel: Relationship, pad: str) -> str:
    custom = "custom " if rel.custom else ""
    return f"{pad}{custom}rel {rel.name} = {_one_or_list([f'<{t}>' for t in rel.targets])}\n"


def _attribute(attr: Attribute, pad: str, texts: _Texts | None = None) -> str:
    prefix = ("custom " if attr.custom else "") + ("uniform " if attr.uniform else "")
    decl = f"{pad}{prefix}{attr.type_name} {attr.name}"
    lines = []
    if attr.value is not None or not attr.connections:
        text = f"{decl} = {_value_text(attr, texts)}" if attr.value is not None else decl
        if attr.interpolation is not None:
            text += f" (\n{pad}{INDENT}interpolation = {quote(attr.interpolation)}\n{pad})"
        lines.append(text + "\n")
    if attr.connections:
        lines.append(f"{decl}.connect = {_one_or_list([f'<{t}>' for t in attr.connections])}\n")
    return "".join(lines)


def _value_text(attr: Attribute, texts: _Texts | None) -> str:
    value = attr.value
    if texts is None or not (isinstance(value, array) or hasattr(value, "dtype")) or len(value) < _SHARED_MIN:
        return format_value(attr.type_name, value)
    key = id(value)
    known = texts.get(key)
    if known is None or known[0] is not value:
        known = (value, format_value(attr.type_name, value))
        texts[key] = known
    return known[1]


def _one_or_list(items: list[str]) -> str:
    """A list-op value as Sdf spells it: a single item bare, otherwise bracketed."""
    return items[0] if len(items) == 1 else "[" + ", ".join(items) + "]"


def format_value(type_name: str, value: Any) -> str:
    vtype, is_array = value_type(type_name)
    if not is_array:
        return _scalar(vtype, value)
    if hasattr(value, "dtype"):
        return "[" + ", ".join(_numpy_elements(vtype, value)) + "]"
    if isinstance(value, array):
        return "[" + ", ".join(_numpy_elements(vtype, _unpack(vtype, value))) + "]"
    return "[" + ", ".join(_scalar(vtype, item) for item in value) + "]"


def _unpack(vtype: ValueType, values: array[Any]) -> Any:
    """A flat ``array.array`` as the numpy array of its elements (text output of big arrays is
    numpy's vectorised formatting either way)."""
    import numpy as np

    flat = np.frombuffer(values, dtype=values.typecode)
    return flat if vtype.width == 1 else flat.reshape(-1, vtype.width)


def _scalar(vtype: ValueType, value: Any) -> str:
    if vtype.width > 1:
        return "(" + ", ".join(_single(vtype.scalar, v) for v in value) + ")"
    return _single(vtype.scalar, value)


def _single(scalar: str, value: Any) -> str:
    if scalar == "float":
        return format_float(float(value))
    if scalar == "double":
        return format_double(float(value))
    if scalar in ("int", "uint"):
        return str(int(value))
    if scalar == "bool":
        return "1" if value else "0"
    if scalar == "asset":
        return f"@{AssetPath(value)}@"
    return quote(str(value))


def _numpy_elements(vtype: ValueType, value: Any) -> list[str]:
    """Bulk formatting of a numpy array: one text per element (a number or a parenthesised tuple)."""
    flat = value.reshape(-1)
    if vtype.scalar == "int":
        texts = [str(v) for v in flat.tolist()]
    elif vtype.scalar == "float":
        texts = format_float_array(flat)
    elif vtype.scalar == "double":
        texts = [format_double(v) for v in flat.tolist()]
    else:
        return [_scalar(vtype, v) for v in value.tolist()]
    width = vtype.width
    if width == 1:
        return texts
    tuple_format = "(" + ", ".join(["%s"] * width) + ")\0"
    return ((tuple_format * (len(texts) // width)) % tuple(texts)).split("\0")[:-1]


def format_double(x: float) -> str:
    if x != x:
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return _usd_notation(repr(x))


# Texts of the floats formatted so far: a robot repeats few values (0 and 1 are most of them; a
# hundred robots' layers hold 127,000 floats and 9,000 distinct ones). Bounded; zero is kept out of
# it, since 0.0 and -0.0 are one key and two texts.
_FLOAT_TEXTS: dict[float, str] = {}
_FLOAT_TEXTS_MAX = 1 << 16


def format_float(x: float) -> str:
    """The shortest text that reads back as the float32 nearest ``x``."""
    if x == 0:
        return "-0" if math.copysign(1.0, x) < 0 else "0"
    text = _FLOAT_TEXTS.get(x)  # NaN is never equal to a key: it is formatted below
    if text is None:
        text = _format_float(x)
        if len(_FLOAT_TEXTS) < _FLOAT_TEXTS_MAX:
            _FLOAT_TEXTS[x] = text
    return text


def _format_float(x: float) -> str:
    if x != x:
        return "nan"
    try:
        f = _F32.unpack(_F32.pack(x))[0]
    except OverflowError:  # beyond float32's range: the cast gives infinity
        f = math.copysign(math.inf, x)
    if math.isinf(f):
        return "inf" if f > 0 else "-inf"
    return _usd_notation(_shortest_f32(f))


def _shortest_f32(f: float) -> str:
    # Correctly rounded to p + 1 significant digits, p growing until it reads back; 9 digits always
    # do. Six digits never lose a shorter form except for subnormals, whose precision is lower.
    for p in range(0, 9) if abs(f) < _F32_NORMAL else (5, 6, 7, 8):
        text = f"{f:.{p}e}"
        if _F32.unpack(_F32.pack(float(text)))[0] == f:
            return text
    return f"{f:.8e}"


def format_float_array(flat: Any) -> list[str]:
    """:func:`format_float` over a numpy array, vectorised.

    numpy estimates each element's shortest digit count (6 to 9) by rounding in float64; every
    element is then printed once with ``%.Ng`` and parsed back, and the few whose text does not
    read back as the same float32 (an estimate spoiled by float64 rounding) get more digits. ``%g``
    prints the fixed notation usd-core uses for most values; exponent forms are re-spelled."""
    import numpy as np

    values = np.asarray(flat, dtype=np.float32).reshape(-1)
    wide = values.astype(np.float64)
    finite = np.isfinite(wide) & (wide != 0)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        exponent = np.where(finite, np.floor(np.log10(np.abs(np.where(finite, wide, 1.0)))), 0.0)
        digits = np.full(len(values), 9, dtype=np.int64)
        for n in (8, 7, 6):
            scale = 10.0 ** (n - 1 - exponent)
            rounded = (np.round(wide * scale) / scale).astype(np.float32)
            digits[(rounded == values) & finite] = n
    digits[~finite] = 6
    as_double = wide.tolist()
    out = [""] * len(as_double)
    for n in (6, 7, 8, 9):
        where = np.nonzero(digits == n)[0].tolist()
        if where:
            texts = ((f"%.{n}g\0" * len(where)) % tuple([as_double[i] for i in where])).split("\0")
            for i, text in zip(where, texts, strict=False):
                out[i] = text
    with np.errstate(over="ignore"):
        back = np.array(out, dtype=np.float64).astype(np.float32)
    # The scalar path for what one %g pass cannot give: a text that reads back wrong, subnormals
    # (whose shortest form may have fewer than 6 digits), and exponent, nan or inf spellings.
    redo = ((back != values) & ~np.isnan(values)) | ((np.abs(values) < _F32_NORMAL) & (values != 0))
    for i, (text, again) in enumerate(zip(out, redo.tolist(), strict=True)):
        if again or "e" in text or "n" in text:
            out[i] = format_float(as_double[i])
    return out


def _usd_notation(text: str) -> str:
    """Re-spell a shortest-digits number (``repr`` or ``%e`` form) the way usd-core does."""
    sign = ""
    if text[0] == "-":
        sign, text = "-", text[1:]
    exp = 0
    if "e" in text:
        text, e = text.split("e")
        exp = int(e)
    whole, _, frac = text.partition(".")
    digits = whole + frac
    point = len(whole) + exp  # value = 0.<digits> * 10**point
    stripped = digits.lstrip("0")
    point -= len(digits) - len(stripped)
    digits = stripped.rstrip("0")
    if not digits:
        return sign + "0"
    sci = point - 1
    if -6 <= sci < 15:
        if point <= 0:
            return f"{sign}0.{'0' * -point}{digits}"
        if point >= len(digits):
            return sign + digits + "0" * (point - len(digits))
        return f"{sign}{digits[:point]}.{digits[point:]}"
    mantissa = digits[0] + ("." + digits[1:] if len(digits) > 1 else "")
    return f"{sign}{mantissa}e{sci}"


_ESCAPES = {"\\": "\\\\", "\t": "\\t", "\r": "\\r", "\b": "\\b", "\f": "\\f", "\v": "\\v", "\a": "\\a"}


# Text that needs no escaping and no other quotes: the common case, quoted without a loop.
_PLAIN_TEXT = re.compile(r'[^"\\\x00-\x1f\x7f]*\Z')


def quote(text: str, allow_single: bool = True) -> str:
    """A string literal as Sdf writes it: single quotes when that avoids escaping a double quote,
    triple quotes around text with line breaks."""
    if _PLAIN_TEXT.match(text):
        return '"' + text + '"'
    q = "'" if allow_single and '"' in text and "'" not in text else '"'
    multiline = "\n" in text
    parts: list[str] = []
    for ch in text:
        if ch == q:
            parts.append("\\" + ch)
        elif ch == "\n":
            parts.append("\n" if multiline else "\\n")
        elif ch in _ESCAPES:
            parts.append(_ESCAPES[ch])
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            parts.append(f"\\x{ord(ch):02x}")
        else:
            parts.append(ch)
    body = "".join(parts)
    fence = q * 3 if multiline else q
    return fence + body + fence
