"""The world a picture shows the robot in (``view`` and ``render`` with ``--world``, ``--terrain``,
``--spawn``): read and placed as a compile places it (emit/common/world.py), the robot's root on the
ground under its feet in the pose the picture draws (every joint at home)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot
from robodesc.ir.rigid import Frame, rpy_rotation

if TYPE_CHECKING:
    from robodesc.emit.common.world import PlacedWorld
    from robodesc.frontends.world.options import WorldOptions
    from robodesc.meshes.buffers import MeshData
    from robodesc.meshes.heightfield import HeightGrid


@dataclass(slots=True)
class ViewWorld:
    placed: PlacedWorld
    roots: list[Frame]  # the robot's root in the world, one per copy


def place_for_view(robot: Robot, options: WorldOptions, findings: Findings) -> ViewWorld | None:
    """The world the options name with ``robot`` placed in it; None when they name none."""
    if not options.given:
        return None
    from robodesc.emit.common.stance import Stance, complete
    from robodesc.emit.common.world import place_world
    from robodesc.frontends.world import load_world
    from robodesc.view.scene import home

    world = load_world(options, findings)
    if world is None:
        return None
    placed = place_world(
        robot, world, findings, resolution=options.terrain_resolution, spawn=options.spawn, copies=options.copies
    )
    pose = complete(robot, {j.name: home(j) for j in robot.joints if j.mimic is None and j.type.dof == 1})
    # Drawn standing on the ground (a welded robot where it is welded): no drop to show in a picture.
    floating = robot.root.name != "world" and robot.fixed_base is not True
    turn = rpy_rotation((0.0, 0.0, placed.yaw))
    roots = [
        Frame(rotation=turn, translation=root) for root in placed.root_positions(robot, Stance(pose, "home"), floating)
    ]
    return ViewWorld(placed, roots)


# The page draws a height image's grid with at most this many points a side (every k-th row and
# column): a 501 x 401 grid as triangles would make the page several megabytes for a picture.
PAGE_GRID = 256
GROUND_RGBA = (0.55, 0.6, 0.5, 1.0)


def world_page_data(world: ViewWorld, first_mesh: int) -> tuple[dict[str, Any], list[MeshData]]:
    """The world as the viewer page draws it: each copy's root pose, and the ground's shapes in the
    world frame (meshes by index into the page's mesh list, from ``first_mesh``); and the meshes."""
    from robodesc.ir.geometry import Mesh
    from robodesc.ir.rigid import pose_frame, rotation_rpy
    from robodesc.ir.world import HeightImage, Plane
    from robodesc.meshes.buffers import MeshReadError
    from robodesc.meshes.data import build_mesh
    from robodesc.view.scene import MeshTable, shape

    meshes: list[MeshData] = []
    ground: list[dict[str, Any]] = []
    placed = world.placed

    def pose(frame: Frame) -> dict[str, Any]:
        return {"xyz": list(frame.translation), "rpy": list(rotation_rpy(frame.rotation))}

    for body in placed.world.bodies:
        for collider in body.colliders:
            frame = pose_frame(body.pose) @ pose_frame(collider.origin)
            item: dict[str, Any] = {"rgba": list(GROUND_RGBA), "name": f"{body.name}/{collider.name}"}
            grid = placed.grid_of(collider)
            data: MeshData | None = None
            if isinstance(collider.shape, Mesh) and collider.shape.path is not None:
                try:
                    data = build_mesh(collider.shape.path, collider.shape.scale)
                except (MeshReadError, OSError):
                    data = None
            elif isinstance(collider.shape, HeightImage) and grid is not None:
                data, frame = grid_mesh(grid.grid), grid.frame
            if data is not None:
                ground.append({**item, "kind": "mesh", "mesh": first_mesh + len(meshes), **pose(frame)})
                meshes.append(data)
            elif isinstance(collider.shape, Plane):
                ground.append({**item, "kind": "box", "size": [40.0, 40.0, 0.001], **pose(frame)})
            elif not isinstance(collider.shape, Mesh | HeightImage):
                # A primitive, as the robot's are drawn (no mesh: the table stays empty).
                ground.append({**item, **shape(collider.shape, MeshTable()), **pose(frame)})
    return {
        "name": placed.world.name,
        "robots": [pose(root) for root in world.roots],
        "ground": ground,
    }, meshes


def grid_mesh(grid: HeightGrid) -> MeshData:
    """A heightfield's surface as triangles, two per cell (as MuJoCo interpolates), at most
    PAGE_GRID points a side."""
    from array import array

    import numpy as np

    from robodesc.meshes.buffers import MeshData

    k = max(1, -(-max(grid.z.shape) // PAGE_GRID))
    z = grid.z[::k, ::k]
    rows, cols = z.shape
    ys, xs = np.meshgrid(
        grid.y0 + np.arange(rows) * grid.step * k, grid.x0 + np.arange(cols) * grid.step * k, indexing="ij"
    )
    points = np.stack([xs, ys, z], axis=-1).reshape(-1, 3).astype(np.float32)
    i = np.arange(rows * cols).reshape(rows, cols)
    a, b, c, d = i[:-1, :-1], i[:-1, 1:], i[1:, :-1], i[1:, 1:]
    faces = np.concatenate([np.stack([a, b, d], -1), np.stack([a, d, c], -1)]).reshape(-1, 3).astype(np.int32)
    corner = points[faces]
    normals = np.cross(corner[:, 1] - corner[:, 0], corner[:, 2] - corner[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-12)
    lo, hi = points.min(axis=0), points.max(axis=0)
    return MeshData(
        points=array("f", points.ravel().tobytes()),
        face_vertex_counts=array("i", [3] * len(faces)),
        face_vertex_indices=array("i", faces.ravel().tobytes()),
        normals=array("f", normals.astype(np.float32).ravel().tobytes()),
        extent=(tuple(float(v) for v in lo), tuple(float(v) for v in hi)),  # type: ignore[arg-type]
    )
