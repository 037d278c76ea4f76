"""Joints under ``<robot>/joints`` and loop closures under ``<robot>/loop_joints``.

Frames: ``body0`` = parent link, ``localPos0/localRot0`` = the URDF joint origin in the parent;
``body1`` = child link with the identity frame. A URDF axis that is not +X, +Y or +Z turns both
local frames by the rotation taking +X onto it, and the joint's axis becomes X.
"""

from __future__ import annotations

from robodesc.emit.usd.context import (
    LOOPS_SCOPE,
    PHYSICS,
    UsdContext,
    check_identifier,
    set_display_name,
)
from robodesc.emit.usd.options import ISAAC_WITHOUT_JOINT_AXIS, LEGACY_JOINT_API
from robodesc.emit.usd.quantities import DEG, PER_DEGREE, AxisFrame, axis_frame
from robodesc.ir.diagnostics import UnsupportedError
from robodesc.ir.model import Joint, JointType, LoopJoint
from robodesc.ir.rigid import Frame, pose_frame
from robodesc.ir.rules import lookup
from robodesc.usdfile.spec import Prim

_TYPE_NAMES = {
    JointType.REVOLUTE: "PhysicsRevoluteJoint",
    JointType.CONTINUOUS: "PhysicsRevoluteJoint",
    JointType.PRISMATIC: "PhysicsPrismaticJoint",
    JointType.FIXED: "PhysicsFixedJoint",
    JointType.SPHERICAL: "PhysicsSphericalJoint",
    # Floating and planar: a generic (D6) joint; free unless a LimitAPI locks a degree of freedom.
    JointType.FLOATING: "PhysicsJoint",
    JointType.PLANAR: "PhysicsJoint",
}


def joint_axis_frame(joint: Joint) -> AxisFrame:
    if joint.type in (JointType.FIXED, JointType.FLOATING):
        return AxisFrame("X", None)
    try:
        return axis_frame(joint.effective_axis)
    except ValueError:
        raise UnsupportedError("joint axis has zero length", element=f"joint {joint.name!r}", loc=joint.src) from None


def emit_joint(ctx: UsdContext, joint: Joint) -> None:
    frame = joint_axis_frame(joint)
    prim = ctx.define(PHYSICS, ctx.joint_paths[joint.name], _TYPE_NAMES[joint.type])
    set_display_name(prim, joint.display_name)
    prim.rel("physics:body0", [ctx.link_paths[joint.parent]])
    prim.rel("physics:body1", [ctx.link_paths[joint.child]])
    _frames(prim, pose_frame(joint.origin), Frame(), frame)
    if joint.type is JointType.PLANAR:
        # Free: the two translations in the plane and the rotation about its normal.
        locked = [f"trans{frame.token}"] + [f"rot{a}" for a in "XYZ" if a != frame.token]
        for dof in locked:
            prim.apply(f"PhysicsLimitAPI:{dof}")
            prim.attr(f"limit:{dof}:physics:low", "float", 1.0)
            prim.attr(f"limit:{dof}:physics:high", "float", -1.0)
    elif joint.type is JointType.SPHERICAL:
        prim.attr("physics:axis", "token", frame.token, uniform=True)
    if joint.type.dof == 1:
        _one_dof(ctx, joint, prim, frame)


def _frames(prim: Prim, frame0: Frame, frame1: Frame, axis: AxisFrame) -> None:
    if axis.rotation is not None:
        frame0, frame1 = frame0.rotated(axis.rotation), frame1.rotated(axis.rotation)
    prim.attr("physics:localPos0", "point3f", frame0.translation)
    prim.attr("physics:localRot0", "quatf", frame0.quat())
    prim.attr("physics:localPos1", "point3f", frame1.translation)
    prim.attr("physics:localRot1", "quatf", frame1.quat())


