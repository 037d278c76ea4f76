"""The world as every target writes it: read once, placed once (docs/worlds.md).

:func:`place_world` runs before the emitters. It turns every terrain collider (a mesh or a height
image) into a heightfield grid (meshes/heightfield.py), reports what the grid loses, and fixes where
the robot stands: ``--spawn X,Y[,Z]``, else the world's include of the robot, else the origin. The
height of a robot's root follows from the ground under its feet in the pose each target starts it
in (:meth:`PlacedWorld.root_position`), so every target puts it on the same ground.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from robodesc.emit.common.stance import CLEARANCE, Stance
from robodesc.ir.diagnostics import ConfigError, Findings
from robodesc.ir.geometry import Box, Mesh, Vec3
from robodesc.ir.model import Robot
from robodesc.ir.rigid import Frame, apply, link_frames, pose_frame, transpose
from robodesc.ir.world import CordField, HeightImage, Plane, StaticBody, World, WorldCollider
from robodesc.meshes.heightfield import DEFAULT_RESOLUTION, HeightfieldError, HeightGrid, rasterize

STAGE = "world"
# A terrain frame whose z axis is this close to the world's is level: its grid holds heights.
_LEVEL = 1e-9


@dataclass(slots=True)
class TerrainGrid:
    """A terrain collider as a heightfield: ``grid`` in the collider's own frame, ``frame`` that
    frame in the world (level: turned about z only)."""

    body: StaticBody
    collider: WorldCollider
    grid: HeightGrid
    frame: Frame

    @property
    def label(self) -> str:
        return f"{self.body.name}/{self.collider.name}"


@dataclass(slots=True)
class PlacedWorld:
    world: World
    grids: list[TerrainGrid] = field(default_factory=list)
    spawn: tuple[float, ...] = (0.0, 0.0)  # X, Y or X, Y, Z (m)
    yaw: float = 0.0  # rad, about the world's z
    spawn_source: str = "origin"
    # Several copies of the robot (``--spawn`` given more than once): every copy's point, the first
    # being ``spawn``. Empty: one robot, at ``spawn``.
    copies: list[tuple[float, ...]] = field(default_factory=list)
    # Each cord field with its cords' anchor points (world frame), drawn once from its seed.
    cords: list[tuple[CordField, list[Vec3]]] = field(default_factory=list)

    @property
    def points(self) -> list[tuple[float, ...]]:
        """Where each copy of the robot stands (one point for one robot)."""
        return self.copies or [self.spawn]

    def root_positions(self, robot: Robot, stance: Stance, floating: bool) -> list[Vec3]:
        """:meth:`root_position` of every copy: each on the ground under its own feet."""
        return [self.root_position(robot, stance, floating, at=point) for point in self.points]

    def grid_of(self, collider: WorldCollider) -> TerrainGrid | None:
        return next((g for g in self.grids if g.collider is collider), None)

    def ground_height(self, x: float, y: float) -> float | None:
        """The highest static surface under (x, y): terrains, level boxes and level planes."""
        best: float | None = None
        for body in self.world.bodies:
            for collider in body.colliders:
                z = self._surface(body, collider, x, y)
                if z is not None and (best is None or z > best):
                    best = z
        return best

    def _surface(self, body: StaticBody, collider: WorldCollider, x: float, y: float) -> float | None:
        frame = pose_frame(body.pose) @ pose_frame(collider.origin)
        local = _to_local(frame, (x, y, 0.0))
        grid = self.grid_of(collider)
        if grid is not None:
            g = grid.grid
            w, h = g.size
            if not (g.x0 - 1e-9 <= local[0] <= g.x0 + w + 1e-9 and g.y0 - 1e-9 <= local[1] <= g.y0 + h + 1e-9):
                return None
            z = float(g.height_at(np.array([local[0]]), np.array([local[1]]))[0])
            return frame.translation[2] + z
        if not _level(frame):
            return None
        shape = collider.shape
        if isinstance(shape, Plane):
            return (
                frame.translation[2]
                if shape.normal[2] > 0 and abs(shape.normal[0]) + abs(shape.normal[1]) < 1e-12
                else None
            )
        if isinstance(shape, Box):
            hx, hy, hz = (s / 2 for s in shape.size)
            if abs(local[0]) <= hx and abs(local[1]) <= hy:
                return frame.translation[2] + hz
        return None

    def root_position(self, robot: Robot, stance: Stance, floating: bool, at: tuple[float, ...] | None = None) -> Vec3:
        """Where the root goes: at the spawn X, Y (``at``, else the spawn; turned by the yaw), and
        high enough that every collider's lowest point clears the ground under it by CLEARANCE (a
        given Z wins)."""
        point = self.spawn if at is None else at
        x, y = point[0], point[1]
        if len(point) == 3:
            return (x, y, point[2])
        points = _low_points(robot, stance.positions)
        if not points:
            ground = self.ground_height(x, y)
            return (x, y, 0.0 if ground is None else ground)
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        need = -math.inf
        for px, py, pz in points:
            wx, wy = x + c * px - s * py, y + s * px + c * py
            ground = self.ground_height(wx, wy)
            if ground is not None:
                need = max(need, ground - pz)
        if need == -math.inf:
            need = -min(p[2] for p in points)  # over no ground: the lowest point at z = 0
        # A welded robot sits on the ground; a floating one starts CLEARANCE above it and drops.
        return (x, y, need + (CLEARANCE if floating else 0.0))


def place_world(
    robot: Robot | None,
    world: World,
    findings: Findings,
    *,
    resolution: float | None = None,
    spawn: tuple[float, ...] | None = None,
    copies: tuple[tuple[float, ...], ...] = (),
) -> PlacedWorld:
    """Heightfields of the world's terrains (at ``resolution`` m, default 2 cm) and the spawn point
    (``robot`` None: a world compiled alone, with no robot to place)."""
    placed = PlacedWorld(world)
    resolution = resolution or DEFAULT_RESOLUTION
    if not (resolution > 0 and math.isfinite(resolution)):
        raise ConfigError(f"--terrain-resolution {resolution}: a positive number of metres")
    for body in world.bodies:
        for collider in body.colliders:
            grid = _grid(body, collider, resolution, findings)
            if grid is not None:
                placed.grids.append(grid)
    if robot is not None:
        _spawn(robot, world, spawn or (copies[0] if copies else None), placed)
    if len(copies) > 1:
        placed.copies = [_point(point) for point in copies]
    for cords in world.cords:
        placed.cords.append((cords, _anchors(placed, cords)))
    return placed


def _anchors(placed: PlacedWorld, cords: CordField) -> list[Vec3]:
    """Anchor points drawn from the field's seed (numpy's PCG64: the same field on every machine),
    each ``anchor_height`` above the ground under it (z = 0 where there is none)."""
    rng = np.random.default_rng(cords.seed)
    x0, y0, x1, y1 = cords.area
    xs = rng.uniform(x0, x1, cords.count) if x1 > x0 else np.full(cords.count, x0)
    ys = rng.uniform(y0, y1, cords.count) if y1 > y0 else np.full(cords.count, y0)
    low, high = cords.anchor_height
    zs = rng.uniform(low, high, cords.count) if high > low else np.full(cords.count, low)
    out: list[Vec3] = []
    for x, y, z in zip(xs.tolist(), ys.tolist(), zs.tolist(), strict=True):
        ground = placed.ground_height(x, y)
        out.append((round(x, 6), round(y, 6), round(z + (ground or 0.0), 6)))
    return out


def _grid(body: StaticBody, collider: WorldCollider, resolution: float, findings: Findings) -> TerrainGrid | None:
    shape = collider.shape
    if not isinstance(shape, Mesh | HeightImage):
        return None
    frame = pose_frame(body.pose) @ pose_frame(collider.origin)
    element = f"collision {collider.name!r} of {body.name!r}"
    if not _level(frame):
        findings.warn(
            "world-terrain-tilted",
            "the terrain's frame is tilted: no heightfield is made from it; it stays a mesh where a target can "
            "hold one (USD, SDF) and MJCF collides its convex hull",
            element=element,
            loc=collider.src,
            stage=STAGE,
        )
        return None
    try:
        if isinstance(shape, HeightImage):
            from robodesc.meshes.heightimage import read_height_image

            grid = read_height_image(shape.path, shape.size)
        else:
            grid = _mesh_grid(shape, resolution)
    except HeightfieldError as exc:
        findings.warn(
            "world-terrain-unreadable",
            f"no heightfield: {exc}; MJCF collides its convex hull, USD and SDF keep the mesh",
            element=element,
            loc=collider.src,
            stage=STAGE,
        )
        return None
    rows, cols = grid.shape
    note = (
        f"a {cols} x {rows} heightfield at {grid.step:g} m; largest height error at the mesh's vertices "
        f"{grid.max_error * 1000:.1f} mm"
    )
    if grid.gap_points:
        note += f"; {grid.gap_points} points over no surface (a gap) lie 1 m below the lowest surface"
    findings.info("world-heightfield", note, element=element, loc=collider.src, stage=STAGE)
    if grid.overhang_points:
        findings.warn(
            "world-terrain-overhang",
            f"{grid.overhang_points} grid points lie under two surfaces (an overhang): the heightfield keeps the "
            "higher one, so MJCF loses what is under it; USD and SDF keep the mesh",
            element=element,
            loc=collider.src,
            stage=STAGE,
        )
    return TerrainGrid(body, collider, grid, frame)


def _mesh_grid(mesh: Mesh, resolution: float) -> HeightGrid:
    from robodesc.meshes.buffers import MeshReadError
    from robodesc.meshes.data import build_mesh

    if mesh.path is None:
        raise HeightfieldError("the mesh was not found")
    try:
        data = build_mesh(mesh.path, mesh.scale)
    except (MeshReadError, OSError) as exc:
        raise HeightfieldError(f"the mesh cannot be read ({exc})") from None
    points = np.frombuffer(data.points, dtype=np.float32).astype(np.float64).reshape(-1, 3)
    triangles = np.frombuffer(data.face_vertex_indices, dtype=np.int32).astype(np.int64).reshape(-1, 3)
    return rasterize(points, triangles, resolution)


def _spawn(robot: Robot, world: World, spawn: tuple[float, ...] | None, placed: PlacedWorld) -> None:
    if spawn is not None:
        placed.spawn, placed.spawn_source = _point(spawn), "--spawn"
        return
    for include in world.includes:
        stem = include.uri.rstrip("/").rsplit("/", 1)[-1]
        if robot.name in (include.name, stem) and include.pose is not None:
            placed.spawn = (include.pose.xyz[0], include.pose.xyz[1])
            placed.yaw = include.pose.rpy[2]
            placed.spawn_source = f"the world's include of {include.uri!r}"
            return


def _point(spawn: tuple[float, ...]) -> tuple[float, ...]:
    values = tuple(float(v) for v in spawn)
    if len(values) not in (2, 3) or not all(math.isfinite(v) for v in values):
        raise ConfigError(f"--spawn {spawn}: X,Y or X,Y,Z, finite numbers of metres")
    return values


def _level(frame: Frame) -> bool:
    return abs(frame.rotation[2][2] - 1.0) < _LEVEL


def _to_local(frame: Frame, point: Vec3) -> Vec3:
    """``point`` (world) in ``frame``: the inverse transform, Rᵀ (p - t)."""
    t = frame.translation
    return apply(transpose(frame.rotation), (point[0] - t[0], point[1] - t[1], point[2] - t[2]))


def _low_points(robot: Robot, q: Mapping[str, float]) -> list[Vec3]:
    """The lowest point of every collider at pose ``q`` in the root frame: primitives exactly, meshes
    by the corners of their box (where the ground is under them matters, not the last millimetre)."""
    from robodesc.emit.common.stance import shape_low_point

    frames = link_frames(robot, q)
    out: list[Vec3] = []
    for link in robot.links:
        at = frames.get(link.name)
        if at is None:
            continue
        for collision in link.collisions:
            point = shape_low_point(collision.geometry, at @ pose_frame(collision.origin))
            if point is not None:
                out.append(point)
    return out
