"""The world as every target writes it: read once, placed once (docs/worlds.md).

:func:`place_world` runs before the emitters. It reads every terrain collider (a mesh's exact
surface, or a height image) and fixes where the robot stands: ``--spawn X,Y[,Z]``, else the world's
include of the robot, else the origin, moved to the nearest spot where the ground under the feet is
level (emit/common/spawn_spot.py). The height of a robot's root follows from the ground under its
feet in the pose each target starts it in (:meth:`PlacedWorld.root_position`), so every target puts
it on the same ground. A terrain becomes a heightfield grid (meshes/heightfield.py, with a finding
of what the grid loses) only when a target asks for one (MJCF): USD and SDF keep the mesh.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from robodesc.emit.common.spawn_spot import level_spot
from robodesc.emit.common.stance import CLEARANCE, Stance
from robodesc.ir.diagnostics import ConfigError, Findings
from robodesc.ir.geometry import Box, Mesh, Vec3
from robodesc.ir.model import Robot
from robodesc.ir.rigid import Frame, link_frames, pose_frame
from robodesc.ir.world import CordField, HeightImage, Plane, StaticBody, World, WorldCollider
from robodesc.meshes.heightfield import DEFAULT_RESOLUTION, HeightfieldError, HeightGrid, TerrainSurface, rasterize

STAGE = "world"
Array = NDArray[np.float64]
# A terrain frame whose z axis is this close to the world's is level: its grid holds heights.
_LEVEL = 1e-9


# MuJoCo's heightfield: the solid below the lowest point (its size[3]), m, and the height span below
# which a grid is flat and drawn as a box (an hfield needs a height range).
HFIELD_BASE = 0.1
HFIELD_FLAT = 1e-9


@dataclass(frozen=True, slots=True)
class MujocoHeightfield:
    """A terrain grid as MuJoCo holds it (:meth:`TerrainGrid.mujoco`), for scene.xml and the
    pictures alike. ``frame``: where the geom goes in the world; ``half``: half its width and depth.
    ``heights`` None: a flat grid, a box ``HFIELD_BASE`` thick whose top is the surface; else each
    height over the lowest, in MuJoCo's row order (the +y edge first), spanning ``span``."""

    frame: Frame
    half: tuple[float, float]
    span: float
    heights: Array | None


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

    def mujoco(self) -> MujocoHeightfield:
        g = self.grid
        width, depth = g.size
        low, high = float(g.z.min()), float(g.z.max())
        half = (width / 2, depth / 2)
        centre = Frame(translation=(g.x0 + width / 2, g.y0 + depth / 2, low))
        if high - low < HFIELD_FLAT:
            slab = Frame(translation=(centre.translation[0], centre.translation[1], low - HFIELD_BASE / 2))
            return MujocoHeightfield(self.frame @ slab, half, 0.0, None)
        # MuJoCo's first row is the +y edge (the grid's is -y); it scales the data to [0, span].
        return MujocoHeightfield(self.frame @ centre, half, high - low, np.flipud(g.z - low))


@dataclass(slots=True)
class Terrain:
    """A level terrain collider as read: the mesh's exact surface (``surface``: what USD and SDF
    collide with), or a height image's grid (``image``: a heightfield already). ``points`` and
    ``triangles`` are the mesh, kept for the heightfield a target may ask for."""

    body: StaticBody
    collider: WorldCollider
    frame: Frame
    surface: TerrainSurface | None = None
    image: HeightGrid | None = None
    points: NDArray[np.float64] | None = None
    triangles: NDArray[np.int64] | None = None

    def heights(self, x: Array, y: Array, grid: HeightGrid | None) -> Array:
        """The terrain's heights at world points (NaN off it): on ``grid`` when given, else on its
        own surface."""
        lx, ly = _local_xy(self.frame, x, y)
        g = grid or self.image
        if g is not None:
            w, h = g.size
            inside = (lx >= g.x0 - 1e-9) & (lx <= g.x0 + w + 1e-9) & (ly >= g.y0 - 1e-9) & (ly <= g.y0 + h + 1e-9)
            z = g.height_at(lx, ly)
            return np.where(inside, self.frame.translation[2] + z, np.nan)
        assert self.surface is not None
        return self.frame.translation[2] + self.surface.height_at(lx, ly)