def _one_dof(ctx: UsdContext, joint: Joint, prim: Prim, frame: AxisFrame) -> None:
    angular = joint.type.is_angular
    unit = DEG if angular else 1.0
    label = f"joint {joint.name!r}"
    prim.attr("physics:axis", "token", frame.token, uniform=True)
    limit = joint.limit
    lower = limit.lower if limit is not None and joint.type is not JointType.CONTINUOUS else None
    upper = limit.upper if limit is not None and joint.type is not JointType.CONTINUOUS else None
    if lower is not None and upper is not None:
        prim.attr("physics:lowerLimit", "float", lower * unit)
        prim.attr("physics:upperLimit", "float", upper * unit)
    elif joint.type is not JointType.CONTINUOUS:
        ctx.warn("usd-no-limit", "joint has no lower/upper limit: written without limits", label, joint.src)
    # Start at the given position (0 by default) when the range allows it, else at the nearer bound.
    initial = ctx.options.initial_positions
    start = initial.get(joint.name, 0.0) if initial else 0.0
    mimic = joint.mimic
    if initial and mimic is not None and joint.name not in initial and mimic.joint in initial:
        # A follower starts where its leader's start puts it: PhysX's mimic constraint would
        # otherwise begin violated and yank both (docs/usd.md).
        multiplier = 1.0 if mimic.multiplier is None else mimic.multiplier
        start = multiplier * initial[mimic.joint] + (mimic.offset or 0.0)
    if lower is not None and upper is not None:
        start = min(max(start, lower), upper)
    kind = "angular" if angular else "linear"
    prim.apply(f"PhysicsJointStateAPI:{kind}")
    prim.attr(f"state:{kind}:physics:position", "float", start * unit)
    prim.attr(f"state:{kind}:physics:velocity", "float", 0.0)
    follower = False
    if joint.mimic is None:
        drive_damps = _drive(ctx, joint, prim, kind, start)
    else:
        follower = _mimic(ctx, joint, prim, frame)
        _follower_effort(joint, prim, kind, ctx.options.drive_type)
        drive_damps = False
    _extras(ctx, joint, prim, kind, passive_damping=not drive_damps, follower=follower)


def _drive(ctx: UsdContext, joint: Joint, prim: Prim, kind: str, start: float) -> bool:
    """Author the drive; True when it already carries the URDF's passive damping (target type none)."""
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
    prim.apply(f"PhysicsDriveAPI:{kind}")
    base = f"drive:{kind}:physics"
    prim.attr(f"{base}:type", "token", options.drive_type, uniform=True)
    prim.attr(f"{base}:stiffness", "float", stiffness * per)
    prim.attr(f"{base}:damping", "float", damping * per)
    if joint.limit is not None and joint.limit.effort is not None and joint.limit.effort > 0:
        prim.attr(f"{base}:maxForce", "float", joint.limit.effort)
    if options.motor_envelope:
        _envelope(joint, prim, kind)
    if target_position is not None:
        prim.attr(f"{base}:targetPosition", "float", target_position * unit)
    if target_velocity is not None:
        prim.attr(f"{base}:targetVelocity", "float", target_velocity * unit)
    return options.target_type == "none"


def _follower_effort(joint: Joint, prim: Prim, kind: str, drive_type: str) -> None:
    """A mimic follower keeps its effort limit: a drive without gains that only carries ``maxForce``,
    as Isaac Sim 6.2's URDF importer writes it (Newton reads the limit from the drive)."""
    if joint.limit is None or joint.limit.effort is None or not joint.limit.effort > 0:
        return
    prim.apply(f"PhysicsDriveAPI:{kind}")
    base = f"drive:{kind}:physics"
    prim.attr(f"{base}:type", "token", drive_type, uniform=True)
    prim.attr(f"{base}:stiffness", "float", 0.0)
    prim.attr(f"{base}:damping", "float", 0.0)
    prim.attr(f"{base}:maxForce", "float", joint.limit.effort)


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


def _mimic(ctx: UsdContext, joint: Joint, prim: Prim, frame: AxisFrame) -> bool:
    """Couple the follower to its leader; False (and a warning) when the leader cannot be one."""
    mimic = joint.mimic
    assert mimic is not None
    label = f"joint {joint.name!r}"
    leader_path = ctx.joint_paths.get(mimic.joint)
    leader = ctx.robot.joint_map().get(mimic.joint)
    if leader_path is None or leader is None or leader.type.dof != 1:
        ctx.warn(
            "usd-bad-mimic", f"mimic leader {mimic.joint!r} is not a one-DOF joint: mimic left out", label, mimic.src
        )
        return False
    multiplier = mimic.multiplier if mimic.multiplier is not None else 1.0
    offset = mimic.offset if mimic.offset is not None else 0.0
    unit = DEG if joint.type.is_angular else 1.0
    prim.apply("NewtonMimicAPI")
    prim.rel("newton:mimicJoint", [leader_path])
    prim.attr("newton:mimicCoef0", "float", offset * unit)
    prim.attr("newton:mimicCoef1", "float", multiplier)
    # PhysX: q + gearing * q_ref + offset = 0, offset in PhysX's internal units (rad or m).
    instance = f"rot{frame.token}"
    prim.apply(f"PhysxMimicJointAPI:{instance}")
    base = f"physxMimicJoint:{instance}"
    prim.rel(f"{base}:referenceJoint", [leader_path])
    leader_token = joint_axis_frame(leader).token
    prim.attr(f"{base}:referenceJointAxis", "token", f"rot{leader_token}")
    prim.attr(f"{base}:gearing", "float", -multiplier)
    prim.attr(f"{base}:offset", "float", -offset)
    if joint.type is JointType.CONTINUOUS:
        ctx.warn(
            "usd-mimic-unlimited",
            "PhysX mimic joints need a finite limit on a revolute follower; this one is continuous",
            label,
            mimic.src,
        )
    return True


