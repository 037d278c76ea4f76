"""The scene floor's height: under the lowest collider of a robot welded to the world.

A welded robot stays where it is written. When some of its colliders lie below z = 0 (a robot whose
base link is its hip, say), a floor at 0 cuts through them, and the contacts push against a body that
cannot move: MuJoCo's accelerations blow up within a second (mujoco_menagerie's test fails on a NaN).
So the floor goes just under the lowest collider, measured at the zero pose (the pose MuJoCo starts
in, qpos0). A floating robot is raised onto the floor instead (emitter._root_pose), and a welded robot
entirely above the floor keeps the floor at 0.
"""

from __future__ import annotations

import itertools
import math

from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Mesh, Sphere
from robodesc.ir.model import Robot
from robodesc.ir.rigid import Frame, apply, link_frames, pose_frame
from robodesc.meshes.buffers import MeshReadError
from robodesc.meshes.data import build_mesh

# The gap between the lowest collider and the floor, m: no contact at the start.
FLOOR_GAP = 1e-3


def floor_height(robot: Robot, root_pose: Frame) -> float:
    """0, or a little below the lowest collider point of the welded robot placed at ``root_pose``."""
    lowest = math.inf
    frames = link_frames(robot)
    for link in robot.links:
        for collision in link.collisions:
            at = root_pose @ frames[link.name] @ pose_frame(collision.origin)
            low = _lowest(collision.geometry, at)
            if low is not None:
                lowest = min(lowest, low)
    if not lowest < 0.0:
        return 0.0
    # Rounded down to 0.1 mm: a short number in scene.xml, still at least FLOOR_GAP below.
    return math.floor((lowest - FLOOR_GAP) * 1e4) / 1e4


def _lowest(geometry: Geometry, at: Frame) -> float | None:
    """The smallest world z of the shape placed at ``at`` (None when a mesh cannot be read)."""
    z = at.translation[2]
    if isinstance(geometry, Sphere):
        return z - geometry.radius
    if isinstance(geometry, Box):
        return min(_corners_z(at, [(-s / 2, s / 2) for s in geometry.size]))
    if isinstance(geometry, (Cylinder, Capsule)):
        # The axis ends, lowered by the radius (exact for a capsule, a bound for a cylinder).
        length = geometry.length / 2
        ends = [z + apply(at.rotation, (0.0, 0.0, s))[2] for s in (-length, length)]
        return min(ends) - geometry.radius
    if isinstance(geometry, Mesh):
        if geometry.path is None:
            return None
        try:
            data = build_mesh(geometry.path, geometry.scale)
        except (MeshReadError, OSError):
            return None
        lo, hi = data.extent
        return min(_corners_z(at, list(zip(lo, hi, strict=True))))
    return None


def _corners_z(at: Frame, ranges: list[tuple[float, float]]) -> list[float]:
    """World z of the eight corners of an axis-aligned box given per-axis (min, max)."""
    return [at.translation[2] + apply(at.rotation, corner)[2] for corner in itertools.product(*ranges)]
