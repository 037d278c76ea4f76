"""Rigid bodies, the articulation root and the optional physics scene."""

from __future__ import annotations

from robodesc.emit.usd.context import GEOMETRY, JOINTS_SCOPE, PHYSICS, UsdContext, set_display_name, set_full_pose
from robodesc.emit.usd.quantities import float32_moments, mass_properties
from robodesc.ir.model import Link
from robodesc.usdfile.spec import Layer


def emit_body(ctx: UsdContext, link: Link) -> None:
    path = ctx.link_paths[link.name]
    label = f"link {link.name!r}"
    xform = ctx.define(GEOMETRY, path, "Xform")
    set_full_pose(xform, ctx.link_poses[link.name])
    set_display_name(xform, link.display_name)
    prim = ctx.over(PHYSICS, path)
    prim.apply("PhysicsRigidBodyAPI")
    if link.contact is not None and link.contact.max_vel is not None:
        # ODE's maxVel: the fastest a contact may push the body out of penetration.
        prim.apply("PhysxRigidBodyAPI")
        prim.attr("physxRigidBody:maxDepenetrationVelocity", "float", link.contact.max_vel)
    inertial = link.inertial
    if inertial is None or inertial.mass is None:
        # The target's massless pass gives every link a mass; only an IR emitted around it gets here.
        ctx.warn(
            "usd-no-mass",
            "link has no mass: every UsdPhysics reader derives one from the colliders (PhysX: 1 kg without "
            "any); the massless pass (placeholder_masses) gives it one that keeps the robot's total",
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
    prim.apply("PhysicsMassAPI")
    prim.attr("physics:mass", "float", props.mass)
    prim.attr("physics:centerOfMass", "point3f", props.center_of_mass)
    if not any(props.diagonal_inertia):
        # A zero tensor is UsdPhysics' fallback ("compute it"); NVIDIA's SimReady MassChecker accepts
        # it only with a zero principalAxes too, so neither is authored: consumers read the same.
        return
    prim.attr("physics:diagonalInertia", "float3", float32_moments(props.diagonal_inertia))
    prim.attr("physics:principalAxes", "quatf", props.principal_axes)


def emit_articulation(ctx: UsdContext, root: Link) -> None:
    """Fixed base: a ``root_joint`` welding the root link to the world and the root API on the robot
    prim (on the root body it would make PhysX float the base). Floating: the root API on the root
    link."""
    options = ctx.options
    if options.fix_base:
        taken = set(ctx.joint_paths)
        name = "root_joint"
        if name in taken:
            index = 0
            while f"{name}_{index}" in taken:
                index += 1
            name = f"{name}_{index}"
            ctx.warn("usd-root-joint-name", f"a joint is already called 'root_joint'; the base weld is {name!r}")
        joint = ctx.define(PHYSICS, f"{ctx.robot_path}/{JOINTS_SCOPE}/{name}", "PhysicsFixedJoint")
        joint.rel("physics:body1", [ctx.link_paths[root.name]])
        target = ctx.over(PHYSICS, ctx.robot_path)
    else:
        target = ctx.over(PHYSICS, ctx.link_paths[root.name])
    target.apply("PhysicsArticulationRootAPI")
    target.apply("PhysxArticulationAPI")
    target.attr("physxArticulation:enabledSelfCollisions", "bool", options.self_collision)
    if options.solver_position_iterations is not None:
        target.attr("physxArticulation:solverPositionIterationCount", "int", options.solver_position_iterations)
    if options.solver_velocity_iterations is not None:
        target.attr("physxArticulation:solverVelocityIterationCount", "int", options.solver_velocity_iterations)
    target.apply("NewtonArticulationRootAPI")
    target.attr("newton:selfCollisionEnabled", "bool", options.self_collision)


def emit_robot_schema(ctx: UsdContext) -> None:
    """Isaac Sim's robot schema (``isaacsim-robot-schema`` 6.2): ``IsaacRobotAPI`` on the robot prim
    listing its links and joints in IR order, ``IsaacLinkAPI`` / ``IsaacJointAPI`` on each. Isaac
    Sim 6.2's URDF importer applies the same APIs (it leaves both lists empty)."""
    robot = ctx.over(PHYSICS, ctx.robot_path)
    robot.apply("IsaacRobotAPI")
    robot.rel("isaac:physics:robotLinks", list(ctx.link_paths.values()))
    robot.rel("isaac:physics:robotJoints", list(ctx.joint_paths.values()))
    for path in ctx.link_paths.values():
        ctx.over(PHYSICS, path).apply("IsaacLinkAPI")
    for path in ctx.joint_paths.values():
        ctx.over(PHYSICS, path).apply("IsaacJointAPI")


def emit_physics_scene(layer: Layer) -> None:
    scene = layer.prim("/PhysicsScene", "PhysicsScene")
    scene.attr("physics:gravityDirection", "vector3f", (0.0, 0.0, -1.0))
    scene.attr("physics:gravityMagnitude", "float", 9.81)