def _follower_velocity(ctx: UsdContext, joint: Joint, velocity: float | None) -> None:
    """A mimic follower is written without a velocity limit. PhysX (ovphysx 0.7) reads one from
    ``physxJointAxis:*:maxJointVelocity`` or ``newton:velocityLimit`` and, on a follower of a hard
    mimic constraint, the two fight: example-robot-data's tiago_pro, whose gripper fingers follow
    at 2 rad/s, ran its whole arm away (joints 4.9e27 rad off in 1 s); without them it holds within
    0.22 rad, as MuJoCo does. ovphysx's gripper guide says the same ("do not set max joint velocity
    on the mimic joints"). The leader's limit bounds the follower already (|multiplier| times it);
    only a follower limit tighter than that is lost, and then the compile says so."""
    mimic = joint.mimic
    assert mimic is not None
    leader = ctx.robot.joint_map().get(mimic.joint)
    lead = leader.limit.velocity if leader is not None and leader.limit is not None else None
    multiplier = abs(mimic.multiplier if mimic.multiplier is not None else 1.0)
    if velocity is None or (lead is not None and lead > 0 and lead * multiplier <= velocity * (1 + 1e-9)):
        return
    bound = "no velocity limit" if lead is None or not lead > 0 else f"a velocity limit of {lead * multiplier:g}"
    ctx.warn(
        "usd-mimic-velocity",
        f"velocity limit {velocity:g} left out: PhysX fights a velocity limit on a mimic follower and can "
        f"run away (docs/usd.md); the leader {mimic.joint!r} gives it {bound}",
        f"joint {joint.name!r}",
        joint.limit.src if joint.limit is not None else joint.src,
    )


