"""Rigid bodies, the articulation root and the optional physics scene."""

from __future__ import annotations

from pxr import Gf, Sdf, UsdGeom, UsdPhysics

from robodesc.emit.usd_context import (
    GEOMETRY,
    JOINTS_SCOPE,
    PHYSICS,
    UsdContext,
    apply_schema,
    schema_attr,
    set_display_name,
    set_full_pose,
)
from robodesc.emit.usd_math import mass_properties
from robodesc.ir.model import Link


def emit_body(ctx: UsdContext, link: Link) -> None:
    path = ctx.link_paths[link.name]
    label = f"link {link.name!r}"
    with ctx.layer(GEOMETRY):
        xform = UsdGeom.Xform.Define(ctx.stage, path)
        set_full_pose(xform, ctx.link_poses[link.name])
        set_display_name(xform.GetPrim(), link.display_name)
    with ctx.layer(PHYSICS):
        prim = ctx.stage.OverridePrim(path)
        UsdPhysics.RigidBodyAPI.Apply(prim)
        inertial = link.inertial
        if inertial is None or inertial.mass is None:
            ctx.warn(
                "usd-no-mass",
                "link has no mass: the simulator derives one from the colliders (PhysX: 1 kg without any)",
                label,
                link.src,
            )
            return
        props = mass_properties(inertial)
        if props.problem is not None:
            ctx.warn(
                "usd-bad-inertia",
                f"{props.problem}; written as is (PhysX treats a zero diagonal as 'compute from the colliders'); "
                "the repair_inertia pass fixes it",
                label,
                inertial.src,
            )
        mass = UsdPhysics.MassAPI.Apply(prim)
        mass.CreateMassAttr(props.mass)
        mass.CreateCenterOfMassAttr(Gf.Vec3f(*props.center_of_mass))
        mass.CreateDiagonalInertiaAttr(Gf.Vec3f(*props.diagonal_inertia))
        w, x, y, z = props.principal_axes
        mass.CreatePrincipalAxesAttr(Gf.Quatf(w, x, y, z))


def emit_articulation(ctx: UsdContext, root: Link) -> None:
    """Fixed base: a ``root_joint`` welding the root link to the world and the root API on the robot
    prim (on the root body it would make PhysX float the base). Floating: the root API on the root
    link."""
    options = ctx.options
    with ctx.layer(PHYSICS):
        if options.fix_base:
            taken = set(ctx.joint_paths)
            name = "root_joint"
            if name in taken:
                index = 0
                while f"{name}_{index}" in taken:
                    index += 1
                name = f"{name}_{index}"
                ctx.warn("usd-root-joint-name", f"a joint is already called 'root_joint'; the base weld is {name!r}")
            joint = UsdPhysics.FixedJoint.Define(ctx.stage, ctx.robot_path.AppendChild(JOINTS_SCOPE).AppendChild(name))
            joint.CreateBody1Rel().SetTargets([ctx.link_paths[root.name]])
            target = ctx.stage.GetPrimAtPath(ctx.robot_path)
        else:
            target = ctx.stage.OverridePrim(ctx.link_paths[root.name])
        UsdPhysics.ArticulationRootAPI.Apply(target)
        apply_schema(target, "PhysxArticulationAPI")
        schema_attr(target, "physxArticulation:enabledSelfCollisions", Sdf.ValueTypeNames.Bool, options.self_collision)
        if options.solver_position_iterations is not None:
            schema_attr(
                target,
                "physxArticulation:solverPositionIterationCount",
                Sdf.ValueTypeNames.Int,
                options.solver_position_iterations,
            )
        if options.solver_velocity_iterations is not None:
            schema_attr(
                target,
                "physxArticulation:solverVelocityIterationCount",
                Sdf.ValueTypeNames.Int,
                options.solver_velocity_iterations,
            )
        apply_schema(target, "NewtonArticulationRootAPI")
        schema_attr(target, "newton:selfCollisionEnabled", Sdf.ValueTypeNames.Bool, options.self_collision)


def emit_physics_scene(ctx: UsdContext) -> None:
    with ctx.layer(PHYSICS):
        scene = UsdPhysics.Scene.Define(ctx.stage, Sdf.Path("/PhysicsScene"))
        scene.CreateGravityDirectionAttr(Gf.Vec3f(0.0, 0.0, -1.0))
        scene.CreateGravityMagnitudeAttr(9.81)
