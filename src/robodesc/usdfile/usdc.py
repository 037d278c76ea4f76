"""The binary ``.usdc`` ("crate") serialisation of a :class:`~robodesc.usdfile.spec.Layer`.

Python, following Sdf's ``crateFile.cpp``: no usd-core, and numpy only when a value already is a
numpy array, whose bytes then go to the file at memcpy speed (or, installed without a C compiler,
to code a long int array, which the C extension ``_intcode`` does otherwise). This module maps the
layer model onto crate specs, fields and values; :mod:`robodesc.usdfile.usdc_encoding` lays out
the file.

Crate version 0.8.0: the payload list op needs it, and nothing newer is needed. It is still the
version usd-core writes new files in (``USD_WRITE_NEW_USDC_FILES_AS_VERSION`` defaults to it in
26.x), and USD reads it since 20.11, so Isaac Sim's USD 24.x/25.x does. The 0.4.0 to 0.7.0 steps
it includes are compressed structural sections, arrays without a rank, and 64-bit array sizes.

The subset written is what the layer model holds: the pseudo-root (defaultPrim, metersPerUnit,
kilogramsPerUnit, upAxis, subLayers with their identity offsets); prims (specifier, typeName,
apiSchemas as a prepended list op, kind, assetInfo name, displayName, prepended payloads,
property and child order); attributes (typeName, custom, uniform, a default of every
:data:`~robodesc.usdfile.spec.VALUE_TYPES` type as scalar or array, interpolation, explicit
connections); relationships (explicit targets, custom). Int arrays of 16 or more elements are
compressed as Sdf compresses them (mesh indices: a third of a geometry layer's bytes saved); float
arrays are not (Sdf's float compression only applies to integral values or a few distinct ones).
Not written: time samples, references, variants. Scalars are inlined into their ValueRep
exactly where Sdf inlines them (numbers, names, doubles a float holds exactly, vectors of small
integers), so the file reads back the way one written by usd-core does.
"""

from __future__ import annotations

import math
import struct
import sys
import weakref
from array import array
from functools import partial
from itertools import chain
from typing import Any, NamedTuple

from robodesc.usdfile.spec import Attribute, Layer, Prim, Relationship, ValueType, value_type
from robodesc.usdfile.usdc_encoding import U64, Crate, Misfit, compressed_int32_bytes, short, uint32s

# ValueRep: 1 array bit, 1 inlined bit, 1 compressed bit, (5 unused), 8-bit type, 48-bit payload.
_ARRAY = 1 << 63
_INLINED = 1 << 62
_COMPRESSED = 1 << 61
# Sdf compresses int arrays of at least this many elements (crateFile.cpp, MinCompressedArraySize).
_MIN_COMPRESSED = 16

# Type enum values from Sdf's crateDataTypes.h: part of the file format.
_BOOL, _INT, _UINT, _FLOAT, _DOUBLE, _STRING, _TOKEN, _ASSET = 1, 3, 4, 8, 9, 10, 11, 12
_QUATD, _QUATF = 16, 17
_DICTIONARY, _TOKEN_LIST_OP, _PATH_LIST_OP, _TOKEN_VECTOR = 31, 32, 34, 41
_SPECIFIER, _VARIABILITY, _LAYER_OFFSET_VECTOR, _STRING_VECTOR, _PAYLOAD_LIST_OP = 42, 44, 49, 50, 55
_VECTORS = {
    ("double", 2): 19,
    ("float", 2): 20,
    ("int", 2): 22,
    ("double", 3): 23,
    ("float", 3): 24,
    ("int", 3): 26,
    ("double", 4): 27,
    ("float", 4): 28,
    ("int", 4): 30,
}
_SCALARS = {"bool": _BOOL, "int": _INT, "uint": _UINT, "float": _FLOAT, "double": _DOUBLE}
_TEXT = {"string": _STRING, "token": _TOKEN, "asset": _ASSET}

# SdfSpecType, SdfSpecifier, SdfVariability enum values.
_ATTRIBUTE_SPEC, _PRIM_SPEC, _PSEUDO_ROOT_SPEC, _RELATIONSHIP_SPEC = 1, 6, 7, 8
_SPECIFIERS = {"def": 0, "over": 1, "class": 2}
_UNIFORM = 1

# List op header bits.
_EXPLICIT, _HAS_EXPLICIT, _HAS_PREPENDED = 1, 2, 32

