"""Bodies and joints: MuJoCo's tree as IR links and joints.

- A body is a link with the body's name. A body with several joints (a humanoid's hip: three
  hinges) becomes a chain: each joint but the last leads to a massless link named after it.
- A joint turns about its anchor (:mod:`.frames`); ``ref`` is the IR's zero, so an IR position is
  MuJoCo's ``qpos - ref`` (limits, springs, keyframes and mimics are moved by it).
- hinge -> revolute (continuous when unlimited), slide -> prismatic, ball -> spherical, free ->
  the root floats (``fixed_base`` False), or a floating joint from ``world`` for a second free body.
- The root: one top body is the root link, placed where the file puts it (``placement``); welded
  (no joint) it is ``fixed_base``. Several top bodies, or a top body on hinges or slides, hang from
  a ``world`` link.
- The body's mass, centre and principal inertia are the compiled model's: explicit ``<inertial>``,
  or MuJoCo's inertia from geoms, exactly (see :mod:`.compiled`).
"""

from __future__ import annotations

import math

from robodesc.frontends.mjcf.context import Reading
from robodesc.frontends.mjcf.frames import frame, inverse, pose, translation
from robodesc.ir.geometry import Inertia, Inertial
from robodesc.ir.model import Dynamics, Joint, JointType, Limit, Link
from robodesc.ir.rigid import Frame

WORLD = "world"
FREE, BALL, SLIDE, HINGE = 0, 1, 2, 3


def read_bodies(r: Reading) -> None:
    m = r.model
    top = _robot_tops(r, [b for b in range(1, m.nbody) if int(m.body_parentid[b]) == 0])
    if not top:
        raise_empty(r)
    needs_world = len(top) != 1 or (_joint_types(r, top[0]) not in ([], [FREE]))
    r.link_of[0] = WORLD
    r.content[0] = Frame()
    if needs_world:
        r.robot.links.append(Link(name=r.unique(WORLD, r.link_names), src=r.loc("body", 0)))
    else:
        root = top[0]
        r.robot.fixed_base = _joint_types(r, root) != [FREE]
        r.robot.placement = pose(frame(m.body_pos[root], m.body_quat[root]))
    for b in range(1, m.nbody):  # parents come before children in MuJoCo's numbering
        if int(m.body_rootid[b]) in r.dropped:
            r.dropped.add(b)
            continue
        _read_body(r, b, is_root=not needs_world and b == top[0])


def _robot_tops(r: Reading, tops: list[int]) -> list[int]:
    """The world's children that belong to the robot. A scene's objects (a top body with no joint in
    its tree but its own free joint: a cube, a table) are left out when a body with joints is there,
    with one warning naming them: the IR holds one robot, and a second free body has no place in it."""
    m = r.model
    jointed = {int(m.body_rootid[int(m.jnt_bodyid[j])]) for j in range(m.njnt) if int(m.jnt_type[j]) != FREE}
    if not jointed:
        return tops
    objects = [b for b in tops if b not in jointed]
    if objects:
        r.dropped.update(objects)
        names = ", ".join(repr(r.name("body", b) or f"body{b}") for b in objects)
        r.warn(
            "mjcf-scene-object",
            f"{len(objects)} top-level bod{'y' if len(objects) == 1 else 'ies'} without joints of {'its' if len(objects) == 1 else 'their'} "
            f"own ({names}): objects of the scene, not the robot; every output leaves them out",
            "worldbody",
            r.loc("body", objects[0]),
        )
    return [b for b in tops if b in jointed]


def raise_empty(r: Reading) -> None:
    from robodesc.ir.diagnostics import ParseError

    raise ParseError("the model has no body: nothing to convert", loc=r.source.loc(r.source.root))


def _joint_types(r: Reading, b: int) -> list[int]:
    m = r.model
    start, count = int(m.body_jntadr[b]), int(m.body_jntnum[b])
    return [int(m.jnt_type[j]) for j in range(start, start + count)] if count > 0 else []


