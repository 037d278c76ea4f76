"""Joints under ``<robot>/joints`` and loop closures under ``<robot>/loop_joints``.

Frames: ``body0`` = parent link, ``localPos0/localRot0`` = the URDF joint origin in the parent;
``body1`` = child link with the identity frame. A URDF axis that is not +X, +Y or +Z turns both
local frames by the rotation taking +X onto it, and the joint's axis becomes X.
"""

from __future__ import annotations

import numpy as np
from pxr import Gf, Sdf, Usd, UsdPhysics

from robodesc.emit.usd_context import (
    JOINTS_SCOPE,
    LOOPS_SCOPE,
    PHYSICS,
    UsdContext,
    apply_schema,
    check_identifier,
    quatf,
    schema_attr,
    set_display_name,
)
from robodesc.emit.usd_math import DEG, PER_DEGREE, AxisFrame, axis_frame
from robodesc.ir.diagnostics import UnsupportedError
from robodesc.ir.model import Joint, JointType, LoopJoint
from robodesc.ir.rules import lookup
from robodesc.ir.transforms import Mat, pose_matrix

F = Sdf.ValueTypeNames.Float


def joint_axis_frame(joint: Joint) -> AxisFrame:
    if joint.type in (JointType.FIXED, JointType.FLOATING):
        return AxisFrame("X", None)
    try:
        return axis_frame(joint.effective_axis)
    except ValueError:
        raise UnsupportedError("joint axis has zero length", element=f"joint {joint.name!r}", loc=joint.src) from None


def emit_joint(ctx: UsdContext, joint: Joint) -> None:
    stage = ctx.stage
    path = ctx.joint_paths[joint.name]
    frame = joint_axis_frame(joint)
    with ctx.layer(PHYSICS):
        j = _define(stage, path, joint.type)
        set_display_name(j.GetPrim(), joint.display_name)
        j.CreateBody0Rel().SetTargets([ctx.link_paths[joint.parent]])
        j.CreateBody1Rel().SetTargets([ctx.link_paths[joint.child]])
        _frames(j, pose_matrix(joint.origin), np.eye(4), frame)
        if joint.type is JointType.PLANAR:
            prim = j.GetPrim()
            # Free: the two translations in the plane and the rotation about its normal.
            locked = [f"trans{frame.token}"] + [f"rot{a}" for a in "XYZ" if a != frame.token]
            for dof in locked:
                limit = UsdPhysics.LimitAPI.Apply(prim, dof)
                limit.CreateLowAttr(1.0)
                limit.CreateHighAttr(-1.0)
        elif joint.type is JointType.SPHERICAL:
            UsdPhysics.SphericalJoint(j.GetPrim()).CreateAxisAttr(frame.token)
        if joint.type.dof == 1:
            _one_dof(ctx, joint, j.GetPrim(), frame)


def _define(stage: Usd.Stage, path: Sdf.Path, jtype: JointType) -> UsdPhysics.Joint:
    if jtype in (JointType.REVOLUTE, JointType.CONTINUOUS):
        return UsdPhysics.RevoluteJoint.Define(stage, path)
    if jtype is JointType.PRISMATIC:
        return UsdPhysics.PrismaticJoint.Define(stage, path)
    if jtype is JointType.FIXED:
        return UsdPhysics.FixedJoint.Define(stage, path)
    if jtype is JointType.SPHERICAL:
        return UsdPhysics.SphericalJoint.Define(stage, path)
    # Floating and planar: a generic (D6) joint; free unless a LimitAPI locks a degree of freedom.
    return UsdPhysics.Joint.Define(stage, path)


def _frames(j: UsdPhysics.Joint, frame0: Mat, frame1: Mat, axis: AxisFrame) -> None:
    r0, r1 = frame0.copy(), frame1.copy()
    if axis.rotation is not None:
        r0[:3, :3] = frame0[:3, :3] @ axis.rotation
        r1[:3, :3] = frame1[:3, :3] @ axis.rotation
    t0, t1 = frame0[:3, 3], frame1[:3, 3]
    j.CreateLocalPos0Attr(Gf.Vec3f(float(t0[0]), float(t0[1]), float(t0[2])))
    j.CreateLocalRot0Attr(quatf(r0))
    j.CreateLocalPos1Attr(Gf.Vec3f(float(t1[0]), float(t1[1]), float(t1[2])))
    j.CreateLocalRot1Attr(quatf(r1))


