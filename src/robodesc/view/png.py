"""PNG files from RGB arrays with zlib alone, and back (for the tests' golden comparisons).

A dozen lines instead of a dependency on Pillow: robodesc only ever writes 8-bit RGB.
"""

from __future__ import annotations

import struct
import zlib

import numpy as np
from numpy.typing import NDArray

from robodesc._files import write_atomic

Image = NDArray[np.uint8]  # height x width x 3


def _chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)


def encode_png(image: Image) -> bytes:
    height, width, channels = image.shape
    assert channels == 3
    # Each row starts with filter type 0 (none); zlib does the rest well enough for renders.
    rows = np.zeros((height, width * 3 + 1), dtype=np.uint8)
    rows[:, 1:] = image.reshape(height, width * 3)
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"".join(
        (
            b"\x89PNG\r\n\x1a\n",
            _chunk(b"IHDR", header),
            _chunk(b"IDAT", zlib.compress(rows.tobytes(), 6)),
            _chunk(b"IEND", b""),
        )
    )


def write_png(path: str, image: Image) -> None:
    write_atomic(path, encode_png(np.ascontiguousarray(image, dtype=np.uint8)))


def decode_png(data: bytes) -> Image:
    """The RGB array of a PNG this module wrote (8-bit RGB, every row unfiltered)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind, body = data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, color = struct.unpack(">IIBB", body[:10])
            if (depth, color) != (8, 2):
                raise ValueError("only 8-bit RGB PNGs")
        elif kind == b"IDAT":
            idat += body
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(height, width * 3 + 1)
    if raw[:, 0].any():
        raise ValueError("filtered rows: not a PNG robodesc wrote")
    return raw[:, 1:].reshape(height, width, 3).copy()
