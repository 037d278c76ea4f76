"""Lowering an object to a builder link (its shape, look, mass, and the inertia of stand-in solids),
or to a :class:`HoloProp` when it is no part of the robot."""

from __future__ import annotations

import os

from robodesc.frontends.compose.builder import Part, RobotBuilder
from robodesc.frontends.compose.meshes import resolve_mesh
from robodesc.frontends.compose.solids import cone, polyhedron, torus
from robodesc.frontends.holo.context import HoloProp, Lowering, Obj
from robodesc.frontends.holo.geometry import geometry
from robodesc.frontends.holo.mass import contact, mass
from robodesc.frontends.holo.materials import color, material
from robodesc.frontends.holo.values import fail
from robodesc.frontends.options import MissingMesh
from robodesc.frontends.packages import PackageResolver
from robodesc.ir.diagnostics import SourceLoc
from robodesc.ir.geometry import Geometry, Inertia, Mesh, Pose
from robodesc.ir.transforms import matrix_pose, pose_matrix

# HoloScript's URDF compiler gives every body without a mass this many kilograms.
HOLOSCRIPT_DEFAULT_MASS = 1.0


def lower_link(ctx: Lowering, builder: RobotBuilder, obj: Obj, *, moves: bool = False, floats: bool = False) -> None:
    """Add the object's link; ``moves`` when a movable joint lies between it and the base, ``floats``
    when it is the base of a robot that is not fixed to the world."""
    label = obj.label
    geom, origin, geom_loc = geometry(ctx, obj)
    parts: list[Part] = []
    rgba = color(ctx, obj)
    mat = material(ctx, obj)
    if geom is not None:
        collision = obj.trait("collidable") is not None
        parts.append(Part(geometry=geom, origin=origin, color=rgba, material=mat, collision=collision, src=geom_loc))
    else:
        ctx.note("no-geometry", "object has no geometry: a link without visuals", label, obj.block.loc)
    kg, inertia = mass(obj)
    dropped = False
    if geom is None and inertia is None and kg is not None:
        if moves or floats:
            # A moving body keeps the mass its author gave, with the inertia HoloScript's own URDF
            # compiler gives a body without a shape (a 1 m cube of that mass): dropping it would
            # leave the 1 kg default in its place.
            inertia = Inertia(kg / 6.0, kg / 6.0, kg / 6.0, src=obj.block.loc)
            what = "the inertia of a 1 m cube of that mass (HoloScript's rule)"
        else:
            dropped = True
            what = "no inertia can be computed, the link gets no inertial"
        ctx.note(
            "mass-without-shape",
            f"mass {kg:g} kg without a shape or an inertia tensor: {what}",
            label,
            obj.block.loc,
            warn=True,
        )
        kg = None if dropped else kg
    com: Pose | None = None
    solid = ctx.solids.get(obj.name)
    if solid is not None and kg is not None and inertia is None:
        inertia, com = _solid_inertia(solid, kg, origin, geom_loc, label)
    if kg is None and moves:
        kg, inertia = _default_mass(ctx, obj, geom, inertia)
    if kg is None and not dropped:  # a dropped mass has had its own warning
        ctx.note(
            "no-mass",
            "object has no mass (mass, @physics { mass } or physics: { mass })",
            label,
            obj.block.loc,
            warn=True,
        )
    builder.link(
        obj.name,
        *parts,
        mass=kg,
        inertia=inertia,
        com=com,
        pose=matrix_pose(obj.world),
        frame="world",
        element=label,
        src=obj.block.name_loc,
        contact=contact(obj),
    )


def _solid_inertia(
    solid: tuple[str, float, float], kg: float, origin: Pose | None, loc: SourceLoc | None, label: str
) -> tuple[Inertia, Pose]:
    """The inertia and centre of mass of the solid a stand-in primitive draws (cone, torus, polyhedron)."""
    kind, a, b = solid
    try:
        props = cone(kg, a, b) if kind == "cone" else torus(kg, a, b) if kind == "torus" else polyhedron(kind, kg, a)
    except OverflowError:
        # Finite sizes whose squares leave the float range (a 1e308 m torus): no inertia to write.
        raise fail(
            f"the inertia of its {kind} ({max(a, b):g} m, {kg:g} kg) is beyond the float range", label, loc
        ) from None
    inertia = Inertia(*props.inertia, src=loc)
    com = matrix_pose(pose_matrix(origin or Pose()) @ pose_matrix(Pose(xyz=(0.0, 0.0, props.com_z))))
    return inertia, com


def _default_mass(
    ctx: Lowering, obj: Obj, geom: Geometry | None, inertia: Inertia | None
) -> tuple[float, Inertia | None]:
    # A body that moves needs a mass in every simulator. HoloScript's own URDF compiler gives
    # 1 kg (and, without a shape, the inertia of a 1 m cube); robodesc does the same, and says so.
    kg = HOLOSCRIPT_DEFAULT_MASS
    if geom is None:
        inertia = Inertia(kg / 6.0, kg / 6.0, kg / 6.0, src=obj.block.loc)
    ctx.note(
        "default-mass",
        f"moving object has no mass: {kg:g} kg, HoloScript's default"
        + (", with the inertia of a 1 m cube (it has no shape)" if geom is None else ""),
        obj.label,
        obj.block.loc,
        warn=True,
    )
    return kg, inertia


def lower_prop(ctx: Lowering, obj: Obj, kind: str) -> HoloProp:
    """The object as a prop (``kind`` "grabbable" or "static"); a missing mesh is at most a warning."""
    geom, _, geom_loc = geometry(ctx, obj)
    if isinstance(geom, Mesh):
        resolver = PackageResolver(explicit=dict(ctx.options.package_paths), input_file=ctx.file)
        policy = ctx.options.missing_mesh
        geom = resolve_mesh(
            geom,
            element=obj.label,
            loc=geom_loc,
            base_dir=os.path.dirname(os.path.abspath(ctx.file)),
            resolver=resolver,
            policy=MissingMesh.WARN if policy is MissingMesh.ERROR else policy,
            findings=ctx.findings,
        )
    kg, _ = mass(obj)
    return HoloProp(obj.name, kind, geom, matrix_pose(obj.world), kg, color(ctx, obj), obj.block.loc)
