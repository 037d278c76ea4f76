"""The container of a crate file (``.usdc``): tables, value data, structural sections and their codecs.

:class:`Crate` collects what :mod:`robodesc.usdfile.usdc` decides a layer is made of (tokens,
strings, paths, value bytes, fields, specs) and lays out the file as Sdf's ``crateFile.cpp``
reads it::

    bootstrap   "PXR-USDC", version, offset of the table of contents (88 bytes)
    values      what a field's 8-byte ValueRep cannot hold inline (arrays 8-byte aligned)
    TOKENS      every distinct token: names, type names, token and string values
    STRINGS     the token index of each string value
    FIELDS      (name token, ValueRep) pairs
    FIELDSETS   each spec's field indexes, every run ended by ~0
    PATHS       the path tree in pre-order: path index, element token, jump to the next sibling
    SPECS       (path index, field set index, spec type) of each spec
    table of contents: name, start and size of each section

Two codecs, mandatory from crate version 0.4.0 on, wrap the sections:

- :func:`fast_compress`: USD's ``TfFastCompression`` framing (a chunk-count byte, 0 for one chunk,
  then an LZ4 block). The block written here holds one literal run and no matches: valid LZ4 that
  any decoder expands back verbatim, so no compressor is needed. The sections are tiny next to the
  arrays a layer carries.
- :func:`compressed_ints`: Sdf's integer coding (``integerCoding.cpp``) of a list of 32-bit
  integers, then :func:`fast_compress`. Each integer is stored as its difference to the previous
  one, classified by a 2-bit code: the most common difference (00), or an 8-, 16- or 32-bit
  signed difference (01, 10, 11).
"""

from __future__ import annotations

import struct
from collections import Counter
from collections.abc import Callable, Sequence
from typing import Any

try:
    from robodesc.usdfile import _intcode
except ImportError:  # installed without a C compiler: numpy codes the large arrays, Python the rest
    _intcode = None  # type: ignore[assignment]

VERSION = (0, 8, 0)
BOOTSTRAP_SIZE = 88  # ident[8], version[8], tocOffset, reserved[8]
# LZ4_MAX_INPUT_SIZE: one chunk holds up to this many bytes; more would need the multi-chunk framing.
_LZ4_MAX_INPUT = 0x7E000000
U64 = struct.Struct("<Q")


class Misfit(Exception):
    """A value that does not fit the file; the writer re-raises it as ValueError naming the spec."""


def short(value: Any) -> str:
    """``repr`` cut to a length an error message can carry."""
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def uint32s(values: Sequence[int]) -> bytes:
    return struct.pack(f"<{len(values)}I", *values)