@dataclass(slots=True)
class PlacedWorld:
    world: World
    terrains: list[Terrain] = field(default_factory=list)
    spawn: tuple[float, ...] = (0.0, 0.0)  # X, Y or X, Y, Z (m)
    yaw: float = 0.0  # rad, about the world's z
    spawn_source: str = "origin"
    # Several copies of the robot (``--spawn`` given more than once): every copy's point, the first
    # being ``spawn``. Empty: one robot, at ``spawn``.
    copies: list[tuple[float, ...]] = field(default_factory=list)
    # Each cord field with its cords' anchor points (world frame), drawn once from its seed.
    cords: list[tuple[CordField, list[Vec3]]] = field(default_factory=list)
    resolution: float = DEFAULT_RESOLUTION
    # Where the heightfields' findings go: the grids are made only when a target asks (MJCF).
    findings: Findings = field(default_factory=Findings)
    _grids: list[TerrainGrid] | None = None

    @property
    def grids(self) -> list[TerrainGrid]:
        """The heightfield of every terrain, made on first use: only a target that writes heightfields
        (MJCF) pays for them (rough_25cm: 10,900 triangles, about 1 s); USD and SDF keep the mesh."""
        if self._grids is None:
            self._grids = [g for t in self.terrains if (g := _grid(t, self.resolution, self.findings)) is not None]
        return self._grids

    @property
    def points(self) -> list[tuple[float, ...]]:
        """Where each copy of the robot stands (one point for one robot)."""
        return self.copies or [self.spawn]

    def root_positions(self, robot: Robot, stance: Stance, floating: bool, *, grid: bool = False) -> list[Vec3]:
        """:meth:`root_position` of every copy: each on the ground under its own feet."""
        return [self.root_position(robot, stance, floating, at=point, grid=grid) for point in self.points]

    def grid_of(self, collider: WorldCollider) -> TerrainGrid | None:
        return next((g for g in self.grids if g.collider is collider), None)

    def probes(self, count: int = 16, *, grid: bool = False) -> list[Vec3]:
        """Points (x, y, ground z) for a reader to find the ground at: the spawn, and ``count``
        points drawn (seed 0) over each terrain, a cell inside its edges."""
        rng = np.random.default_rng(0)
        xs, ys = [self.spawn[0]], [self.spawn[1]]
        for terrain in self.terrains:
            made = self.grid_of(terrain.collider) if grid else None
            g = made.grid if made is not None else terrain.image
            if g is not None:
                w, h = g.size
                lo, hi = np.array([g.x0, g.y0]) + g.step, np.array([g.x0 + w, g.y0 + h]) - g.step
            else:
                assert terrain.points is not None
                lo, hi = terrain.points[:, :2].min(axis=0) + 0.01, terrain.points[:, :2].max(axis=0) - 0.01
            local = rng.uniform(lo, hi, size=(count, 2))
            r, t = terrain.frame.rotation, terrain.frame.translation
            xs += (r[0][0] * local[:, 0] + r[0][1] * local[:, 1] + t[0]).tolist()
            ys += (r[1][0] * local[:, 0] + r[1][1] * local[:, 1] + t[1]).tolist()
        z = self.ground_heights(np.array(xs), np.array(ys), grid=grid)
        return [(x, y, float(h)) for x, y, h in zip(xs, ys, z.tolist(), strict=True) if math.isfinite(h)]

    def ground_height(self, x: float, y: float, *, grid: bool = False) -> float | None:
        """The highest static surface under (x, y): terrains (their mesh, or with ``grid`` the
        heightfield a target writes), level boxes and level planes."""
        z = float(self.ground_heights(np.array([x]), np.array([y]), grid=grid)[0])
        return None if math.isnan(z) else z

    def ground_heights(self, x: Array, y: Array, *, grid: bool = False) -> Array:
        """:meth:`ground_height` at many points at once (NaN where there is no ground)."""
        x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
        best = np.full(np.broadcast(x, y).shape, -np.inf)
        for body in self.world.bodies:
            for collider in body.colliders:
                z = self._surface(body, collider, x, y, grid)
                if z is not None:
                    best = np.fmax(best, z)
        return np.where(np.isfinite(best), best, np.nan)

    def _surface(self, body: StaticBody, collider: WorldCollider, x: Array, y: Array, grid: bool) -> Array | None:
        terrain = next((t for t in self.terrains if t.collider is collider), None)
        if terrain is not None:
            made = self.grid_of(collider) if grid else None
            return terrain.heights(x, y, made.grid if made is not None else None)
        frame = pose_frame(body.pose) @ pose_frame(collider.origin)
        if not _level(frame):
            return None
        shape = collider.shape
        top = frame.translation[2]
        if isinstance(shape, Plane):
            if shape.normal[2] > 0 and abs(shape.normal[0]) + abs(shape.normal[1]) < 1e-12:
                return np.full(np.broadcast(x, y).shape, top)
            return None
        if isinstance(shape, Box):
            hx, hy, hz = (s / 2 for s in shape.size)
            lx, ly = _local_xy(frame, x, y)
            return np.where((np.abs(lx) <= hx) & (np.abs(ly) <= hy), top + hz, np.nan)
        return None

    def root_position(
        self, robot: Robot, stance: Stance, floating: bool, at: tuple[float, ...] | None = None, *, grid: bool = False
    ) -> Vec3:
        """Where the root goes: at the spawn X, Y (``at``, else the spawn; turned by the yaw), and
        high enough that every collider's lowest point clears the ground under it by CLEARANCE (a
        given Z wins). ``grid``: the ground as the target's heightfield has it (MJCF), not the mesh."""
        point = self.spawn if at is None else at
        x, y = point[0], point[1]
        if len(point) == 3:
            return (x, y, point[2])
        points = _low_points(robot, stance.positions)
        if not points:
            ground = self.ground_height(x, y, grid=grid)
            return (x, y, 0.0 if ground is None else ground)
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        need = -math.inf
        for px, py, pz in points:
            wx, wy = x + c * px - s * py, y + s * px + c * py
            ground = self.ground_height(wx, wy, grid=grid)
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
    """The world's terrains (their surfaces; heightfields at ``resolution`` m, default 2 cm, when a
    target asks) and the spawn point (``robot`` None: a world compiled alone, with no robot to place)."""
    resolution = resolution or DEFAULT_RESOLUTION
    if not (resolution > 0 and math.isfinite(resolution)):
        raise ConfigError(f"--terrain-resolution {resolution}: a positive number of metres")
    placed = PlacedWorld(world, resolution=resolution, findings=findings)
    for body in world.bodies:
        for collider in body.colliders:
            terrain = _terrain(body, collider, findings)
            if terrain is not None:
                placed.terrains.append(terrain)
    if robot is not None:
        _spawn(robot, world, spawn or (copies[0] if copies else None), placed)
        if len(placed.spawn) == 2 and placed.terrains and len(copies) <= 1:
            xy = (placed.spawn[0], placed.spawn[1])
            placed.spawn = level_spot(robot, placed.ground_heights, xy, placed.yaw, placed.spawn_source, findings)
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