_U32 = struct.Struct("<I")
_F32 = struct.Struct("<f")
_IDENTITY_OFFSET = struct.pack("<dd", 0.0, 1.0)  # SdfLayerOffset (offset, scale)
_BIG_ENDIAN = sys.byteorder == "big"


def usdc_bytes(layer: Layer) -> bytes:
    """The layer as a crate file; ValueError (naming the spec) for a value that does not fit its type."""
    return b"".join(usdc_chunks(layer))


def usdc_chunks(layer: Layer) -> list[bytes | memoryview]:
    """:func:`usdc_bytes` as pieces to write one after another: float arrays (mesh points and
    normals, most of a geometry layer) are views of the layer's own arrays, not copies. The layer's
    arrays must stay unchanged until the pieces are written."""
    crate = Crate()
    if layer.root.properties:
        raise ValueError("the pseudo-root of a layer cannot hold properties")
    crate.spec("/", _PSEUDO_ROOT_SPEC, _layer_fields(crate, layer))
    stack = [(f"/{prim.name}", prim) for prim in reversed(layer.root.children.values())]
    while stack:  # pre-order without recursion: kinematic trees can nest deeply
        path, prim = stack.pop()
        _write_prim(crate, path, prim)
        stack.extend((f"{path}/{child.name}", child) for child in reversed(prim.children.values()))
    return crate.finish()


class _Numeric(NamedTuple):
    enum: int
    code: str  # array / struct code of one component: ? i f d
    width: int
    quat: bool


# ---------------------------------------------------------------------------------------------
# Specs and their fields


def _layer_fields(crate: Crate, layer: Layer) -> list[tuple[str, int]]:
    try:
        fields: list[tuple[str, int]] = []
        if layer.default_prim is not None:
            fields.append(("defaultPrim", _token_rep(crate, layer.default_prim)))
        if layer.meters_per_unit is not None:
            fields.append(("metersPerUnit", _double_rep(crate, layer.meters_per_unit)))
        if layer.kilograms_per_unit is not None:
            fields.append(("kilogramsPerUnit", _double_rep(crate, layer.kilograms_per_unit)))
        if layer.up_axis is not None:
            fields.append(("upAxis", _token_rep(crate, layer.up_axis)))
        if layer.sublayers:
            fields.append(
                ("subLayers", _index_vector(crate, _STRING_VECTOR, [crate.string(s) for s in layer.sublayers]))
            )
            # Sdf keeps one offset per sublayer; usd-core writes the identity ones too.
            offsets = U64.pack(len(layer.sublayers)) + _IDENTITY_OFFSET * len(layer.sublayers)
            fields.append(("subLayerOffsets", _rep(_LAYER_OFFSET_VECTOR, crate.blob(offsets))))
        if layer.root.children:
            fields.append(("primChildren", _name_vector(crate, layer.root)))
    except Misfit as e:
        raise ValueError(f"layer metadata: {e}") from None
    return fields


def _write_prim(crate: Crate, path: str, prim: Prim) -> None:
    try:
        # A name with "/" or "." would still parse as a path, just not as this prim's.
        if not prim.name.isidentifier():
            raise Misfit(f"{prim.name!r} is not a valid prim name")
        crate.spec(path, _PRIM_SPEC, _prim_fields(crate, prim))
    except Misfit as e:
        raise ValueError(f"{path}: {e}") from None
    for prop in prim.properties.values():
        prop_path = f"{path}.{prop.name}"
        try:
            if isinstance(prop, Relationship):
                crate.spec(prop_path, _RELATIONSHIP_SPEC, _relationship_fields(crate, prop))
            else:
                crate.spec(prop_path, _ATTRIBUTE_SPEC, _attribute_fields(crate, prop))
        except Misfit as e:
            kind = "rel" if isinstance(prop, Relationship) else prop.type_name
            raise ValueError(f"{prop_path} ({kind}): {e}") from None


