"""Where the picture's camera stands: the robot's bounding box seen from a named direction.

The box is MuJoCo's own (each geom's axis-aligned box in its frame, turned into the world), so the
framing matches what is drawn. The distance fits the box's bounding sphere in the narrower of the
two fields of view, so nothing is cut off at any aspect ratio.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

# azimuth, elevation in degrees (MuJoCo's free camera: azimuth 0 looks along +x, elevation < 0
# looks down). URDF robots face +x: "front" stands in front of the robot looking back at it.
VIEWS: dict[str, tuple[float, float]] = {
    "front": (180.0, -8.0),
    "side": (90.0, -8.0),
    "top": (180.0, -89.0),
    "iso": (140.0, -28.0),
}


def bounds(model: Any, data: Any, groups: set[int]) -> tuple[np.ndarray, np.ndarray] | None:
    """World-space min and max corners of the geoms in ``groups`` (None when there are none)."""
    lo = np.full(3, np.inf)
    hi = np.full(3, -np.inf)
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
    for i in range(model.ngeom):
        if int(model.geom_group[i]) not in groups:
            continue
        center, half = model.geom_aabb[i, :3], model.geom_aabb[i, 3:]
        rot = data.geom_xmat[i].reshape(3, 3)
        corners = data.geom_xpos[i] + (center + signs * half) @ rot.T
        lo = np.minimum(lo, corners.min(axis=0))
        hi = np.maximum(hi, corners.max(axis=0))
    if not np.all(np.isfinite(lo)):
        return None
    return lo, hi


def frame_camera(camera: Any, box: tuple[np.ndarray, np.ndarray] | None, view: str, fovy: float, aspect: float) -> None:
    """Point MuJoCo's free camera ``camera`` (an ``MjvCamera``) at ``box`` from ``view``: the
    nearest distance at which all eight corners of the box are inside both fields of view."""
    lo, hi = box if box is not None else (np.full(3, -0.25), np.full(3, 0.25))
    center = (lo + hi) / 2
    azimuth, elevation = VIEWS[view]
    az, el = math.radians(azimuth), math.radians(elevation)
    forward = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    tan_v = math.tan(math.radians(fovy) / 2)
    tan_h = tan_v * aspect
    half = np.maximum((hi - lo) / 2, 0.01)
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * half
    # A corner at (x, y) across and ``depth`` along the view is inside when |x| <= tan * (d + depth).
    depth = corners @ forward
    need = np.maximum(np.abs(corners @ right) / tan_h, np.abs(corners @ up) / tan_v) - depth
    camera.lookat[:] = center
    camera.distance = float(need.max()) * 1.08
    camera.azimuth, camera.elevation = azimuth, elevation
