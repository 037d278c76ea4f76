"""A mesh's arrays as a binary glTF (GLB) file: positions and triangle indices, nothing else.

The viewer shades meshes flat (per-face normals from screen-space derivatives), so normals are not
stored: they would add half again to the page for no visible difference on CAD meshes. Points are
float32 and indices uint32, as robodesc's mesh readers give them (:class:`MeshData`), copied
without numpy.
"""

from __future__ import annotations

import json
import struct
import sys
from array import array

from robodesc.meshes.buffers import MeshData

_GLB_MAGIC = 0x46546C67  # "glTF"
_JSON_CHUNK = 0x4E4F534A  # "JSON"
_BIN_CHUNK = 0x004E4942  # "BIN\0"
_FLOAT = 5126
_UNSIGNED_INT = 5125
_ARRAY_BUFFER = 34962
_ELEMENT_ARRAY_BUFFER = 34963


def _little_endian(values: array[float] | array[int]) -> bytes:
    if sys.byteorder == "little":
        return values.tobytes()
    swapped = array(values.typecode, values)
    swapped.byteswap()
    return swapped.tobytes()


def _pad(data: bytes, fill: bytes) -> bytes:
    return data + fill * (-len(data) % 4)


def mesh_glb(mesh: MeshData) -> bytes:
    """One GLB holding one mesh primitive (triangles) of ``mesh``'s points and faces."""
    points = _little_endian(mesh.points)
    # int32 indices are never negative, so their bytes are the uint32 glTF wants.
    indices = _little_endian(mesh.face_vertex_indices)
    count = len(mesh.points) // 3
    (lo, hi) = mesh.extent
    document = {
        "asset": {"version": "2.0", "generator": "robodesc view"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
        "buffers": [{"byteLength": len(points) + len(indices)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(points), "target": _ARRAY_BUFFER},
            {"buffer": 0, "byteOffset": len(points), "byteLength": len(indices), "target": _ELEMENT_ARRAY_BUFFER},
        ],
        "accessors": [
            # glTF requires min/max on POSITION; the readers' extent is exactly that.
            {
                "bufferView": 0,
                "componentType": _FLOAT,
                "count": count,
                "type": "VEC3",
                "min": list(lo),
                "max": list(hi),
            },
            {"bufferView": 1, "componentType": _UNSIGNED_INT, "count": len(mesh.face_vertex_indices), "type": "SCALAR"},
        ],
    }
    head = _pad(json.dumps(document, separators=(",", ":")).encode(), b" ")
    body = _pad(points + indices, b"\0")
    total = 12 + 8 + len(head) + 8 + len(body)
    return b"".join(
        (
            struct.pack("<III", _GLB_MAGIC, 2, total),
            struct.pack("<II", len(head), _JSON_CHUNK),
            head,
            struct.pack("<II", len(body), _BIN_CHUNK),
            body,
        )
    )
