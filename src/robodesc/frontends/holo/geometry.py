"""An object's shape: ``geometry`` (a primitive, a mesh file, or a HoloScript solid URDF lacks,
written as the closest primitive) sized by ``scale`` (or ``radius``/``height``/``size``)."""

from __future__ import annotations

import math

from robodesc.frontends.compose.solids import POLYHEDRA
from robodesc.frontends.holo.context import Lowering, Obj
from robodesc.frontends.holo.values import fail, num, string, vec3
from robodesc.ir.diagnostics import SourceLoc
from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Mesh, Pose, Sphere, Vec3

MESH_SUFFIXES = (".stl", ".obj", ".dae", ".glb", ".gltf", ".fbx", ".ply", ".usd", ".usda", ".usdc", ".usdz", ".3ds")
PRIMITIVES = ("box", "cube", "sphere", "cylinder", "cone", "capsule", "plane")
# HoloScript shapes URDF lacks, and the primitive each is written as (with a finding).
ROUND_SOLIDS = ("dodecahedron", "icosahedron", "octahedron", "tetrahedron", "icosphere", "geodesic")
RING_SOLIDS = ("torus", "ring", "disc", "disk", "tube")

Shape = tuple[Geometry | None, Pose | None, SourceLoc | None]


def geometry(ctx: Lowering, obj: Obj) -> Shape:
    """The object's geometry, the pose of the geometry in the link (or None), and where it was written."""
    label = obj.label
    if "geometry" not in obj.props:
        return None, None, None
    gval = obj.props["geometry"]
    kind = string(gval, "geometry", label)
    scale = _scale(ctx, obj)
    sx, sy, sz = scale
    lowered = kind.lower()
    if lowered.endswith(MESH_SUFFIXES) or "/" in kind or "://" in kind:
        return Mesh(uri=kind, scale=scale, src=gval.loc), None, gval.loc
    true_kind = lowered
    lowered = _primitive(ctx, kind, label, gval.loc)
    if lowered in ("box", "cube"):
        return Box(size=(sx, sy, sz), src=gval.loc), None, gval.loc
    if lowered == "sphere":
        if not (sx == sy == sz):
            ctx.note(
                "non-uniform-sphere",
                f"sphere scale {list(scale)} is not uniform: radius from the largest",
                label,
                gval.loc,
                warn=True,
            )
        if true_kind in POLYHEDRA:
            ctx.solids[obj.name] = (true_kind, max(scale) / 2.0, 0.0)
        return Sphere(radius=max(scale) / 2.0, src=gval.loc), None, gval.loc
    if lowered == "plane":
        ctx.note("plane-as-box", "plane read as a 1 mm thick box of its x and z extents", label, gval.loc, warn=True)
        return Box(size=(sx, sz, 0.001), src=gval.loc), None, gval.loc
    return _cylinder_like(ctx, obj, lowered, true_kind, scale, gval.loc)


def _primitive(ctx: Lowering, kind: str, label: str, loc: SourceLoc) -> str:
    """The primitive a shape is written as: itself, or a stand-in (with a finding)."""
    lowered = kind.lower()
    if lowered in ROUND_SOLIDS:
        ctx.note(
            "substituted-geometry",
            f"URDF has no {lowered}: written as the sphere of its scale (the closest primitive)"
            + ("; its inertia is the polyhedron's" if lowered in POLYHEDRA else ""),
            label,
            loc,
            warn=True,
        )
        return "sphere"
    if lowered in RING_SOLIDS:
        ctx.note(
            "substituted-geometry",
            f"URDF has no {lowered}: written as the cylinder of its extents (the closest primitive); "
            "its inertia is the solid torus's ([outer diameter, tube diameter, outer diameter])",
            label,
            loc,
            warn=True,
        )
        return "cylinder"
    if lowered not in PRIMITIVES:
        ctx.note(
            "substituted-geometry",
            f"geometry {kind!r} is no primitive robodesc knows ({', '.join(PRIMITIVES)}) and no mesh file: "
            "written as the box of its scale",
            label,
            loc,
            warn=True,
        )
        return "box"
    return lowered


def _cylinder_like(ctx: Lowering, obj: Obj, lowered: str, true_kind: str, scale: Vec3, loc: SourceLoc) -> Shape:
    """Cylinders, capsules, cones and rings: HoloScript's scale is [diameter, height, diameter]."""
    label = obj.label
    sx, sy, sz = scale
    up_rot = Pose(rpy=(-math.pi / 2, 0.0, 0.0)) if ctx.y_up else None
    if not ctx.cylinder_noted:
        ctx.cylinder_noted = True
        ctx.note(
            "cylinder-convention",
            "cylinder-like scale read as [diameter, height, diameter] with the height along the up axis",
            label,
            loc,
        )
    if sx != sz:
        ctx.note(
            "elliptic-cylinder",
            f"{lowered} scale {list(scale)} has different x and z diameters; the larger is used",
            label,
            loc,
            warn=True,
        )
    radius = max(sx, sz) / 2.0
    if lowered == "cone":
        ctx.note(
            "cone-as-cylinder",
            "URDF has no cone: written as a cylinder of the same extents; its inertia and centre of mass "
            "are the cone's (apex up, as three.js draws it)",
            label,
            loc,
            warn=True,
        )
        ctx.solids[obj.name] = ("cone", radius, sy)
    elif true_kind in RING_SOLIDS:
        tube = min(sy, radius) / 2.0
        ctx.solids[obj.name] = ("torus", radius - tube, tube)
    if lowered == "capsule":
        if sy < 2 * radius:
            raise fail(f"capsule height {sy:g} is less than its diameter {2 * radius:g}", label, loc)
        return Capsule(radius=radius, length=sy - 2 * radius, src=loc), up_rot, loc
    return Cylinder(radius=radius, length=sy, src=loc), up_rot, loc


def _scale(ctx: Lowering, obj: Obj) -> Vec3:
    label = obj.label
    if "scale" not in obj.props and any(k in obj.props for k in ("radius", "height", "length", "size")):
        return _scale_from_dimensions(ctx, obj)
    if "scale" not in obj.props:
        if "geometry" in obj.props:
            ctx.note("default-scale", "no scale: the unit primitive (1 m) is used", label, obj.props["geometry"].loc)
        return (1.0, 1.0, 1.0)
    value = obj.props["scale"]
    if isinstance(value.data, float):
        s = num(value, "scale", label)
        scale = (s, s, s)
    else:
        scale = vec3(value, "scale", label)
    if any(not c > 0 for c in scale):
        raise fail(f"scale must be positive, got {list(scale)}", label, value.loc)
    return scale


def _scale_from_dimensions(ctx: Lowering, obj: Obj) -> Vec3:
    """``radius``/``height``/``length``/``size`` instead of ``scale`` (HoloScript's Isaac Lab examples)."""
    label = obj.label
    p = obj.props
    if "size" in p:
        size = p["size"]
        if isinstance(size.data, float):
            s = num(size, "size", label)
            return (s, s, s)
        return vec3(size, "size", label)
    radius = num(p["radius"], "radius", label) if "radius" in p else None
    height = None
    for key in ("height", "length"):
        if key in p:
            height = num(p[key], key, label)
            break
    d = 2.0 * radius if radius is not None else (height or 1.0)
    h = height if height is not None else d
    ctx.note(
        "dimensions-as-scale",
        f"radius/height read as the scale [{d:g}, {h:g}, {d:g}] (diameter, height, diameter)",
        label,
        obj.block.loc,
    )
    return (d, h, d)
