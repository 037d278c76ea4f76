"""The ``home`` keyframe: ``--init-joint-pos`` (else zero; a floating robot's default stance) clamped
into each joint's range, the root where the root body starts (a floating robot's at its stance height),
and position actuators holding that pose."""

from __future__ import annotations

import xml.etree.ElementTree as ET

from robodesc.emit.common.numbers import fmt_vec
from robodesc.emit.mjcf.context import MjcfContext
from robodesc.ir.rules import lookup


def home_keyframe(ctx: MjcfContext, worldbody: ET.Element, actuator: ET.Element | None) -> ET.Element:
    joints = ctx.robot.joint_map()
    qpos: list[float] = []
    by_joint: dict[str, float] = {}
    for name, kind, ir_name in ctx.qpos_joints:
        if kind == "free":
            body = worldbody.find("body")
            pos = body.get("pos", "0 0 0") if body is not None else "0 0 0"
            quat = body.get("quat", "1 0 0 0") if body is not None else "1 0 0 0"
            xyz = [float(x) for x in pos.split()]
            if ctx.options.home_height is not None:
                xyz[2] = ctx.options.home_height  # the stance's spawn height (target._default_base_and_pose)
            qpos.extend([*xyz, *(float(x) for x in quat.split())])
            continue
        if kind == "ball":
            qpos.extend((1.0, 0.0, 0.0, 0.0))
            continue
        wanted = (
            lookup(dict(ctx.options.init_joint_pos), name, "init_joint_pos") if ctx.options.init_joint_pos else None
        )
        q = wanted if wanted is not None else 0.0
        joint = joints.get(ir_name) if ir_name is not None else None
        limit = joint.limit if joint is not None and joint.type.value != "continuous" else None
        if limit is not None and limit.lower is not None and limit.upper is not None:
            clamped = min(max(q, limit.lower), limit.upper)
            if clamped != q:
                ctx.warn(
                    "mjcf-home-clamped",
                    f"home position {q:g} is outside the range [{limit.lower:g}, {limit.upper:g}]: clamped to {clamped:g}",
                    f"joint {name!r}",
                    joint.src if joint is not None else None,
                )
                q = clamped
        qpos.append(q)
        by_joint[name] = q
    key = ET.Element("keyframe")
    el = ET.SubElement(key, "key", name="home", qpos=fmt_vec(qpos))
    if actuator is not None and len(actuator):
        ctrl = [by_joint.get(a.get("joint", ""), 0.0) if a.tag == "position" else 0.0 for a in actuator]
        el.set("ctrl", fmt_vec(ctrl))
    return key