def _one_dof(ctx: UsdContext, joint: Joint, prim: Usd.Prim, frame: AxisFrame) -> None:
    angular = joint.type.is_angular
    unit = DEG if angular else 1.0
    label = f"joint {joint.name!r}"
    typed = UsdPhysics.RevoluteJoint(prim) if angular else UsdPhysics.PrismaticJoint(prim)
    typed.CreateAxisAttr(frame.token)
    limit = joint.limit
    lower = limit.lower if limit is not None and joint.type is not JointType.CONTINUOUS else None
    upper = limit.upper if limit is not None and joint.type is not JointType.CONTINUOUS else None
    if lower is not None and upper is not None:
        typed.CreateLowerLimitAttr(lower * unit)
        typed.CreateUpperLimitAttr(upper * unit)
    elif joint.type is not JointType.CONTINUOUS:
        ctx.warn("usd-no-limit", "joint has no lower/upper limit: written without limits", label, joint.src)
    # Start at 0 when the range allows it, else at the nearer bound.
    start = 0.0
    if lower is not None and upper is not None:
        start = min(max(0.0, lower), upper)
    kind = "angular" if angular else "linear"
    # PhysicsJointStateAPI is not in usd-core's UsdPhysics module: apply it by name.
    apply_schema(prim, f"PhysicsJointStateAPI:{kind}")
    schema_attr(prim, f"state:{kind}:physics:position", F, start * unit)
    schema_attr(prim, f"state:{kind}:physics:velocity", F, 0.0)
    if joint.mimic is None:
        _drive(ctx, joint, prim, kind, start)
    else:
        _mimic(ctx, joint, prim, frame)
    _extras(joint, prim, unit)


def _drive(ctx: UsdContext, joint: Joint, prim: Usd.Prim, kind: str, start: float) -> None:
    options = ctx.options
    angular = kind == "angular"
    per = PER_DEGREE if angular else 1.0
    unit = DEG if angular else 1.0
    dyn = joint.dynamics
    target_position: float | None = None
    target_velocity: float | None = None
    if options.target_type == "position":
        stiffness = _gain(ctx, options.stiffness, joint, "stiffness")
        damping = _gain(ctx, options.damping, joint, "damping")
        target_position = start
    elif options.target_type == "velocity":
        stiffness = 0.0
        damping = _gain(ctx, options.damping, joint, "damping")
        target_velocity = 0.0
    else:
        # No target: only the URDF's passive spring and damping act through the drive.
        stiffness = dyn.spring_stiffness if dyn is not None and dyn.spring_stiffness is not None else 0.0
        damping = dyn.damping if dyn is not None and dyn.damping is not None else 0.0
        if dyn is not None and dyn.spring_reference is not None:
            target_position = dyn.spring_reference
    drive = UsdPhysics.DriveAPI.Apply(prim, kind)
    drive.CreateTypeAttr(options.drive_type)
    drive.CreateStiffnessAttr(stiffness * per)
    drive.CreateDampingAttr(damping * per)
    if joint.limit is not None and joint.limit.effort is not None and joint.limit.effort > 0:
        drive.CreateMaxForceAttr(joint.limit.effort)
    if target_position is not None:
        drive.CreateTargetPositionAttr(target_position * unit)
    if target_velocity is not None:
        drive.CreateTargetVelocityAttr(target_velocity * unit)


def _gain(ctx: UsdContext, gain: object, joint: Joint, what: str) -> float:
    value = lookup(gain, joint.name, what)  # type: ignore[arg-type]
    if value is None:
        ctx.warn(
            "usd-no-gain",
            f"no {what} pattern matches this joint: 0 written",
            f"joint {joint.name!r}",
            joint.src,
        )
        return 0.0
    return value


def _mimic(ctx: UsdContext, joint: Joint, prim: Usd.Prim, frame: AxisFrame) -> None:
    mimic = joint.mimic
    assert mimic is not None
    label = f"joint {joint.name!r}"
    leader_path = ctx.joint_paths.get(mimic.joint)
    leader = ctx.robot.joint_map().get(mimic.joint)
    if leader_path is None or leader is None or leader.type.dof != 1:
        ctx.warn(
            "usd-bad-mimic", f"mimic leader {mimic.joint!r} is not a one-DOF joint: mimic left out", label, mimic.src
        )
        return
    multiplier = mimic.multiplier if mimic.multiplier is not None else 1.0
    offset = mimic.offset if mimic.offset is not None else 0.0
    unit = DEG if joint.type.is_angular else 1.0
    apply_schema(prim, "NewtonMimicAPI")
    prim.CreateRelationship("newton:mimicJoint", custom=False).SetTargets([leader_path])
    schema_attr(prim, "newton:mimicCoef0", F, offset * unit)
    schema_attr(prim, "newton:mimicCoef1", F, multiplier)
    # PhysX: q + gearing * q_ref + offset = 0, offset in PhysX's internal units (rad or m).
    instance = f"rot{frame.token}"
    apply_schema(prim, f"PhysxMimicJointAPI:{instance}")
    base = f"physxMimicJoint:{instance}"
    prim.CreateRelationship(f"{base}:referenceJoint", custom=False).SetTargets([leader_path])
    leader_token = joint_axis_frame(leader).token
    schema_attr(prim, f"{base}:referenceJointAxis", Sdf.ValueTypeNames.Token, f"rot{leader_token}")
    schema_attr(prim, f"{base}:gearing", F, -multiplier)
    schema_attr(prim, f"{base}:offset", F, -offset)
    if joint.type is JointType.CONTINUOUS:
        ctx.warn(
            "usd-mimic-unlimited",
            "PhysX mimic joints need a finite limit on a revolute follower; this one is continuous",
            label,
            mimic.src,
        )