class Crate:
    """Deduplicating tables and value data, serialised by :meth:`finish`."""

    def __init__(self) -> None:
        # Pieces of the file in order; an array's elements may be a memoryview of the caller's array,
        # which goes to the file without a copy. [0]: the bootstrap, written last.
        self._chunks: list[bytes | memoryview] = [b""]
        self._size = BOOTSTRAP_SIZE
        self._blobs: dict[tuple[bytes, bytes, bool], int] = {}
        self._tokens: dict[str, int] = {}
        self._token_bytes: list[bytes] = []
        self._strings: dict[str, int] = {}
        self._string_tokens: list[int] = []
        self._fields: dict[tuple[int, int], int] = {}
        self._field_sets: dict[tuple[int, ...], int] = {}
        self._field_set_data: list[int] = []
        self._specs: list[tuple[int, int, int]] = []
        # Token 0 must never name a property: the PATHS section marks those by negating the index.
        self.token(";-)")
        self.paths = PathTable(self.token)
        # ValueRep of an array object already written, by identity: a mesh shared by a visual and a
        # collider is one MeshData, whose arrays need packing once. The object is kept alive with
        # its rep, so its id is not reused while the crate exists.
        self.arrays: dict[tuple[int, str], tuple[object, int]] = {}

    def token(self, text: str) -> int:
        if not isinstance(text, str):
            raise Misfit(f"{short(text)} is not a string")
        found = self._tokens.get(text)
        if found is not None:
            return found
        try:
            encoded = text.encode("utf-8")
        except UnicodeEncodeError as e:
            raise Misfit(f"{short(text)}: {e}") from None
        if b"\0" in encoded:  # tokens are stored NUL-terminated
            raise Misfit(f"{short(text)} contains a NUL character")
        index = self._tokens[text] = len(self._token_bytes)
        self._token_bytes.append(encoded)
        return index

    def string(self, text: str) -> int:
        """Index of a string value (strings are stored as tokens, through one more table)."""
        found = self._strings.get(text)
        if found is not None:
            return found
        token = self.token(text)
        index = self._strings[text] = len(self._string_tokens)
        self._string_tokens.append(token)
        return index

    def blob(self, head: bytes, body: bytes | memoryview = b"", align: bool = False) -> int:
        """File offset of these value bytes (``head + body``), written once however many fields share
        them. A memoryview body (an array's own memory) is not compared with others: the writer
        already stores one array object once, and hashing it would cost the copy it avoids."""
        key = (head, body, align) if isinstance(body, bytes) else None
        found = self._blobs.get(key) if key is not None else None
        if found is not None:
            return found
        if align and self._size % 8:
            self._append(bytes(8 - self._size % 8))
        offset = self._size
        if key is not None:
            self._blobs[key] = offset
        self._append(head)
        self._append(body)
        return offset

    def spec(self, path: str, spec_type: int, fields: list[tuple[str, int]]) -> None:
        """A spec at ``path`` with these (field name, ValueRep) pairs."""
        indexes = []
        for name, rep in fields:
            key = (self.token(name), rep)
            indexes.append(self._fields.setdefault(key, len(self._fields)))
        field_set = self._field_sets.get(tuple(indexes))
        if field_set is None:
            field_set = self._field_sets[tuple(indexes)] = len(self._field_set_data)
            self._field_set_data += [*indexes, -1]  # ~0 ends each run
        self._specs.append((self.paths.add(path), field_set, spec_type))

    def finish(self) -> list[bytes | memoryview]:
        """The file as its pieces in order (``b"".join`` them, or write them one after another)."""
        toc = [U64.pack(6)]
        for name, section in self._sections():
            toc.append(name.encode().ljust(16, b"\0") + struct.pack("<qq", self._size, len(section)))
            self._append(section)
        toc_offset = self._size
        self._append(b"".join(toc))
        self._chunks[0] = b"PXR-USDC" + bytes(VERSION).ljust(8, b"\0") + struct.pack("<q", toc_offset) + bytes(64)
        return self._chunks

    def _append(self, data: bytes | memoryview) -> None:
        self._chunks.append(data)
        self._size += data.nbytes if isinstance(data, memoryview) else len(data)

    def _sections(self) -> list[tuple[str, bytes]]:
        token_data = b"".join(t + b"\0" for t in self._token_bytes)
        packed_tokens = fast_compress(token_data)
        tokens = struct.pack("<QQQ", len(self._token_bytes), len(token_data), len(packed_tokens)) + packed_tokens
        strings = U64.pack(len(self._string_tokens)) + uint32s(self._string_tokens)
        names = [token for token, _ in self._fields]
        reps = fast_compress(struct.pack(f"<{len(self._fields)}Q", *(rep for _, rep in self._fields)))
        fields = U64.pack(len(names)) + compressed_ints(names) + U64.pack(len(reps)) + reps
        field_sets = U64.pack(len(self._field_set_data)) + compressed_ints(self._field_set_data)
        specs = U64.pack(len(self._specs)) + b"".join(
            compressed_ints([spec[column] for spec in self._specs]) for column in range(3)
        )
        return [
            ("TOKENS", tokens),
            ("STRINGS", strings),
            ("FIELDS", fields),
            ("FIELDSETS", field_sets),
            ("PATHS", self.paths.section()),
            ("SPECS", specs),
        ]


class PathTable:
    """Every path a spec or a value names, parents before children, as a tree for the PATHS section."""

    def __init__(self, token: Callable[[str], int]) -> None:
        self._token = token
        self._index: dict[str, int] = {}
        self._elements: list[int] = []  # name token of each path, negated for a property name
        self._children: list[list[int]] = []
        self.add("/")

    def add(self, path: str) -> int:
        found = self._index.get(path)
        if found is not None:
            return found
        parent = None
        element = 0  # the root's (and the empty path's) element is never read
        if path not in ("/", ""):  # "" is the empty path: indexed, but outside the tree
            parent_path, name, is_property = split_path(path)
            parent = self.add(parent_path)
            element = -self._token(name) if is_property else self._token(name)
        index = self._index[path] = len(self._elements)
        self._elements.append(element)
        self._children.append([])
        if parent is not None:
            self._children[parent].append(index)
        return index

    def section(self) -> bytes:
        order: list[int] = []
        stack = [0]
        while stack:  # pre-order without recursion: prim trees can nest deeply
            node = stack.pop()
            order.append(node)
            stack.extend(reversed(self._children[node]))
        subtree = [1] * len(self._elements)
        for node in reversed(order):
            subtree[node] += sum(subtree[c] for c in self._children[node])
        has_sibling = {c for kids in self._children for c in kids[:-1]}
        jumps = []
        for node in order:
            # Pre-order puts a node's first child right after it, its next sibling after its subtree.
            if self._children[node]:
                jumps.append(subtree[node] if node in has_sibling else -1)
            else:
                jumps.append(0 if node in has_sibling else -2)
        return b"".join(
            (
                U64.pack(len(self._elements)),  # the empty path counts, but is not in the tree
                U64.pack(len(order)),
                compressed_ints(order),
                compressed_ints([self._elements[n] for n in order]),
                compressed_ints(jumps),
            )
        )


