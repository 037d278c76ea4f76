"""Where the picture's camera stands: the robot's geoms seen from a named direction.

The points fitted are the corners of every drawn geom's own box (MuJoCo's ``geom_aabb``, in the
geom's frame, turned into the world), which hug the robot much closer than one world-aligned box
would from a slanted view. The camera looks at the middle of their extent across the view and
stands at the nearest distance that keeps every corner inside both fields of view.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robodesc.view.views import VIEWS

_SIGNS = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
Points = NDArray[np.float64]


def corners(model: Any, data: Any, groups: set[int]) -> Points | None:
    """World-space corners (8 per geom) of the geoms in ``groups``; None when there are none."""
    out = []
    for i in range(model.ngeom):
        if int(model.geom_group[i]) not in groups:
            continue
        center, half = model.geom_aabb[i, :3], model.geom_aabb[i, 3:]
        rot = data.geom_xmat[i].reshape(3, 3)
        out.append(data.geom_xpos[i] + (center + _SIGNS * half) @ rot.T)
    return np.concatenate(out) if out else None


def _basis(view: str) -> tuple[Points, Points, Points]:
    azimuth, elevation = VIEWS[view]
    az, el = math.radians(azimuth), math.radians(elevation)
    forward = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    return forward, right, np.cross(right, forward)


def frame_camera(camera: Any, points: Points | None, view: str, fovy: float, aspect: float) -> None:
    """Point MuJoCo's free camera ``camera`` (an ``MjvCamera``) at ``points`` from ``view``."""
    if points is None:
        points = _SIGNS * 0.25
    forward, right, up = _basis(view)
    # Centre the extent across the view (right and up) and take the middle along it.
    x, y, z = points @ right, points @ up, points @ forward
    center = right * (x.max() + x.min()) / 2 + up * (y.max() + y.min()) / 2 + forward * (z.max() + z.min()) / 2
    rel = points - center
    tan_v = math.tan(math.radians(fovy) / 2)
    tan_h = tan_v * aspect
    # A point at (x, y) across and ``depth`` along the view is inside when |x| <= tan * (d + depth).
    need = np.maximum(np.abs(rel @ right) / tan_h, np.abs(rel @ up) / tan_v) - rel @ forward
    camera.lookat[:] = center
    camera.distance = max(float(need.max()) * 1.06, 0.05)
    camera.azimuth, camera.elevation = VIEWS[view]
