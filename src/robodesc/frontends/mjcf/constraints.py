"""``<equality>`` and ``<contact>``.

- ``joint``: ``q1 = c0 + c1·q2`` (polycoef's higher terms must be 0) is joint1's mimic of joint2,
  offset moved by both joints' ``ref`` (IR positions are ``qpos - ref``).
- ``connect``: a spherical loop joint; both sides' frames at the anchor, taken where the model is
  at ``qpos0``. ``weld``: a fixed loop joint, the frames at body2's anchor with body2's axes.
- An inactive equality (``active="false"``), and tendon or flex equalities, are warnings.
- ``<contact>``: the IR filters collisions per link (``self_collide``), not per pair: an
  ``<exclude>`` or a ``<pair>`` is a warning naming what each target loses.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from robodesc.frontends.mjcf.context import Reading
from robodesc.frontends.mjcf.frames import frame, inverse, pose, translation
from robodesc.ir.diagnostics import SourceLoc
from robodesc.ir.model import Joint, LoopFrame, LoopJoint, Mimic
from robodesc.ir.rigid import Frame

_CONNECT, _WELD, _JOINT, _TENDON, _FLEX = 0, 1, 2, 3, 4
_BODY, _SITE = 1, 6  # mjOBJ_BODY, mjOBJ_SITE


def read_equalities(r: Reading) -> None:
    import mujoco

    m = r.model
    data = mujoco.MjData(m)
    mujoco.mj_kinematics(m, data)  # world frames at qpos0, for the loop closures
    joints = r.robot.joint_map()
    names: set[str] = {j.name for j in r.robot.loop_joints}
    for e in range(m.neq):
        name = r.name("equality", e) or f"equality{e}"
        label = f"equality {name!r}"
        loc = r.loc("equality", e)
        kind = int(m.eq_type[e])
        if not bool(m.eq_active0[e]):
            r.warn(
                "mjcf-equality-inactive", "an inactive equality (active=false) is left out of every output", label, loc
            )
            continue
        if kind == _JOINT:
            _mimic(r, e, joints, label, loc)
        elif kind in (_CONNECT, _WELD):
            loop = _loop(r, data, e, kind, r.unique(name, names), loc)
            if loop is not None:
                r.robot.loop_joints.append(loop)
        else:
            what = {_TENDON: "tendon", _FLEX: "flex"}.get(kind, "distance")
            r.warn(
                "mjcf-equality-not-held",
                f"a {what} equality has no IR form: URDF, SDF, USD and MJCF outputs leave it out",
                label,
                loc,
            )
    _resolve_chains(r)


def _linear(mimic: Mimic) -> tuple[float, float]:
    """(multiplier, offset), URDF's defaults (1, 0) where not given."""
    return (1.0 if mimic.multiplier is None else mimic.multiplier, 0.0 if mimic.offset is None else mimic.offset)


def _resolve_chains(r: Reading) -> None:
    """A mimic of a mimic (Stretch's telescoping arm: l0 follows l1, l1 follows l2, l2 follows l3)
    made one leader of each chain: URDF readers refuse a chain (Newton's add_urdf: "Reference joint is
    already a mimic joint"; ros2_control and Isaac's importer take one leader), and composing the
    linear maps is exact: q_f = o1 + m1 (o2 + m2 q_l) = (o1 + m1 o2) + m1 m2 q_l."""
    joints = r.robot.joint_map()
    resolved = []
    for joint in r.robot.joints:
        mimic = joint.mimic
        seen = {joint.name}
        while mimic is not None and mimic.joint in joints and joints[mimic.joint].mimic is not None:
            upper = joints[mimic.joint].mimic
            assert upper is not None
            if upper.joint in seen:  # a cycle of equalities: MuJoCo solves it, no leader exists
                r.warn(
                    "mjcf-mimic-cycle",
                    f"joint equalities form a cycle through {sorted(seen)}: the mimic is left as written",
                    f"joint {joint.name!r}",
                    mimic.src,
                )
                break
            seen.add(mimic.joint)
            m1, o1 = _linear(mimic)
            m2, o2 = _linear(upper)
            mimic = Mimic(joint=upper.joint, multiplier=m1 * m2, offset=o1 + m1 * o2, src=mimic.src)
            joint.mimic = mimic
        if len(seen) > 1 and joint.mimic is not None and joint.mimic.joint not in seen:
            resolved.append(f"{joint.name} -> {joint.mimic.joint}")
    if resolved:
        r.info(
            "mjcf-mimic-chain",
            f"joint equalities chained through followers, each made a mimic of its chain's leader: {', '.join(resolved)}",
            f"robot {r.robot.name!r}",
            None,
        )