def _extras(joint: Joint, prim: Usd.Prim, unit: float) -> None:
    armature = joint.armature
    velocity = joint.limit.velocity if joint.limit is not None else None
    dyn = joint.dynamics
    friction = dyn.friction if dyn is not None else None
    damping = dyn.damping if dyn is not None else None
    if armature is None and velocity is None and friction is None and damping is None:
        return
    if armature is not None or velocity is not None or friction is not None:
        apply_schema(prim, "PhysxJointAPI")
        if armature is not None:
            schema_attr(prim, "physxJoint:armature", F, armature)
        if velocity is not None:
            schema_attr(prim, "physxJoint:maxJointVelocity", F, velocity * unit)
        if friction is not None:
            schema_attr(prim, "physxJoint:jointFriction", F, friction)
    apply_schema(prim, "NewtonJointAPI")
    if armature is not None:
        schema_attr(prim, "newton:armature", F, armature)
    if velocity is not None:
        schema_attr(prim, "newton:maxJointVelocity", F, velocity * unit)
    if friction is not None:
        schema_attr(prim, "newton:friction", F, friction)
    if damping is not None:
        schema_attr(prim, "newton:damping", F, damping)


def emit_loop_joint(ctx: UsdContext, loop: LoopJoint, path: Sdf.Path) -> None:
    label = f"loop_joint {loop.name!r}"
    for side in (loop.link1, loop.link2):
        if side.link not in ctx.link_paths:
            raise UnsupportedError(f"refers to unknown link {side.link!r}", element=label, loc=loop.src)
    kind = loop.type.lower()
    jtype = {
        "spherical": JointType.SPHERICAL,
        "revolute": JointType.REVOLUTE,
        "continuous": JointType.CONTINUOUS,
        "prismatic": JointType.PRISMATIC,
        "fixed": JointType.FIXED,
    }.get(kind)
    if jtype is None:
        raise UnsupportedError(
            f"loop joint type {loop.type!r} has no UsdPhysics equivalent", element=label, loc=loop.src
        )
    frame = AxisFrame("X", None)
    if jtype in (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC):
        try:
            frame = axis_frame(loop.axis or (1.0, 0.0, 0.0))
        except ValueError:
            raise UnsupportedError("loop joint axis has zero length", element=label, loc=loop.src) from None
    with ctx.layer(PHYSICS):
        j = _define(ctx.stage, path, jtype)
        set_display_name(j.GetPrim(), loop.display_name)
        j.CreateBody0Rel().SetTargets([ctx.link_paths[loop.link1.link]])
        j.CreateBody1Rel().SetTargets([ctx.link_paths[loop.link2.link]])
        _frames(j, pose_matrix(loop.link1.origin), pose_matrix(loop.link2.origin), frame)
        j.CreateExcludeFromArticulationAttr(True)
        if jtype in (JointType.REVOLUTE, JointType.CONTINUOUS):
            UsdPhysics.RevoluteJoint(j.GetPrim()).CreateAxisAttr(frame.token)
        elif jtype is JointType.PRISMATIC:
            UsdPhysics.PrismaticJoint(j.GetPrim()).CreateAxisAttr(frame.token)
        elif jtype is JointType.SPHERICAL:
            UsdPhysics.SphericalJoint(j.GetPrim()).CreateAxisAttr(frame.token)


def loop_scope_paths(ctx: UsdContext) -> dict[str, Sdf.Path]:
    scope = ctx.robot_path.AppendChild(LOOPS_SCOPE)
    out: dict[str, Sdf.Path] = {}
    for loop in ctx.robot.loop_joints:
        name = check_identifier(loop.name, f"loop_joint {loop.name!r}", loop.src)
        if name in out:
            raise UnsupportedError("two loop joints share this name", element=f"loop_joint {name!r}", loc=loop.src)
        out[name] = scope.AppendChild(name)
    return out


def joint_scope(ctx: UsdContext) -> Sdf.Path:
    return ctx.robot_path.AppendChild(JOINTS_SCOPE)
