"""Couplings and closures (``<equality>``) and contact filtering (``<contact>``).

- ``<mimic>``: ``<joint joint1=follower joint2=leader polycoef="offset multiplier 0 0 0">``, which is
  MuJoCo's ``q1 = c0 + c1 q2``: the URDF's ``q = multiplier q_leader + offset``.
- Isaac ``<loop_joint>``: a site on each side at its frame; spherical -> ``connect`` of the two sites,
  fixed -> ``weld`` of them; other types -> ``connect`` with a warning (MuJoCo has no hinge closure).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

from robodesc.emit.mjcf.context import MjcfContext, insert_site, num, set_pose
from robodesc.ir.model import JointType


def equality(ctx: MjcfContext) -> ET.Element | None:
    root = ET.Element("equality")
    joints = ctx.robot.joint_map()
    for joint in ctx.robot.joints:
        mimic = joint.mimic
        if mimic is None:
            continue
        leader = joints.get(mimic.joint)
        if leader is None or leader.type.dof != 1 or joint.type.dof != 1:
            ctx.warn(
                "mjcf-bad-mimic",
                f"mimic of {mimic.joint!r}: both joints must have one DOF; the mimic is left out",
                f"joint {joint.name!r}",
                mimic.src,
            )
            continue
        offset = mimic.offset if mimic.offset is not None else 0.0
        multiplier = mimic.multiplier if mimic.multiplier is not None else 1.0
        ET.SubElement(
            root, "joint", name=f"{joint.name}_mimic", joint1=joint.name, joint2=leader.name,
            polycoef=f"{num(offset)} {num(multiplier)} 0 0 0",
        )  # fmt: skip
    for loop in ctx.robot.loop_joints:
        label = f"loop_joint {loop.name!r}"
        sites = []
        for i, side in enumerate((loop.link1, loop.link2), start=1):
            body = ctx.bodies.get(side.link)
            if body is None:
                ctx.warn("mjcf-loop-dropped", f"link {side.link!r} is not a body: loop left out", label, loop.src)
                break
            site = ET.Element("site", name=ctx.unique_site(f"{loop.name}_{i}"))
            set_pose(site, side.origin)
            insert_site(body, site)
            sites.append(site.get("name", ""))
        else:
            kind = loop.type.lower()
            tag = "weld" if kind == "fixed" else "connect"
            if kind not in ("spherical", "fixed"):
                ctx.warn(
                    "mjcf-loop-approximated",
                    f"a {loop.type} loop joint is written as a point connection (MuJoCo's equality "
                    "constraints have no hinge or slider closure): its rotation is free",
                    label,
                    loop.src,
                )
            ET.SubElement(root, tag, name=loop.name, site1=sites[0], site2=sites[1])
    return root if len(root) else None


def contact(ctx: MjcfContext) -> ET.Element | None:
    """With self-collision on, exclude every jointed parent-child pair explicitly (MuJoCo filters
    them too, unless the parent is the world); with it off the collision class makes the robot's
    geoms collide with the world only, so nothing is needed."""
    if not ctx.options.self_collision:
        return None
    root = ET.Element("contact")
    for joint in ctx.robot.joints:
        if joint.type is JointType.FIXED:
            continue
        if joint.parent in ctx.bodies and joint.child in ctx.bodies:
            ET.SubElement(root, "exclude", body1=joint.parent, body2=joint.child)
    return root if len(root) else None
