"""The scene floor's height: under the lowest collider of a robot welded to the world.

A welded robot stays where it is written. When some of its colliders lie below z = 0 (a robot whose
base link is its hip, say), a floor at 0 cuts through them, and the contacts push against a body that
cannot move: MuJoCo's accelerations blow up within a second (mujoco_menagerie's test fails on a NaN).
So the floor goes just under the lowest collider, measured at the zero pose (the pose MuJoCo starts
in, qpos0). A floating robot is raised onto the floor instead (emitter._root_pose), and a welded robot
entirely above the floor keeps the floor at 0.
"""

from __future__ import annotations

import math

from robodesc.emit.common.stance import lowest_point
from robodesc.ir.model import Robot
from robodesc.ir.rigid import Frame

# The gap between the lowest collider and the floor, m: no contact at the start, nor once the arm has
# sagged under its own weight. A welded arm holds its home within 0.01 rad, about 1 cm at the reach of a
# typical arm: with a 1 mm gap example-robot-data's UR5 sagged its wrist onto the floor within 5 s, and
# the four mesh contacts cost 44 % of its steps/s (66,600 -> 120,000 with this gap; issue 35).
FLOOR_GAP = 1e-2


def floor_height(robot: Robot, root_pose: Frame) -> float:
    """0, or a little below the lowest collider point of the welded robot placed at ``root_pose``
    (meshes by their bounding box: the floor may sit lower than needed, never inside one)."""
    lowest = lowest_point(robot, {}, root=root_pose, exact=False)
    if lowest is None or not lowest < 0.0:
        return 0.0
    # Rounded down to 0.1 mm: a short number in scene.xml, still at least FLOOR_GAP below.
    return math.floor((lowest - FLOOR_GAP) * 1e4) / 1e4