def _prim_fields(crate: Crate, prim: Prim) -> list[tuple[str, int]]:
    specifier = _SPECIFIERS.get(prim.specifier)
    if specifier is None:
        raise Misfit(f"unknown specifier {prim.specifier!r}")
    fields = [("specifier", _rep(_SPECIFIER, specifier, _INLINED))]
    if prim.type_name:
        fields.append(("typeName", _token_rep(crate, prim.type_name)))
    if prim.deleted_api_schemas:
        # Not needed in a crate file yet (only the Isaac physics layer deletes, and it is .usda).
        raise ValueError(f"{prim.name}: deleted apiSchemas are written to .usda only")
    if prim.variant_selections:
        # Likewise: only the composed stage's root layer selects a variant, and it is .usda.
        raise ValueError(f"{prim.name}: variant selections are written to .usda only")
    if prim.instanceable is not None:
        raise ValueError(f"{prim.name}: instanceable is written to .usda only")
    if prim.api_schemas:
        items = [crate.token(s) for s in prim.api_schemas]
        fields.append(("apiSchemas", _list_op(crate, _TOKEN_LIST_OP, _HAS_PREPENDED, items)))
    if prim.kind is not None:
        fields.append(("kind", _token_rep(crate, prim.kind)))
    if prim.asset_name is not None:
        fields.append(("assetInfo", _name_dictionary(crate, prim.asset_name)))
    if prim.display_name is not None:
        fields.append(("displayName", _rep(_STRING, crate.string(prim.display_name), _INLINED)))
    if prim.payloads:
        fields.append(("payload", _payload_list_op(crate, prim)))
    if prim.properties:
        names = [crate.token(p.name) for p in prim.properties.values()]
        fields.append(("properties", _index_vector(crate, _TOKEN_VECTOR, names)))
    if prim.children:
        fields.append(("primChildren", _name_vector(crate, prim)))
    return fields


def _attribute_fields(crate: Crate, attr: Attribute) -> list[tuple[str, int]]:
    try:
        vtype, is_array = value_type(attr.type_name)
    except KeyError:
        raise Misfit(f"unknown type name {attr.type_name!r}") from None
    fields = [("typeName", _token_rep(crate, attr.type_name))]
    if attr.custom:
        fields.append(("custom", _rep(_BOOL, 1, _INLINED)))
    if attr.uniform:  # varying is the fallback, so Sdf writes variability only when uniform
        fields.append(("variability", _rep(_VARIABILITY, _UNIFORM, _INLINED)))
    if attr.value is not None:
        rep = (
            _shared_array_rep(crate, attr.type_name, vtype, attr.value)
            if is_array
            else _scalar_rep(crate, vtype, attr.value)
        )
        fields.append(("default", rep))
    if attr.interpolation is not None:
        fields.append(("interpolation", _token_rep(crate, attr.interpolation)))
    if attr.connections:
        items = [crate.paths.add(p) for p in attr.connections]
        fields.append(("connectionPaths", _list_op(crate, _PATH_LIST_OP, _EXPLICIT | _HAS_EXPLICIT, items)))
    return fields


def _relationship_fields(crate: Crate, rel: Relationship) -> list[tuple[str, int]]:
    fields = []
    if rel.custom:
        fields.append(("custom", _rep(_BOOL, 1, _INLINED)))
    # Relationships are always uniform; Sdf authors it on every relationship spec.
    fields.append(("variability", _rep(_VARIABILITY, _UNIFORM, _INLINED)))
    # An empty list stays an explicit (empty) opinion, as `rel x = []` is in the usda form.
    items = [crate.paths.add(p) for p in rel.targets]
    bits = _EXPLICIT | (_HAS_EXPLICIT if items else 0)
    fields.append(("targetPaths", _list_op(crate, _PATH_LIST_OP, bits, items)))
    return fields


def _token_rep(crate: Crate, text: str) -> int:
    return _rep(_TOKEN, crate.token(text), _INLINED)


def _index_vector(crate: Crate, type_enum: int, indexes: list[int]) -> int:
    """A std::vector of tokens or strings: count, then uint32 indexes."""
    return _rep(type_enum, crate.blob(U64.pack(len(indexes)) + uint32s(indexes)))


def _list_op(crate: Crate, type_enum: int, header: int, items: list[int]) -> int:
    """An SdfListOp with at most one item list (explicit or prepended) of uint32 indexes."""
    blob = bytes((header,))
    if items:
        blob += U64.pack(len(items)) + uint32s(items)
    return _rep(type_enum, crate.blob(blob))


def _name_vector(crate: Crate, prim: Prim) -> int:
    return _index_vector(crate, _TOKEN_VECTOR, [crate.token(c.name) for c in prim.children.values()])


