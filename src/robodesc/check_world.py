"""The stand of ``validate --dynamics --world`` (docs/dynamics.md, "On a world"): the world placed
once more, as the compile placed it, for what the engines cannot tell by themselves.

Each engine reads the world its compile wrote (MJCF's scene.xml, USD's world stage). The driver
adds what is the same for all of them: where the root starts at the home pose (the spawn the
placement chose, emit/common/world.py, at the height its stance needs over the terrain's mesh),
each foot's sole in its link's frame (to find it in the world from the pose an engine reports), the
ground's height under any point (the terrain's exact surface), and for Newton each terrain as a
heightfield file: Newton's MuJoCo solver collides a static triangle mesh as its convex hull (a
box dropped in gap_40cm's gap rested on the hull), so its worker swaps the mesh for the grid.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any

import numpy as np

from robodesc.emit.common.stance import Stance, complete, lowest_collider, shape_low_point
from robodesc.emit.common.world import PlacedWorld, place_world
from robodesc.ir.diagnostics import ConfigError, Findings
from robodesc.ir.model import Robot
from robodesc.ir.rigid import apply, link_frames, pose_frame, transpose
from robodesc.meshes.data import MeshCache
from robodesc.validation.dynamics.scenarios import DynamicsOptions, WorldStand, feet, home_pose


def world_stand(
    robot: Robot,
    opts: DynamicsOptions,
    options: Mapping[str, Any],
    files: Mapping[str, str],
    sensors: tuple[str, ...],
    folder: str,
) -> WorldStand:
    placed = _placed(robot, options)
    q = complete(robot, home_pose(robot, opts.pose))
    root = placed.root_position(robot, Stance(q, "home"), floating=True)
    return WorldStand(
        files=dict(files),
        spawn=(root[0], root[1], root[2], placed.yaw),
        soles=_soles(robot, q),
        ground=placed.ground_heights,
        sensors=sensors,
        heightfields=_heightfields(placed, folder),
    )


def _placed(robot: Robot, options: Mapping[str, Any]) -> PlacedWorld:
    from robodesc.frontends.world import load_world
    from robodesc.options import build_options

    keys = ("world", "terrain", "terrain_size", "terrain_resolution", "spawn", "model_path", "cords")
    built = build_options({k: options[k] for k in keys if k in options})
    findings = Findings()
    world = load_world(built.world, findings)
    if world is None:
        raise ConfigError("validate --dynamics: the world could not be read (the compile said why)")
    given = built.world
    return place_world(robot, world, findings, resolution=given.terrain_resolution, spawn=given.spawn)


def _soles(robot: Robot, q: Mapping[str, float]) -> dict[str, tuple[float, float, float]]:
    """Each foot's lowest point at the home pose, in the foot link's own frame."""
    frames = link_frames(robot, q)
    meshes = MeshCache()
    out: dict[str, tuple[float, float, float]] = {}
    for name in feet(robot, dict(q)):
        link, at = robot.link(name), frames.get(name)
        if at is None or not link.collisions:
            continue
        sole = link.collisions[lowest_collider(link, at, meshes)]
        point = shape_low_point(sole.geometry, at @ pose_frame(sole.origin), meshes)
        if point is None:
            continue
        t = at.translation
        out[name] = apply(transpose(at.rotation), (point[0] - t[0], point[1] - t[1], point[2] - t[2]))
    return out


def _heightfields(placed: PlacedWorld, folder: str) -> list[dict[str, Any]]:
    """Each terrain's heightfield as an .npz for Newton's worker (which puts them in place of every
    static triangle mesh of the world stage: the robot's own shapes all belong to its bodies)."""
    out = []
    for i, grid in enumerate(placed.grids):
        path = os.path.join(folder, f"terrain_{i}.npz")
        g, frame = grid.grid, grid.frame
        yaw = float(np.arctan2(frame.rotation[1][0], frame.rotation[0][0]))
        np.savez(path, z=g.z, x0=g.x0, y0=g.y0, step=g.step, frame=np.array([*frame.translation, yaw]))
        out.append({"npz": path, "label": grid.label})
    return out