def _read_body(r: Reading, b: int, is_root: bool) -> None:
    m = r.model
    name = r.unique(r.name("body", b) or f"body{b}", r.link_names)
    loc = r.loc("body", b)
    parent = int(m.body_parentid[b])
    if float(m.body_gravcomp[b]) != 0.0:
        r.warn(
            "mjcf-gravcomp",
            f"gravcomp {float(m.body_gravcomp[b]):g}: MuJoCo cancels this share of the body's weight; the IR has no "
            "such force, so in every output gravity loads the body fully",
            f"body {name!r}",
            loc,
        )
    if int(m.body_mocapid[b]) >= 0:
        r.info("mjcf-mocap", "a mocap body is moved by the user in MuJoCo: it is welded here", f"body {name!r}", loc)
    placed = frame(m.body_pos[b], m.body_quat[b])  # the body in its parent's frame, at qpos0
    # From the parent's IR link frame to this body's frame.
    here = r.content[parent] @ placed
    previous = r.link_of[parent]
    start, count = int(m.body_jntadr[b]), int(m.body_jntnum[b])
    joints = list(range(start, start + count)) if count > 0 else []
    anchor = (0.0, 0.0, 0.0)
    first = True
    for k, j in enumerate(joints):
        kind = int(m.jnt_type[j])
        jname_written = r.name("joint", j)
        if kind == FREE:
            if is_root:
                continue  # the root floats: fixed_base False
            jname = r.unique(jname_written or f"{name}_free", r.joint_names)
            joint = Joint(jname, JointType.FLOATING, previous, name, origin=pose(here), src=r.loc("joint", j))
            r.robot.joints.append(joint)
            r.joint_of[j] = jname
            previous, here, first = name, Frame(), False
            break
        jname = r.unique(jname_written or f"{name}_joint{k + 1}", r.joint_names)
        new_anchor = anchor if kind == SLIDE else tuple(float(v) for v in m.jnt_pos[j])
        origin = (here @ translation(new_anchor)) if first else translation(_sub(new_anchor, anchor))
        anchor = new_anchor  # type: ignore[assignment]
        last = k == len(joints) - 1
        child = name if last else r.unique(f"{jname}_link", r.link_names)
        if not last:
            r.robot.links.append(Link(name=child, src=r.loc("joint", j)))
        r.robot.joints.append(_joint(r, j, jname, kind, previous, child, pose(origin)))
        r.joint_of[j] = jname
        previous, here, first = child, Frame(), False
    if first and not is_root:
        # A body welded to its parent: a fixed joint (MuJoCo's bodies without joints).
        jname = r.unique(f"{name}_fixed", r.joint_names)
        r.robot.joints.append(Joint(jname, JointType.FIXED, previous, name, origin=pose(here), src=loc))
    r.link_of[b] = name
    r.content[b] = inverse(translation(anchor))
    written = r.name("body", b)
    # A name made unique (a body named as a joint's intermediate link) keeps the written one.
    display = written if written is not None and written != name else None
    r.robot.links.append(Link(name=name, inertial=_inertial(r, b), display_name=display, src=loc))


def _sub(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, float, float]:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _joint(r: Reading, j: int, name: str, kind: int, parent: str, child: str, origin: object) -> Joint:
    m = r.model
    loc = r.loc("joint", j)
    dof = int(m.jnt_dofadr[j])
    axis = tuple(float(v) for v in m.jnt_axis[j])
    ref = float(m.qpos0[int(m.jnt_qposadr[j])]) if kind in (HINGE, SLIDE) else 0.0
    if ref != 0.0:
        r.info(
            "mjcf-joint-ref",
            f"ref {ref:g}: the IR's zero is this position, so its limits, spring and keyframe values are moved by it",
            f"joint {name!r}",
            loc,
        )
    limited = bool(m.jnt_limited[j])
    lo, hi = (float(m.jnt_range[j][0]) - ref, float(m.jnt_range[j][1]) - ref) if limited else (None, None)
    effort = None
    if bool(m.jnt_actfrclimited[j]):
        effort = max(abs(float(m.jnt_actfrcrange[j][0])), abs(float(m.jnt_actfrcrange[j][1])))
    if kind == HINGE:
        jtype = JointType.REVOLUTE if limited else JointType.CONTINUOUS
    elif kind == SLIDE:
        jtype = JointType.PRISMATIC
    else:
        jtype = JointType.SPHERICAL
        if limited:
            r.warn(
                "mjcf-ball-limit",
                f"a ball joint's cone limit ({math.degrees(float(m.jnt_range[j][1])):g} deg) has no IR field: "
                "every output leaves the ball joint unlimited",
                f"joint {name!r}",
                loc,
            )
    limit = None
    if jtype in (JointType.REVOLUTE, JointType.PRISMATIC, JointType.CONTINUOUS) and (limited or effort is not None):
        limit = Limit(lower=lo, upper=hi, effort=effort, src=loc)
    stiffness = float(m.jnt_stiffness[j])
    damping = float(m.dof_damping[dof])
    friction = float(m.dof_frictionloss[dof])
    dynamics = None
    if damping or friction or stiffness:
        spring_ref = float(m.qpos_spring[int(m.jnt_qposadr[j])]) - ref if stiffness and kind in (HINGE, SLIDE) else None
        dynamics = Dynamics(
            damping=damping or None,
            friction=friction or None,
            spring_stiffness=stiffness or None,
            spring_reference=spring_ref,
            src=loc,
        )
    armature = float(m.dof_armature[dof]) or None
    return Joint(
        name,
        jtype,
        parent,
        child,
        origin=origin,  # type: ignore[arg-type]
        axis=axis if jtype is not JointType.SPHERICAL else None,  # type: ignore[arg-type]
        limit=limit,
        dynamics=dynamics,
        armature=armature,
        display_name=r.name("joint", j) if r.name("joint", j) not in (None, name) else None,
        src=loc,
    )


def _inertial(r: Reading, b: int) -> Inertial | None:
    m = r.model
    mass = float(m.body_mass[b])
    diag = [float(v) for v in m.body_inertia[b]]
    if mass == 0.0 and not any(diag):
        return None
    centre = r.content[b] @ frame(m.body_ipos[b], m.body_iquat[b])
    return Inertial(
        mass=mass,
        origin=pose(centre),
        inertia=Inertia(ixx=diag[0], iyy=diag[1], izz=diag[2]),
        src=r.loc("body", b),
    )