def _name_dictionary(crate: Crate, name: str) -> int:
    # VtDictionary {"name": name}: count, then per entry the key's string index and a VtValue,
    # which is a forward offset (8: the rep follows, nothing nested) and the value's ValueRep.
    value_rep = _rep(_STRING, crate.string(name), _INLINED)
    blob = U64.pack(1) + _U32.pack(crate.string("name")) + struct.pack("<qQ", 8, value_rep)
    return _rep(_DICTIONARY, crate.blob(blob))


def _payload_list_op(crate: Crate, prim: Prim) -> int:
    parts = [bytes((_HAS_PREPENDED,)), U64.pack(len(prim.payloads))]
    for payload in prim.payloads:
        # An empty prim path is the empty SdfPath: "the target layer's defaultPrim".
        prim_path = crate.paths.add(payload.prim_path)
        parts.append(struct.pack("<II", crate.string(payload.asset_path), prim_path) + _IDENTITY_OFFSET)
    return _rep(_PAYLOAD_LIST_OP, crate.blob(b"".join(parts)))


# ---------------------------------------------------------------------------------------------
# Values


def _rep(type_enum: int, payload: int, flags: int = 0) -> int:
    return flags | (type_enum << 48) | payload


def _numeric(vtype: ValueType) -> _Numeric:
    code = {"bool": "?", "int": "i", "uint": "I", "float": "f", "double": "d"}.get(vtype.scalar)
    if code is None:
        raise Misfit(f"no crate encoding for {vtype.scalar} values")
    if vtype.role == "Quat":
        return _Numeric(_QUATF if code == "f" else _QUATD, code, 4, True)
    if vtype.width == 1:
        return _Numeric(_SCALARS[vtype.scalar], code, 1, False)
    return _Numeric(_VECTORS[vtype.scalar, vtype.width], code, vtype.width, False)


def _pack(fmt: str, *values: Any) -> bytes:
    try:
        return struct.pack(fmt, *values)
    except (struct.error, OverflowError, TypeError) as e:
        raise Misfit(f"{short(values)}: {e}") from None


def _scalar_rep(crate: Crate, vtype: ValueType, value: Any) -> int:
    if vtype.scalar in _TEXT:
        text = _text(value)
        index = crate.string(text) if vtype.scalar == "string" else crate.token(text)
        return _rep(_TEXT[vtype.scalar], index, _INLINED)
    num = _numeric(vtype)
    if num.width > 1:
        return _vector_rep(crate, num, value)
    if num.code == "?":
        if not _is_bool(value):
            raise Misfit(f"{short(value)} is not a bool")
        return _rep(_BOOL, int(bool(value)), _INLINED)
    if num.code == "d":
        return _double_rep(crate, value)
    bits = int.from_bytes(_pack("<" + num.code, value), "little")
    return _rep(num.enum, bits, _INLINED)


def _double_rep(crate: Crate, value: Any) -> int:
    packed = _pack("<d", value)
    try:
        single = _F32.pack(value)
    except OverflowError:
        single = b""
    # Sdf inlines a double that a float holds exactly (NaN never compares equal: stays out of line).
    if single and _F32.unpack(single)[0] == struct.unpack("<d", packed)[0]:
        return _rep(_DOUBLE, int.from_bytes(single, "little"), _INLINED)
    return _rep(_DOUBLE, crate.blob(packed))


def _vector_rep(crate: Crate, num: _Numeric, value: Any) -> int:
    comps = _components(num, value)
    packed = _pack(f"<{num.width}{num.code}", *comps)
    if not num.quat:  # Sdf never inlines quaternions (its reader would not decode them)
        small = _small_ints(comps)
        if small is not None:
            return _rep(num.enum, small, _INLINED)
    return _rep(num.enum, crate.blob(packed))


def _components(num: _Numeric, value: Any) -> tuple[Any, ...]:
    if isinstance(value, str | bytes) or not hasattr(value, "__len__"):
        raise Misfit(f"{short(value)} is not a {num.width}-tuple")
    comps = tuple(value)
    if len(comps) != num.width:
        raise Misfit(f"{short(value)} has {len(comps)} components, expected {num.width}")
    if num.quat:  # (w, x, y, z) in the model; GfQuat stores the imaginary part first
        comps = (comps[1], comps[2], comps[3], comps[0])
    return comps


