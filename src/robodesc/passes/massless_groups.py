"""The group maths of the ``massless`` pass: fixed groups, collider masses and the 1 g placeholders
moved from a group's heaviest link. Why, and what each option does: passes/massless.py's docstring."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from robodesc.ir.geometry import Inertial, Pose
from robodesc.ir.inertia import from_tensor, parallel_axis, tensor
from robodesc.ir.model import JointType, Link, Robot
from robodesc.ir.principal import inertia_problem
from robodesc.ir.transforms import Mat, pose_matrix
from robodesc.passes.context import PassContext
from robodesc.passes.massless_common import NAME, PLACEHOLDER_GYRATION, PLACEHOLDER_MASS, massless_link


@dataclass(slots=True)
class FixedGroup:
    """Links joined by fixed joints; ``frames`` maps each to its pose in the top link's frame."""

    top: str
    moving: bool
    frames: dict[str, Mat] = field(default_factory=dict)


def fixed_groups(robot: Robot) -> list[FixedGroup]:
    """Every link in exactly one group, groups in the links' order of their top link. A group
    moves when its top link's parent joint is not fixed; the root's group does not count as moving
    (whether the base floats is the target's choice, and its mass is the source's either way)."""
    parents = robot.parent_joint()
    children = robot.child_joints()
    groups: list[FixedGroup] = []
    for link in robot.links:
        joint = parents.get(link.name)
        if joint is not None and joint.type is JointType.FIXED:
            continue
        group = FixedGroup(top=link.name, moving=joint is not None, frames={link.name: np.eye(4)})
        stack = [link.name]
        while stack:
            name = stack.pop()
            for child in children.get(name, []):
                if child.type is JointType.FIXED and child.child not in group.frames:
                    group.frames[child.child] = group.frames[name] @ pose_matrix(child.origin)
                    stack.append(child.child)
        groups.append(group)
    return groups


def carried_by(robot: Robot) -> dict[str, str]:
    """Massless links whose fixed group has mass: the link -> the group's heaviest link."""
    links = robot.link_map()
    out: dict[str, str] = {}
    for group in fixed_groups(robot):
        heavy = _heaviest(group, links)
        if heavy is None:
            continue
        for name in group.frames:
            if massless_link(links[name]):
                out[name] = heavy
    return out


def _mass(link: Link) -> float:
    inertial = link.inertial
    return inertial.mass if inertial is not None and inertial.mass is not None and inertial.mass > 0 else 0.0


def _heaviest(group: FixedGroup, links: dict[str, Link]) -> str | None:
    best = max(group.frames, key=lambda n: _mass(links[n]))
    return best if _mass(links[best]) > 0 else None


def apply(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    links = robot.link_map()
    for group in fixed_groups(robot):
        if ctx.options.mass_from_colliders and group.moving and _heaviest(group, links) is None:
            _from_geometry(group, links, ctx)
        if ctx.options.placeholder_masses:
            _placeholders(group, links, ctx)
    return robot


def _from_geometry(group: FixedGroup, links: dict[str, Link], ctx: PassContext) -> None:
    # shape_inertia brings numpy's mesh maths: imported only when a dead group needs it.
    from robodesc.passes.shape_inertia import inertial_from_props, link_props

    for name in group.frames:
        link = links[name]
        found = link_props(link)
        if found is None:
            continue
        props, source = found
        mass = ctx.options.density * props.volume
        if not mass > 0:
            continue
        new = inertial_from_props(props, mass=mass)
        new.src = link.inertial.src if link.inertial is not None else None
        link.inertial = new
        for note in props.notes:
            ctx.warn("mesh-not-watertight", note, element=f"link {name!r}", loc=link.src)
        ctx.warn(
            "mass-from-geometry",
            f"a moving link without mass (joint below {group.top!r} would move nothing): given its {source} "
            f"geometry's mass at {ctx.options.density:g} kg/m³, {mass:.6g} kg",
            element=f"link {name!r}",
            loc=link.src,
        )


def _placeholder_tensor() -> np.ndarray:
    return np.eye(3) * PLACEHOLDER_MASS * PLACEHOLDER_GYRATION**2


def _placeholders(group: FixedGroup, links: dict[str, Link], ctx: PassContext) -> None:
    empty = [n for n in group.frames if massless_link(links[n])]
    if not empty:
        return
    heavy = _heaviest(group, links)
    if heavy is not None and _borrow(heavy, empty, group, links, ctx):
        return
    for name in empty:
        link = links[name]
        origin = link.inertial.origin if link.inertial is not None and link.inertial.origin is not None else Pose()
        src = link.inertial.src if link.inertial is not None else None
        link.inertial = Inertial(
            mass=PLACEHOLDER_MASS, origin=origin, inertia=from_tensor(_placeholder_tensor()), src=src
        )
        why = "its fixed group has no mass to take it from" if heavy is None else f"{heavy!r} cannot spare it"
        ctx.warn(
            "mass-placeholder",
            f"no mass, and the target needs one on every body: given {PLACEHOLDER_MASS:g} kg ({why}; "
            f"the robot weighs {PLACEHOLDER_MASS:g} kg more)",
            element=f"link {name!r}",
            loc=link.src,
        )


def _borrow(heavy: str, empty: list[str], group: FixedGroup, links: dict[str, Link], ctx: PassContext) -> bool:
    """Move :data:`PLACEHOLDER_MASS` from ``heavy`` to each massless link of the group, keeping the
    group's mass, centre of mass and inertia; False (nothing changed) when what stays on ``heavy``
    would not be a physical body."""
    link = links[heavy]
    inertial = link.inertial
    assert inertial is not None and inertial.mass is not None
    to_heavy = np.linalg.inv(group.frames[heavy])
    spots = [(to_heavy @ group.frames[n])[:3, 3] for n in empty]
    taken = PLACEHOLDER_MASS * len(empty)
    mass = inertial.mass - taken
    if not mass > 0 or inertial.inertia is None:
        return False
    frame = pose_matrix(inertial.origin)
    com = frame[:3, 3]
    rot = frame[:3, :3]
    about_com = rot @ tensor(inertial.inertia) @ rot.T  # heavy's tensor about its centre, link axes
    new_com = (inertial.mass * com - PLACEHOLDER_MASS * sum(spots, np.zeros(3))) / mass
    # The old body about new_com, minus each placeholder about it (its own tensor plus its offset's
    # share): what is left is the remaining body about its own centre, new_com.
    whole = parallel_axis(about_com, inertial.mass, com - new_com)
    for spot in spots:
        whole = whole - parallel_axis(_placeholder_tensor(), PLACEHOLDER_MASS, spot - new_com)
    rest = from_tensor(whole)
    if inertia_problem(rest) is not None:
        return False
    xyz = (float(new_com[0]), float(new_com[1]), float(new_com[2]))
    link.inertial = Inertial(mass=mass, origin=Pose(xyz=xyz), inertia=rest, src=inertial.src)
    for name in empty:
        member = links[name]
        src = member.inertial.src if member.inertial is not None else None
        member.inertial = Inertial(
            mass=PLACEHOLDER_MASS, origin=Pose(), inertia=from_tensor(_placeholder_tensor()), src=src
        )
        ctx.info(
            "mass-placeholder",
            f"no mass of its own (carried by {heavy!r}, fixed to it): given {PLACEHOLDER_MASS:g} kg taken from "
            f"{heavy!r}, so the rigid group's mass, centre of mass and inertia are the source's",
            element=f"link {name!r}",
            loc=member.src,
        )
    return True
