"""The Isaac folder's world (``--isaac-sim --world FILE``, docs/isaac.md, "A world"): the world
stage beside the robot's USD, as ``-t usd`` writes it, the ground alone for Isaac Lab's terrain
importer, and what the Isaac Lab module says of both.

Isaac Lab makes its own ``PhysicsScene`` (``SimulationCfg``) and brings a terrain in with
``TerrainImporterCfg``: ``terrain_type="usd"`` references a USD file under its prim, and
``"plane"`` makes its own infinite ground plane. So the ground goes in a file of its own
(``<stem>_terrain.usda``: no scene, no robot, no cords), the world's step and gravity go in the
module as ``SimulationCfg`` values, and the robot's ``init_state`` is its spawn point on the terrain.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from robodesc.emit.common.stance import Stance
from robodesc.emit.isaac.settings import IsaacSettings
from robodesc.ir.diagnostics import Findings
from robodesc.ir.geometry import Vec3
from robodesc.ir.model import Robot
from robodesc.ir.world import Plane

if TYPE_CHECKING:
    from robodesc.emit.common.world import PlacedWorld

STAGE = "emit:isaac"


@dataclass(slots=True, frozen=True)
class IsaacWorld:
    """The world as the folder writes it: where each copy's root starts, and the Isaac Lab terrain."""

    roots: list[Vec3]
    yaw: float  # rad about z, every copy
    terrain_type: str  # Isaac Lab's TerrainImporterCfg.terrain_type: "usd" or "plane"
    dt: float | None
    gravity: Vec3 | None


def place(
    robot: Robot,
    placed: PlacedWorld,
    settings: IsaacSettings,
    initial: Mapping[str, float],
    given: frozenset[str],
    findings: Findings,
) -> IsaacWorld:
    """Put the robot on the world's ground in the pose the folder starts it in (the USD's joint
    state and the module's ``init_state``: the default pose, ``initial``). A given ``--init-pos``
    wins for the first copy."""
    floating = not settings.fix_base
    roots = [
        (x, y, round(z, 6))  # to the micrometre: the module's numbers stay readable
        for x, y, z in placed.root_positions(robot, Stance(dict(initial), "initial"), floating)
    ]
    if "init_pos" in given:
        roots[0] = settings.init_pos
    else:
        settings.init_pos = roots[0]
    terrain_type = "plane" if _flat_plane(placed) else "usd"
    findings.info(
        "isaac-world",
        f"{len(roots)} robot(s) on the world {placed.world.name!r}: the first root at "
        f"({', '.join(f'{v:.3f}' for v in roots[0])}) m ({placed.spawn_source}); Isaac Lab's terrain "
        + (
            "is its own ground plane (the world's ground is a level plane at z = 0)"
            if terrain_type == "plane"
            else "is the world's ground as a USD file (terrain_type 'usd')"
        ),
        element=f"robot {robot.name!r}",
        stage=STAGE,
    )
    physics = placed.world.physics
    return IsaacWorld(roots, placed.yaw, terrain_type, physics.step, physics.gravity)


def _flat_plane(placed: PlacedWorld) -> bool:
    """The ground is nothing but level planes through z = 0 (or no ground, only cords): Isaac Lab's
    own plane is the same ground, and its importer needs no file for it."""
    from robodesc.ir.rigid import pose_frame

    for body in placed.world.bodies:
        for collider in body.colliders:
            if not isinstance(collider.shape, Plane):
                return False
            frame = pose_frame(body.pose) @ pose_frame(collider.origin)
            up = frame.rotation[2][2] * collider.shape.normal[2]
            if abs(frame.translation[2]) > 1e-9 or abs(up - 1.0) > 1e-9:
                return False
    return True


def lab_world(world: IsaacWorld, names: Mapping[str, str]) -> dict[str, Any]:
    """``WORLD`` in the Isaac Lab module: plain data, file names relative to the module."""
    return {
        "terrain_type": world.terrain_type,
        "terrain_usd": names["terrain"] if world.terrain_type == "usd" else None,
        "world_usd": names["world"],
        "dt": world.dt,
        "gravity": world.gravity,
        # Every copy's root, first the one ROBOT["init_state"] holds; yaw (rad) about z.
        "spawns": [tuple(float(v) for v in root) for root in world.roots],
        "yaw": world.yaw,
    }


def write_world_files(
    robot: Robot, staging: str, names: Mapping[str, str], world: IsaacWorld, placed: PlacedWorld, findings: Findings
) -> list[str]:
    """Write the world stage (and the terrain file for ``terrain_type="usd"``); return their roles."""
    from robodesc.emit.usd import robot_friction, write_terrain, write_world

    contacts = any(s.type.value == "contact" for s in robot.sensors)
    mu = robot_friction(robot)  # Isaac Lab 3 runs Newton: the ground's friction capped at the robot's
    write_world(
        os.path.join(staging, names["world"]),
        names["usd"],
        robot.name,
        placed,
        world.roots,
        findings,
        contacts=contacts,
        robot_mu=mu,
    )
    if world.terrain_type != "usd":
        return ["world"]
    write_terrain(os.path.join(staging, names["terrain"]), placed, findings, robot_mu=mu)
    return ["world", "terrain"]