def _mimic(r: Reading, e: int, joints: Mapping[str, Joint], label: str, loc: SourceLoc) -> None:
    m = r.model
    j1, j2 = int(m.eq_obj1id[e]), int(m.eq_obj2id[e])
    follower = joints.get(r.joint_of.get(j1, ""))
    coef = [float(v) for v in m.eq_data[e][:5]]
    if j2 < 0:
        r.warn("mjcf-equality-not-held", "a joint held at a constant has no IR form: left out", label, loc)
        return
    leader = joints.get(r.joint_of.get(j2, ""))
    if follower is None or leader is None:
        r.warn("mjcf-equality-not-held", "the joints of this equality are not one-DOF joints of the robot", label, loc)
        return
    if any(coef[2:]):
        r.warn(
            "mjcf-mimic-polynomial",
            f"polycoef {' '.join(f'{c:g}' for c in coef)}: the IR's mimic is linear; the quadratic and higher "
            "terms are left out",
            label,
            loc,
        )
    ref1 = float(m.qpos0[int(m.jnt_qposadr[j1])])
    ref2 = float(m.qpos0[int(m.jnt_qposadr[j2])])
    offset = coef[0] + coef[1] * ref2 - ref1
    follower.mimic = Mimic(joint=leader.name, multiplier=coef[1], offset=offset, src=loc)


def _loop(r: Reading, data: Any, e: int, kind: int, name: str, loc: SourceLoc) -> LoopJoint | None:
    m = r.model
    objtype = int(m.eq_objtype[e])
    o1, o2 = int(m.eq_obj1id[e]), int(m.eq_obj2id[e])
    eq = [float(v) for v in m.eq_data[e]]
    if objtype == _SITE:
        b1, b2 = int(m.site_bodyid[o1]), int(m.site_bodyid[o2])
        side1 = frame(m.site_pos[o1], m.site_quat[o1])
        side2 = frame(m.site_pos[o2], m.site_quat[o2])
        world = _world(data, b2) @ side2
    else:
        b1, b2 = o1, o2
        if kind == _CONNECT:
            side1 = translation(eq[0:3])  # the anchor, in body1's frame
            world = _world(data, b1) @ side1
        else:
            # A weld's anchor is a point of body2 (MuJoCo 3), with body2's axes.
            side2 = translation(eq[0:3])
            world = _world(data, b2) @ side2
    l1, l2 = r.link_of.get(b1), r.link_of.get(b2)
    if l1 is None or l2 is None:
        r.warn("mjcf-equality-not-held", "a side of this closure is not a body of the robot", f"equality {name!r}", loc)
        return None
    f1 = r.content[b1] @ inverse(_world(data, b1)) @ world
    f2 = r.content[b2] @ inverse(_world(data, b2)) @ world
    return LoopJoint(
        name=name,
        type="spherical" if kind == _CONNECT else "fixed",
        link1=LoopFrame(l1, pose(f1), src=loc),
        link2=LoopFrame(l2, pose(f2), src=loc),
        src=loc,
    )


def _world(data: Any, b: int) -> Frame:
    return frame(data.xpos[b], data.xquat[b])


def read_contact(r: Reading) -> None:
    import mujoco

    from robodesc.frontends.mjcf.source import tag

    m = r.model
    for section in r.source.root.iter("contact"):
        for el in section:
            kind = tag(el)
            b1 = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, el.get("body1", ""))
            b2 = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, el.get("body2", ""))
            related = b1 > 0 and b2 > 0 and (int(m.body_parentid[b2]) == b1 or int(m.body_parentid[b1]) == b2)
            if kind == "exclude" and related:
                # MuJoCo never collides a body with its parent (filterparent), and the targets filter
                # parent-child pairs their own way: nothing is lost.
                r.info(
                    "mjcf-contact-exclude",
                    f"bodies {el.get('body1')!r} and {el.get('body2')!r} are parent and child, which no target collides",
                    "contact exclude",
                    r.source.loc(el),
                )
            elif kind == "exclude":
                r.warn(
                    "mjcf-contact-exclude",
                    f"bodies {el.get('body1')!r} and {el.get('body2')!r} never collide in MuJoCo; the IR filters per "
                    "link, not per pair: the MJCF output excludes jointed parent-child pairs only, URDF, SDF and USD "
                    "follow each target's self-collision option",
                    "contact exclude",
                    r.source.loc(el),
                )
            elif kind == "pair":
                r.warn(
                    "mjcf-contact-pair",
                    f"an explicit contact pair ({el.get('geom1')!r}, {el.get('geom2')!r}) and its own friction, "
                    "solref and solimp have no IR form: every output lets the geoms' own parameters decide",
                    "contact pair",
                    r.source.loc(el),
                )
