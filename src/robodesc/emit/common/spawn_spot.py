"""Where a legged robot can stand on uneven ground: the nearest spot whose ground is level under its feet.

The stance (emit/common/stance.py) is made for flat ground: every foot at one height. Spawned where
the ground under one foot is higher (rough_25cm at the origin: 14 cm between Spirit's feet), the
robot rests on that foot with the others in the air, drops onto them and tips over. Unless the user
gave ``--spawn``, the spawn moves to the nearest point of a 2.5 cm lattice, within
:data:`SEARCH_RADIUS`, where the ground under every foot lies within :data:`LEVEL` and no other
collider (a belly over a bump) sits lower over the ground than the feet; a finding says where and
why. A ``--spawn`` given is kept, with a warning when its ground is not level. Heights are the
terrain's own (its mesh's surface, what USD and SDF collide with); every target then stands the
robot at the same X, Y.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from robodesc.emit.common.stance import choose_stance, lowest_collider, shape_low_point
from robodesc.ir.diagnostics import Findings
from robodesc.ir.geometry import Vec3
from robodesc.ir.model import Robot
from robodesc.ir.rigid import link_frames, pose_frame
from robodesc.meshes.data import MeshCache

Array = NDArray[np.float64]
# The ground's height at many points (NaN over none): PlacedWorld.ground_heights.
Ground = Callable[[Array, Array], Array]
STAGE = "world"
LEVEL = 0.01  # m: the largest difference of the ground's height under the feet a stance keeps
SEARCH_RADIUS = 2.0  # m
STEP = 0.025  # m between candidate spots


def level_spot(
    robot: Robot, ground: Ground, spawn: tuple[float, float], yaw: float, source: str, findings: Findings
) -> tuple[float, float]:
    """Where the robot stands: ``spawn`` (X, Y, chosen by ``source``), or the nearest level spot."""
    stance = choose_stance(robot, None)
    if len(stance.legs) < 3:
        return spawn  # not a robot that stands on legs: its height alone is placed
    frames = link_frames(robot, stance.positions)
    meshes = MeshCache()
    feet: list[Vec3] = []
    others: list[Vec3] = []
    for link in robot.links:
        at = frames.get(link.name)
        if at is None or not link.collisions:
            continue
        foot = any(leg.foot == link.name for leg in stance.legs)
        sole = lowest_collider(link, at, meshes) if foot else -1
        for i, collision in enumerate(link.collisions):
            point = shape_low_point(collision.geometry, at @ pose_frame(collision.origin), meshes)
            if point is not None:
                (feet if i == sole else others).append(point)
    x0, y0 = spawn
    foot_xy = _turn(np.array(feet), yaw)
    other_xy = _turn(np.array(others), yaw) if others else np.zeros((0, 3))
    start = _spread(ground, x0, y0, foot_xy, other_xy)
    element = f"robot {robot.name!r}"
    if start[0] <= LEVEL:
        return spawn
    where = f"({x0:g}, {y0:g})"
    uneven = (
        f"the ground under its {len(feet)} feet at {where} differs by {_cm(start[0])} (its stance is made for level "
        "ground: it would rest on the highest foot and tip over)"
    )
    if source == "--spawn":
        findings.warn(
            "world-spawn-uneven", uneven + "; --spawn is kept: choose a level spot", element=element, stage=STAGE
        )
        return spawn
    best = _search(ground, x0, y0, foot_xy, other_xy)
    if best is None:
        findings.warn(
            "world-spawn-uneven",
            uneven + f"; no spot within {SEARCH_RADIUS:g} m is level within {_cm(LEVEL)}: give --spawn X,Y",
            element=element,
            stage=STAGE,
        )
        return spawn
    x, y, spread = best
    findings.info(
        "world-spawn-moved",
        f"{uneven}: it stands at ({x:.3g}, {y:.3g}) instead, {math.hypot(x - x0, y - y0):.2f} m from "
        f"{'the origin' if source == 'origin' else source}, the nearest spot where the ground under every foot lies within {_cm(spread)} "
        f"(at most {_cm(LEVEL)}); --spawn X,Y chooses another",
        element=element,
        stage=STAGE,
    )
    return (round(x, 6), round(y, 6))


def _cm(metres: float) -> str:
    return f"{metres * 100:.1f} cm"


def _turn(points: Array, yaw: float) -> Array:
    """Root-frame points turned by the spawn's yaw (x, y) with their height (z) kept."""
    c, s = math.cos(yaw), math.sin(yaw)
    out = points.copy()
    out[:, 0] = c * points[:, 0] - s * points[:, 1]
    out[:, 1] = s * points[:, 0] + c * points[:, 1]
    return out


def _spread(ground: Ground, x: float, y: float, feet: Array, others: Array) -> tuple[float, bool]:
    spread, clear = _score(ground, np.array([x]), np.array([y]), feet, others)
    return float(spread[0]), bool(clear[0])


def _score(
    ground: Ground,
    xs: Array,
    ys: Array,
    feet: Array,
    others: Array,
) -> tuple[Array, NDArray[np.bool_]]:
    """Per spot: the spread of the ground's height under the feet (inf where a foot is over no
    ground), and whether every other collider clears the ground when the feet stand on it."""
    soles = ground(xs[:, None] + feet[None, :, 0], ys[:, None] + feet[None, :, 1])
    over_none = np.isnan(soles).any(axis=1)
    soles = np.where(np.isnan(soles), 0.0, soles)
    spread = np.where(over_none, np.inf, soles.max(axis=1) - soles.min(axis=1))
    need = (soles - feet[None, :, 2]).max(axis=1)  # the root height the feet ask for
    if not len(others):
        return spread, np.ones(len(xs), dtype=bool)
    under = ground(xs[:, None] + others[None, :, 0], ys[:, None] + others[None, :, 1])
    body = np.where(np.isnan(under), -np.inf, under - others[None, :, 2]).max(axis=1)
    return spread, body <= need + 1e-9


def _search(ground: Ground, x0: float, y0: float, feet: Array, others: Array) -> tuple[float, float, float] | None:
    """The nearest level spot (ties: the most level), ring by ring out to SEARCH_RADIUS."""
    n = int(SEARCH_RADIUS / STEP)
    offsets = np.arange(-n, n + 1) * STEP
    dx, dy = np.meshgrid(offsets, offsets)
    dist = np.hypot(dx, dy).ravel()
    order = np.argsort(dist, kind="stable")
    dx, dy, dist = dx.ravel()[order], dy.ravel()[order], dist[order]
    keep = dist <= SEARCH_RADIUS + 1e-9
    dx, dy, dist = dx[keep], dy[keep], dist[keep]
    # Rings of one lattice step: the first ring with a level spot holds the nearest ones.
    ring = np.floor(dist / STEP).astype(np.int64)
    for r in np.unique(ring):
        at = ring == r
        xs, ys = x0 + dx[at], y0 + dy[at]
        spread, clear = _score(ground, xs, ys, feet, others)
        ok = (spread <= LEVEL) & clear
        if ok.any():
            i = int(np.argmin(np.where(ok, spread, np.inf)))
            return float(xs[i]), float(ys[i]), float(spread[i])
    return None