def _small_ints(comps: tuple[Any, ...]) -> int | None:
    """The inline payload Sdf uses for a vector of integers in [-128, 127] (one int8 each)."""
    ints = []
    for c in comps:
        if not -128 <= c <= 127 or c != int(c) or (c == 0 and math.copysign(1.0, c) < 0):
            return None  # NaN fails the range test; -0.0 would read back as +0.0
        ints.append(int(c))
    return int.from_bytes(struct.pack(f"<{len(ints)}b", *ints).ljust(4, b"\0"), "little")


def _is_bool(value: Any) -> bool:
    return isinstance(value, bool) or getattr(getattr(value, "dtype", None), "kind", "") == "b"


def _text(value: Any) -> str:
    if not isinstance(value, str):
        raise Misfit(f"{short(value)} is not a string")
    return value


class _Packed(NamedTuple):
    """An array value's bytes in the file and the ValueRep bits that go with them."""

    enum: int
    head: bytes
    body: bytes | memoryview
    align: bool
    flags: int


# Arrays whose owner never modifies them (meshes a batch worker shares between robots): their packed
# bytes by type name, kept while the array lives, so that every later layer reuses them.
_kept: dict[int, tuple[weakref.ref[Any], dict[str, _Packed | int]]] = {}


def keep_packed(*values: array[Any]) -> None:
    """Promise that these arrays are never modified: their packed bytes are kept for later layers
    (without the promise a changed array would be written as it was)."""
    for value in values:
        key = id(value)
        entry = _kept.get(key)
        if entry is None or entry[0]() is not value:
            _kept[key] = (weakref.ref(value, partial(_forget, _kept, key)), {})


def _forget(
    kept: dict[int, tuple[weakref.ref[Any], dict[str, _Packed | int]]], key: int, ref: weakref.ref[Any]
) -> None:
    # ``kept`` is bound when the callback is made: at interpreter exit the module's names are gone.
    entry = kept.get(key)
    if entry is not None and entry[0] is ref:  # not a newer array that took the same id
        del kept[key]


def _shared_array_rep(crate: Crate, type_name: str, vtype: ValueType, value: Any) -> int:
    if not isinstance(value, array):  # lists and tuples are built per attribute: nothing to share
        return _array_rep(crate, vtype, value)
    key = (id(value), type_name)
    found = crate.arrays.get(key)
    if found is None:
        kept = _kept.get(id(value))
        if kept is not None and kept[0]() is value and vtype.scalar not in _TEXT:
            packed = kept[1].get(type_name)
            if packed is None:
                packed = kept[1][type_name] = _pack_array(crate, vtype, value)
            rep = packed if isinstance(packed, int) else _place(crate, packed)
        else:
            rep = _array_rep(crate, vtype, value)
        found = crate.arrays[key] = (value, rep)
    return found[1]


def _array_rep(crate: Crate, vtype: ValueType, value: Any) -> int:
    packed = _pack_array(crate, vtype, value)
    return packed if isinstance(packed, int) else _place(crate, packed)


def _place(crate: Crate, packed: _Packed) -> int:
    return _rep(packed.enum, crate.blob(packed.head, packed.body, align=packed.align), packed.flags)


def _pack_array(crate: Crate, vtype: ValueType, value: Any) -> _Packed | int:
    """The array's bytes, or the ValueRep itself for an empty array (nothing is written for it)."""
    enum = _TEXT[vtype.scalar] if vtype.scalar in _TEXT else _numeric(vtype).enum
    if isinstance(value, str | bytes):
        raise Misfit(f"{short(value)} is not an array")
    try:
        count = len(value)
    except TypeError:
        raise Misfit(f"{short(value)} is not an array") from None
    if isinstance(value, array):
        count //= vtype.width  # flat: the elements' scalars one after another
    if count == 0:
        return _rep(enum, 0, _ARRAY)  # the empty array is payload 0, nothing written
    body: bytes | memoryview
    if vtype.scalar in _TEXT:
        body = _text_array_bytes(crate, vtype.scalar, value)
    else:
        body = _numeric_array_bytes(_numeric(vtype), value)
    if enum == _INT and count >= _MIN_COMPRESSED:
        # As Sdf writes int arrays (mesh indices): the count, then the integer coding, in a third
        # to a sixteenth of the bytes; unaligned, since readers decode them rather than map them.
        return _Packed(enum, U64.pack(count), compressed_int32_bytes(body), False, _ARRAY | _COMPRESSED)
    # Aligned so that readers can map the elements in place (Sdf's zero-copy arrays).
    return _Packed(enum, U64.pack(count), body, True, _ARRAY)


