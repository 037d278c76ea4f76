"""One actuator per movable, non-mimic, one-DOF joint, in SI joint units.

Gains come from the same options as USD's drives and are written as they are: MuJoCo's hinge
units are radians, so ``kp`` is N·m/rad and ``kv`` N·m·s/rad. USD's per-degree values are these
times pi/180; nothing here converts through degrees (tests/mjcf/test_gains.py).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Collection

from robodesc.emit.common.source_drives import MJCF_ACTUATOR
from robodesc.emit.mjcf.context import MjcfContext, num
from robodesc.ir.model import Joint, JointType
from robodesc.ir.rules import lookup

# target_type -> actuator kind, when --mjcf-actuator is not given.
FROM_TARGET = {"position": "position", "velocity": "velocity", "none": "motor"}


def actuator_kind(ctx: MjcfContext) -> str:
    if "actuator" in ctx.given:
        return ctx.options.actuator
    return FROM_TARGET[ctx.options.target_type]


def joint_kind(kind: str, joint: Joint, given: Collection[str]) -> str:
    """The actuator of ``joint``: the source's own kind (``Joint.drive``) unless the user chose one."""
    if joint.drive is None or "actuator" in given or "target_type" in given:
        return kind
    return MJCF_ACTUATOR.get(joint.drive.kind, kind)


def reductions(ctx: MjcfContext) -> dict[str, float]:
    """Mechanical reductions by joint, from simple transmissions (one joint, one actuator)."""
    out: dict[str, float] = {}
    for t in ctx.robot.transmissions:
        if len(t.joints) == 1 and len(t.actuators) == 1:
            reduction = t.actuators[0].mechanical_reduction
            if reduction is not None and reduction != 0 and reduction != 1:
                out[t.joints[0].name] = reduction
    return out


def actuators(ctx: MjcfContext) -> ET.Element | None:
    """The ``<actuator>`` element (None when there is nothing to actuate or ``none`` was asked)."""
    kind = actuator_kind(ctx)
    if kind == "none":
        return None
    if ctx.options.drive_type == "acceleration":
        ctx.warn(
            "mjcf-acceleration-drive",
            "MuJoCo actuators are force actuators: the gains are written as force gains (PhysX's "
            "acceleration drive scales them by the joint's inertia)",
            "option 'drive_type'",
        )
    gears = reductions(ctx)
    root = ET.Element("actuator")
    for joint in ctx.robot.actuated_joints():
        if joint.type.dof != 1:
            if joint.type is not JointType.FLOATING:
                ctx.warn(
                    "mjcf-no-actuator",
                    f"a {joint.type.value} joint gets no actuator (MuJoCo actuates one-DOF joints here)",
                    f"joint {joint.name!r}",
                    joint.src,
                )
            continue
        root.append(_actuator(ctx, joint_kind(kind, joint, ctx.given), joint, gears.get(joint.name)))
    return root if len(root) else None


def _actuator(ctx: MjcfContext, kind: str, joint: Joint, gear: float | None) -> ET.Element:
    el = ET.Element(kind, name=joint.name, joint=joint.name)
    limit = joint.limit
    effort = limit.effort if limit is not None and limit.effort is not None and limit.effort > 0 else None
    bounded = joint.type is not JointType.CONTINUOUS and limit is not None
    if kind == "position":
        el.set("kp", num(_gain(ctx, ctx.options.stiffness, joint, "stiffness")))
        el.set("kv", num(_gain(ctx, ctx.options.damping, joint, "damping")))
        if bounded and limit is not None and limit.lower is not None and limit.upper is not None:
            el.set("ctrlrange", f"{num(limit.lower)} {num(limit.upper)}")
        if effort is not None:
            el.set("forcerange", f"{num(-effort)} {num(effort)}")
    elif kind == "velocity":
        el.set("kv", num(_gain(ctx, ctx.options.damping, joint, "damping")))
        velocity = limit.velocity if limit is not None else None
        if velocity is not None and velocity > 0:
            el.set("ctrlrange", f"{num(-velocity)} {num(velocity)}")
        if effort is not None:
            el.set("forcerange", f"{num(-effort)} {num(effort)}")
    else:
        # A motor's control is the motor's torque: through the reduction the joint gets gear × ctrl,
        # and the joint's effort limit bounds ctrl at effort / gear.
        ratio = gear if gear is not None else 1.0
        if gear is not None:
            el.set("gear", num(gear))
        if effort is not None:
            bound = effort / abs(ratio)
            el.set("ctrlrange", f"{num(-bound)} {num(bound)}")
            # The actuator's own force, clamped as the control is: the source's effort at the joint.
            el.set("forcerange", f"{num(-bound)} {num(bound)}")
    if gear is not None and kind != "motor":
        ctx.info(
            "mjcf-reduction-joint-space",
            f"mechanical reduction {gear:g}: the {kind} actuator's gains stay in joint units (as the USD drive's); "
            "it applies to --mjcf-actuator motor",
            f"joint {joint.name!r}",
            joint.src,
        )
    return el


def _gain(ctx: MjcfContext, gain: object, joint: Joint, what: str) -> float:
    value = lookup(gain, joint.name, what)  # type: ignore[arg-type]
    if value is None:
        ctx.warn("mjcf-no-gain", f"no {what} pattern matches this joint: 0 written", f"joint {joint.name!r}", joint.src)
        return 0.0
    return value
