"""Lowering for Isaac and Newton: a flat collision mesh becomes a thin box of its extent.

A mesh whose vertices lie in a plane (Stretch's ArUco marker plates, ``link_aruco_*``) has no convex
hull: PhysX cannot cook one, and Newton's MuJoCo backend refuses the file ("MuJoCo contact
generation does not support planar mesh collider"). The MJCF target already writes a box for such
a mesh (``mjcf-flat-mesh``); this pass does the same in the IR for the Isaac folder, so its USD and
its URDF carry the box: the extent of the mesh in its own frame, ``THICKNESS`` thick across the flat
axis, centred where the mesh is. Runs with ``isaac_limits`` (the Isaac preset). Each change is a
finding; a mesh that cannot be read is left as it is.
"""

from __future__ import annotations

import os

from robodesc.ir.geometry import Box, Mesh, Pose
from robodesc.ir.model import Robot
from robodesc.ir.rigid import apply, pose_frame, rotation_rpy
from robodesc.meshes.buffers import MeshReadError, flat_box
from robodesc.meshes.data import build_mesh
from robodesc.passes.context import PassContext

NAME = "flat_colliders"
THICKNESS = 1e-4  # m: the box across the flat axis (the MJCF target's 2 x 5e-5 m)


def flat_colliders(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    for link in robot.links:
        for collision in link.collisions:
            mesh = collision.geometry
            if not isinstance(mesh, Mesh) or mesh.path is None or not os.path.isfile(mesh.path):
                continue
            box = _flat_box(mesh)
            if box is None:
                continue
            size, centre = box
            frame = pose_frame(collision.origin)
            xyz = frame.translation
            moved = apply(frame.rotation, centre)
            collision.origin = Pose(
                xyz=(xyz[0] + moved[0], xyz[1] + moved[1], xyz[2] + moved[2]),
                rpy=rotation_rpy(frame.rotation) if collision.origin is not None else (0.0, 0.0, 0.0),
                src=collision.origin.src if collision.origin is not None else None,
            )
            collision.geometry = Box(size=size, src=mesh.src)
            ctx.warn(
                "flat-collider",
                f"collision mesh {mesh.uri!r} is flat (no convex hull: PhysX cannot cook it, Newton's MuJoCo "
                f"backend refuses it): a box of its extent, {THICKNESS:g} m thick, stands in for it",
                element=f"link {link.name!r}",
                loc=mesh.src,
            )
    return robot


def _flat_box(mesh: Mesh) -> tuple[tuple[float, float, float], tuple[float, float, float]] | None:
    """(size, centre in the mesh's frame) of the box for a flat mesh; None for a solid one."""
    assert mesh.path is not None
    try:
        data = build_mesh(mesh.path, mesh.scale)
    except (MeshReadError, OSError, ValueError):
        return None
    return flat_box(data, THICKNESS)