def _text_array_bytes(crate: Crate, scalar: str, value: Any) -> bytes:
    items = value.tolist() if hasattr(value, "tolist") else value
    # Array elements are string indexes, asset paths included (only a scalar asset is a token).
    if scalar == "token":
        indexes = array("I", [crate.token(_text(t)) for t in items])
    else:
        indexes = array("I", [crate.string(_text(t)) for t in items])
    return _native_to_little(indexes)


def _numeric_array_bytes(num: _Numeric, value: Any) -> bytes | memoryview:
    if isinstance(value, array):
        return _packed_bytes(num, value)
    if hasattr(value, "dtype") and hasattr(value, "tobytes") and value.dtype.kind != "O":
        return _numpy_bytes(num, value)
    flat = _flatten(num, value.tolist() if hasattr(value, "tolist") else value)
    if num.code == "?":
        if not all(_is_bool(x) for x in flat):
            raise Misfit("bool[] elements must be bools")
        return bytes(map(bool, flat))
    try:
        packed = array(num.code, flat)
    except (TypeError, OverflowError) as e:
        raise Misfit(f"{short(value)}: {e}") from None
    # array('f') turns a double beyond float32's range into inf where struct refuses it.
    overflow = num.code == "f" and (math.inf in packed or -math.inf in packed)
    if overflow and sum(map(math.isinf, packed)) != sum(map(math.isinf, flat)):
        raise Misfit("a value is beyond float32's range")
    return _native_to_little(packed)


def _flatten(num: _Numeric, items: Any) -> list[Any]:
    rows = list(items)
    if num.width == 1:
        return rows
    for i, row in enumerate(rows):
        if isinstance(row, str | bytes) or not hasattr(row, "__len__") or len(row) != num.width:
            raise Misfit(f"element {i} ({short(row)}) is not a {num.width}-tuple")
    if num.quat:
        return [c for row in rows for c in (row[1], row[2], row[3], row[0])]
    return list(chain.from_iterable(rows))


def _packed_bytes(num: _Numeric, values: array[Any]) -> bytes | memoryview:
    """A flat ``array.array`` of the element type's own C scalars: its memory is the payload, as a
    view (no copy; the array cannot be resized while the view exists)."""
    if values.typecode != num.code or num.quat:
        raise Misfit(f"array('{values.typecode}') for {num.code!r} elements, expected array('{num.code}')")
    if len(values) % num.width:
        raise Misfit(f"array of {len(values)} scalars is not a whole number of {num.width}-tuples")
    return _native_to_little(array(values.typecode, values)) if _BIG_ENDIAN else memoryview(values).cast("B")


def _numpy_bytes(num: _Numeric, arr: Any) -> bytes:
    import numpy as np  # the caller already did: a numpy array is in hand

    shape_ok = arr.ndim == 1 if num.width == 1 else arr.ndim == 2 and arr.shape[1] == num.width
    if not shape_ok:
        expected = "(n,)" if num.width == 1 else f"(n, {num.width})"
        raise Misfit(f"numpy array of shape {arr.shape}, expected {expected}")
    kind = arr.dtype.kind
    allowed = {"?": "b", "i": "iu", "I": "iu", "f": "fiu", "d": "fiu"}[num.code]
    if kind not in allowed:
        raise Misfit(f"numpy array of dtype {arr.dtype} for {num.code!r} elements")
    wide = num.code == "i" and arr.dtype.itemsize >= 4 and arr.size
    if wide and (int(arr.min()) < -(2**31) or int(arr.max()) >= 2**31):
        raise Misfit("a value is beyond int32's range")
    if num.code == "I" and arr.size and (int(arr.min()) < 0 or int(arr.max()) >= 2**32):
        raise Misfit("a value is beyond uint32's range")
    if num.quat:
        arr = arr[:, [1, 2, 3, 0]]
    dtype = {"?": "?", "i": "<i4", "I": "<u4", "f": "<f4", "d": "<f8"}[num.code]
    try:
        with np.errstate(over="raise"):
            out = np.ascontiguousarray(arr, dtype=dtype)
    except FloatingPointError:
        raise Misfit("a value is beyond float32's range") from None
    data: bytes = out.tobytes()
    return data


def _native_to_little(values: array[Any]) -> bytes:
    if _BIG_ENDIAN:  # crate files are little-endian
        values.byteswap()
    return values.tobytes()