def split_path(path: str) -> tuple[str, str, bool]:
    """(parent path, last element, whether it is a property name) of an absolute prim or property path."""
    head, _, last = path.rpartition("/")
    prim_name, dot, prop = last.partition(".")
    valid = (
        path.startswith("/")
        and "." not in head
        and prim_name.isidentifier()
        and (not dot or all(part.isidentifier() for part in prop.split(":")))
    )
    if not valid:
        raise Misfit(f"{path!r} is not an absolute prim or property path")
    if dot:
        return path[: -len(prop) - 1], prop, True
    return head or "/", prim_name, False


def fast_compress(data: bytes) -> bytes:
    """``data`` in TfFastCompression framing, as one chunk with a literal-only LZ4 block."""
    size = len(data)
    if size > _LZ4_MAX_INPUT:
        raise ValueError(f"crate section of {size} bytes exceeds one LZ4 chunk")
    if size < 15:
        # The token's high nibble is the literal length; the low nibble (match length) is unused
        # because the last sequence of a block is literals only.
        header = bytes((0, size << 4))
    else:
        # Length 15 in the nibble means "more follows": bytes of 255 and a final byte below 255.
        rest = size - 15
        header = b"\x00\xf0" + b"\xff" * (rest // 255) + bytes((rest % 255,))
    return header + data


def _wrap32(value: int) -> int:
    """``value`` as the int32 with the same low 32 bits (the C++ coder does int32 arithmetic)."""
    return (value + 0x80000000) % 0x100000000 - 0x80000000


def encode_ints(values: Sequence[int]) -> bytes:
    """Sdf's integer coding of ``values`` (each taken modulo 2**32, as int32 or uint32 alike)."""
    if not values:
        return b""
    deltas: list[int] = []
    previous = 0
    for value in values:
        value = _wrap32(value)
        deltas.append(_wrap32(value - previous))
        previous = value
    # The most common difference costs no data bytes; ties go to the largest value, as in Sdf,
    # so that the output does not depend on hash order.
    counts = Counter(deltas)
    common = max(counts, key=lambda d: (counts[d], d))
    codes = bytearray((len(deltas) * 2 + 7) // 8)
    data = bytearray()
    for i, delta in enumerate(deltas):
        if delta == common:
            code = 0
        elif -0x80 <= delta < 0x80:
            code = 1
            data += struct.pack("<b", delta)
        elif -0x8000 <= delta < 0x8000:
            code = 2
            data += struct.pack("<h", delta)
        else:
            code = 3
            data += struct.pack("<i", delta)
        codes[i >> 2] |= code << (2 * (i & 3))
    return struct.pack("<i", common) + bytes(codes) + bytes(data)


def compressed_ints(values: Sequence[int]) -> bytes:
    """``uint64 size`` + compressed integer coding of ``values``: how the sections store every list."""
    return compressed_int32_bytes(uint32s([v & 0xFFFFFFFF for v in values]))


def compressed_int32_bytes(data: bytes | memoryview) -> bytes:
    """:func:`compressed_ints` of little-endian int32 ``data`` (an int array's bytes in the file)."""
    block = fast_compress(encode_int32_bytes(data))
    return U64.pack(len(block)) + block


# Below this many values the Python coder is as quick as loading numpy.
_PYTHON_CODER_LIMIT = 4096


def encode_int32_bytes(data: bytes | memoryview) -> bytes:
    """:func:`encode_ints` of little-endian int32 ``data``: through the C extension, else numpy for a
    long list; all three give the same bytes."""
    if _intcode is not None:
        coded: bytes = _intcode.encode(data)
        return coded
    count = len(data) // 4
    if count <= _PYTHON_CODER_LIMIT:
        return encode_ints(struct.unpack(f"<{count}i", data))
    return _encode_numpy(data)


def _encode_numpy(data: bytes | memoryview) -> bytes:
    import numpy as np

    values = np.frombuffer(data, dtype="<u4")
    deltas = np.diff(values, prepend=np.uint32(0)).astype("<u4").view("<i4")  # wrapping, as int32
    distinct, counts = np.unique(deltas, return_counts=True)
    common = int(distinct[counts == counts.max()].max())
    small = (deltas >= -0x80) & (deltas < 0x80)
    medium = (deltas >= -0x8000) & (deltas < 0x8000)
    codes = np.where(deltas == common, 0, np.where(small, 1, np.where(medium, 2, 3))).astype(np.uint8)
    padded = np.zeros(-(-len(codes) // 4) * 4, dtype=np.uint8)
    padded[: len(codes)] = codes
    quads = padded.reshape(-1, 4)
    packed = quads[:, 0] | quads[:, 1] << 2 | quads[:, 2] << 4 | quads[:, 3] << 6
    widths = np.array([0, 1, 2, 4], dtype=np.int64)[codes]
    starts = np.cumsum(widths) - widths
    out = np.zeros(int(widths.sum()), dtype=np.uint8)
    low_bytes = deltas.view(np.uint8).reshape(-1, 4)  # little-endian: byte k is bits 8k..8k+7
    for width in (1, 2, 4):
        chosen = widths == width
        for k in range(width):
            out[starts[chosen] + k] = low_bytes[chosen, k]
    return struct.pack("<i", common) + packed.astype(np.uint8).tobytes() + out.tobytes()