def _extras(
    ctx: UsdContext, joint: Joint, prim: Prim, kind: str, *, passive_damping: bool, follower: bool = False
) -> None:
    """Armature, velocity limit, friction and passive damping in PhysX's and Newton's vocabularies.

    PhysX reads them from the multiple-apply ``PhysxJointAxisAPI:<kind>`` (``physx-usd-schemas``
    25.11; the instance is the drive's, ``angular`` on a revolute joint and ``linear`` on a prismatic
    one): armature in kg·m² (kg), maximum joint velocity in deg/s (m/s), static and dynamic friction
    efforts in N·m (N), viscous friction in N·m·s/deg (N·s/m). URDF's ``<dynamics friction>`` is the
    Coulomb friction effort, so it is both the static effort (what holds a resting joint) and the
    dynamic one (what opposes a moving joint). Newton's names and units are ``newton-usd-schemas``
    0.6's ``NewtonJointAPI`` (damping in effort·s/deg, velocity limit in deg/s). The legacy
    single-apply ``PhysxJointAPI`` is written only for the Isaac Sim releases that read it
    (``isaac_version``). With target type ``none`` the drive already carries the URDF damping, so it
    is not given twice.
    """
    angular = kind == "angular"
    armature = joint.armature
    velocity = joint.limit.velocity if joint.limit is not None else None
    if velocity is not None and not velocity > 0:
        # URDF's placeholder 0 (as effort 0, which writes no maxForce): NewtonJointAPI's range is
        # (0, inf], and 0 would freeze the joint in Newton.
        velocity = None
    if follower:
        _follower_velocity(ctx, joint, velocity)
        velocity = None
    dyn = joint.dynamics
    friction = dyn.friction if dyn is not None else None
    damping = dyn.damping if dyn is not None and passive_damping else None
    if armature is None and velocity is None and friction is None and damping is None:
        return
    unit = DEG if angular else 1.0
    per = PER_DEGREE if angular else 1.0
    version = ctx.options.isaac_version
    # Isaac Sim 4.x has no PhysxJointAxisAPI: it reads only the legacy spelling.
    if version not in ISAAC_WITHOUT_JOINT_AXIS:
        axis = f"physxJointAxis:{kind}"
        prim.apply(f"PhysxJointAxisAPI:{kind}")
        if armature is not None:
            prim.attr(f"{axis}:armature", "float", armature)
        if velocity is not None:
            prim.attr(f"{axis}:maxJointVelocity", "float", velocity * unit)
        if friction is not None:
            prim.attr(f"{axis}:staticFrictionEffort", "float", friction)
            prim.attr(f"{axis}:dynamicFrictionEffort", "float", friction)
        if damping is not None:
            prim.attr(f"{axis}:viscousFrictionCoefficient", "float", damping * per)
    if version in LEGACY_JOINT_API and (armature is not None or velocity is not None):
        # physxJoint:jointFriction is PhysX's unitless friction coefficient (scaled by the joint's
        # constraint force), not an effort: a URDF friction has no place in it.
        prim.apply("PhysxJointAPI")
        if armature is not None:
            prim.attr("physxJoint:armature", "float", armature)
        if velocity is not None:
            prim.attr("physxJoint:maxJointVelocity", "float", velocity * unit)
    if friction and version in ISAAC_WITHOUT_JOINT_AXIS:
        ctx.warn(
            "usd-friction-unwritten",
            f"Isaac Sim {version}.x's PhysX has no friction effort (only a unitless coefficient): the URDF's "
            f"friction {friction:g} reaches it only through newton:friction, which it does not read",
            f"joint {joint.name!r}",
            dyn.src if dyn is not None else joint.src,
        )
    prim.apply("NewtonJointAPI")
    if armature is not None:
        prim.attr("newton:armature", "float", armature)
    if velocity is not None:
        prim.attr("newton:velocityLimit", "float", velocity * unit)
    if friction is not None:
        prim.attr("newton:friction", "float", friction)
    if damping is not None:
        prim.attr("newton:damping", "float", damping * per)


def _envelope(joint: Joint, prim: Prim, kind: str) -> None:
    """``PhysxDrivePerformanceEnvelopeAPI:<kind>`` from the URDF effort (stall torque) and velocity
    (no-load speed): a DC motor's line |τ| <= effort·(1 - |ω|/velocity), which PhysX writes as
    ``maxForce - velocityDependentResistance·|ω|`` with ``maxActuatorVelocity`` where it reaches 0.
    Angular values per degree, as the schema's units say (resistance N·m·s/deg, velocity deg/s)."""
    limit = joint.limit
    if limit is None or not (limit.effort or 0.0) > 0 or not (limit.velocity or 0.0) > 0:
        return
    assert limit.effort is not None and limit.velocity is not None
    unit = DEG if kind == "angular" else 1.0
    base = f"physxDrivePerformanceEnvelope:{kind}"
    prim.apply(f"PhysxDrivePerformanceEnvelopeAPI:{kind}")
    prim.attr(f"{base}:maxActuatorVelocity", "float", limit.velocity * unit)
    prim.attr(f"{base}:velocityDependentResistance", "float", limit.effort / (limit.velocity * unit))


def emit_loop_joint(ctx: UsdContext, loop: LoopJoint, path: str) -> None:
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
    prim = ctx.define(PHYSICS, path, _TYPE_NAMES[jtype])
    set_display_name(prim, loop.display_name)
    prim.rel("physics:body0", [ctx.link_paths[loop.link1.link]])
    prim.rel("physics:body1", [ctx.link_paths[loop.link2.link]])
    _frames(prim, pose_frame(loop.link1.origin), pose_frame(loop.link2.origin), frame)
    prim.attr("physics:excludeFromArticulation", "bool", True, uniform=True)
    if jtype is not JointType.FIXED:
        prim.attr("physics:axis", "token", frame.token, uniform=True)


def loop_scope_paths(ctx: UsdContext) -> dict[str, str]:
    scope = f"{ctx.robot_path}/{LOOPS_SCOPE}"
    out: dict[str, str] = {}
    for loop in ctx.robot.loop_joints:
        name = check_identifier(loop.name, f"loop_joint {loop.name!r}", loop.src)
        if name in out:
            raise UnsupportedError("two loop joints share this name", element=f"loop_joint {name!r}", loc=loop.src)
        out[name] = f"{scope}/{name}"
    return out
