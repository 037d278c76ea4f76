"""State threaded through the USD emitter's stages: the stage, which layer each kind of opinion goes
to, prim paths of links and joints, the mesh cache and the findings."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field

import numpy as np
from pxr import Gf, Sdf, Usd, UsdGeom

from robodesc.emit.usd_meshio import MeshCache
from robodesc.emit.usd_options import UsdOptions
from robodesc.ir.diagnostics import Findings, SourceLoc, UnsupportedError
from robodesc.ir.model import Robot
from robodesc.ir.transforms import Mat, matrix_to_quat_wxyz

STAGE = "emit:usd"

# Children of the robot prim that robodesc itself creates.
JOINTS_SCOPE = "joints"
LOOPS_SCOPE = "loop_joints"
LOOKS_SCOPE = "Looks"
RESERVED_ROBOT_CHILDREN = (JOINTS_SCOPE, LOOPS_SCOPE, LOOKS_SCOPE)
RESERVED_LINK_CHILDREN = ("visuals", "collisions")

# Layer roles (single-file output sends them all to one layer).
GEOMETRY = "geometry"
MATERIALS = "materials"
PHYSICS = "physics"


@dataclass
class UsdContext:
    robot: Robot
    options: UsdOptions
    stage: Usd.Stage
    findings: Findings
    # Folder of the layer(s) being written, for relative texture paths.
    layer_dir: str
    layers: dict[str, Sdf.Layer] = field(default_factory=dict)
    meshes: MeshCache = field(default_factory=MeshCache)
    robot_path: Sdf.Path = field(default_factory=lambda: Sdf.Path.emptyPath)
    link_paths: dict[str, Sdf.Path] = field(default_factory=dict)
    joint_paths: dict[str, Sdf.Path] = field(default_factory=dict)
    # World (robot-frame) pose of every link at q = 0.
    link_poses: dict[str, Mat] = field(default_factory=dict)

    @contextmanager
    def layer(self, role: str) -> Iterator[None]:
        target = self.layers.get(role)
        if target is None:
            yield
            return
        previous = self.stage.GetEditTarget()
        self.stage.SetEditTarget(Usd.EditTarget(target))
        try:
            yield
        finally:
            self.stage.SetEditTarget(previous)

    def warn(self, code: str, message: str, element: str = "", loc: SourceLoc | None = None) -> None:
        self.findings.warn(code, message, element=element, loc=loc, stage=STAGE)


def check_identifier(name: str, element: str, loc: SourceLoc | None) -> str:
    if not Sdf.Path.IsValidIdentifier(name):
        raise UnsupportedError(
            f"{name!r} is not a valid USD prim name (letters, digits and '_', not starting with a digit); "
            "run the sanitize_names pass before emitting USD (the robodesc pipeline does)",
            element=element,
            loc=loc,
        )
    return name


def unique_name(base: str, used: set[str], fallback: str) -> str:
    """A valid identifier for an optional IR name (visual, collision, material): ``base`` when it is
    one and still free, else ``fallback`` with a counter."""
    if base and Sdf.Path.IsValidIdentifier(base) and base not in used:
        used.add(base)
        return base
    stem = fallback
    index = 0
    while f"{stem}_{index}" in used:
        index += 1
    name = f"{stem}_{index}"
    used.add(name)
    return name


def set_display_name(prim: Usd.Prim, display_name: str | None) -> None:
    if display_name:
        prim.SetDisplayName(display_name)


def set_pose(xformable: UsdGeom.Xformable, m: Mat, scale: tuple[float, float, float] | None = None) -> None:
    """translate (double3) + orient (quatd) [+ scale (float3)]; identity parts are still written on
    bodies by callers that need a complete pose, elsewhere they are skipped.

    The orient is double precision: for a rotation under ~5e-4 rad a quatf's real part rounds to
    exactly 1, and usd-core (GfRotation takes the angle from acos(w)) then evaluates the identity."""
    t = m[:3, 3]
    if np.any(t):
        xformable.AddTranslateOp().Set(Gf.Vec3d(float(t[0]), float(t[1]), float(t[2])))
    w, x, y, z = matrix_to_quat_wxyz(m[:3, :3])
    if (w, x, y, z) != (1.0, 0.0, 0.0, 0.0):
        xformable.AddOrientOp(UsdGeom.XformOp.PrecisionDouble).Set(Gf.Quatd(w, x, y, z))
    if scale is not None:
        xformable.AddScaleOp().Set(Gf.Vec3f(*scale))


def set_full_pose(xformable: UsdGeom.Xformable, m: Mat) -> None:
    t = m[:3, 3]
    xformable.AddTranslateOp().Set(Gf.Vec3d(float(t[0]), float(t[1]), float(t[2])))
    w, x, y, z = matrix_to_quat_wxyz(m[:3, :3])
    xformable.AddOrientOp(UsdGeom.XformOp.PrecisionDouble).Set(Gf.Quatd(w, x, y, z))


def quatf(m: Mat) -> Gf.Quatf:
    w, x, y, z = matrix_to_quat_wxyz(m[:3, :3])
    return Gf.Quatf(w, x, y, z)


def apply_schema(prim: Usd.Prim, schema: str) -> None:
    """Apply an API schema by name: PhysX and Newton schemas are not registered in plain usd-core."""
    prim.AddAppliedSchema(schema)


def schema_attr(prim: Usd.Prim, name: str, type_name: Sdf.ValueTypeName, value: object) -> None:
    prim.CreateAttribute(name, type_name, custom=False).Set(value)