def _terrain(body: StaticBody, collider: WorldCollider, findings: Findings) -> Terrain | None:
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

            return Terrain(body, collider, frame, image=read_height_image(shape.path, shape.size))
        points, triangles = _mesh_arrays(shape)
        return Terrain(body, collider, frame, TerrainSurface(points, triangles), None, points, triangles)
    except HeightfieldError as exc:
        _unreadable(exc, element, collider, findings)
        return None


def _unreadable(exc: HeightfieldError, element: str, collider: WorldCollider, findings: Findings) -> None:
    findings.warn(
        "world-terrain-unreadable",
        f"no heightfield: {exc}; MJCF collides its convex hull, USD and SDF keep the mesh",
        element=element,
        loc=collider.src,
        stage=STAGE,
    )


def _grid(terrain: Terrain, resolution: float, findings: Findings) -> TerrainGrid | None:
    collider, body = terrain.collider, terrain.body
    element = f"collision {collider.name!r} of {body.name!r}"
    try:
        if terrain.image is not None:
            grid = terrain.image
        else:
            assert terrain.points is not None and terrain.triangles is not None
            grid = rasterize(terrain.points, terrain.triangles, resolution)
    except HeightfieldError as exc:
        _unreadable(exc, element, collider, findings)
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
    return TerrainGrid(body, collider, grid, terrain.frame)


def _mesh_arrays(mesh: Mesh) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
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
    return points, triangles


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


def _local_xy(frame: Frame, x: Array, y: Array) -> tuple[Array, Array]:
    """World points (x, y, 0) in a level ``frame``: Rᵀ (p - t), its x and y (a level frame turns
    about z only, so the points' height does not enter them)."""
    r = frame.rotation
    dx, dy = (
        np.asarray(x, dtype=np.float64) - frame.translation[0],
        np.asarray(y, dtype=np.float64) - frame.translation[1],
    )
    return r[0][0] * dx + r[1][0] * dy, r[0][1] * dx + r[1][1] * dy


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
