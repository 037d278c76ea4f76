"""Lump every link attached by a fixed joint into its parent (optional; ``merge_fixed``).

Leaves first, so chains of fixed joints collapse into their first movable ancestor. For each
merged child: the inertials combine (parallel-axis theorem, with the joint's rotation); visuals,
collisions, child joints, fixed frames, sensors and loop-joint ends move to the parent with their
origins composed; gazebo references follow. The lost link becomes a :class:`FixedFrame` of the same
name at the same place, so no frame is lost. Joints with ``dont_collapse="true"``, and joints a
transmission, ros2_control block or mimic refers to, are kept.
"""

from __future__ import annotations

import numpy as np

from robodesc.ir.geometry import Inertial, Pose
from robodesc.ir.inertia import from_tensor, parallel_axis, tensor
from robodesc.ir.model import FixedFrame, Joint, JointType, Link, Robot
from robodesc.ir.transforms import Mat, matrix_pose, pose_matrix
from robodesc.passes.context import PassContext
from robodesc.passes.references import retarget_extension

NAME = "merge_fixed"


def _compose(t: Mat, pose: Pose | None) -> Pose:
    out = matrix_pose(t @ pose_matrix(pose))
    out.src = pose.src if pose is not None else None
    return out


def _in_link_axes(inertial: Inertial, t: Mat) -> tuple[float, Mat, Mat]:
    """mass, centre of mass and tensor about it, in the frame ``t`` maps the link into."""
    mass = inertial.mass or 0.0
    local = pose_matrix(inertial.origin)
    frame = t @ local
    com = frame[:3, 3]
    m = tensor(inertial.inertia) if inertial.inertia is not None else np.zeros((3, 3))
    r = frame[:3, :3]
    return mass, com, r @ m @ r.T


def combine_inertials(parent: Inertial | None, child: Inertial | None, t: Mat) -> Inertial | None:
    """The parent's inertial plus the child's, the child's frame sitting at ``t`` in the parent."""
    if child is None:
        return parent
    parts = [_in_link_axes(child, t)]
    if parent is not None:
        parts.append(_in_link_axes(parent, np.eye(4)))
    total = sum(p[0] for p in parts)
    if total <= 0:
        return parent if parent is not None else Inertial(mass=child.mass, origin=_compose(t, child.origin))
    com = sum((p[0] * p[1] for p in parts), np.zeros(3)) / total
    m = sum((parallel_axis(p[2], p[0], p[1] - com) for p in parts), np.zeros((3, 3)))
    xyz = (float(com[0]), float(com[1]), float(com[2]))
    src = parent.src if parent is not None else child.src
    return Inertial(mass=total, origin=Pose(xyz=xyz), inertia=from_tensor(m), src=src)


def merge_fixed(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    merged = 0
    # A joint a transmission, ros2_control block or mimic names is kept: removing it would leave
    # that reference dangling.
    referenced = {tj.name: f"transmission {tr.name!r}" for tr in robot.transmissions for tj in tr.joints}
    referenced.update({cj.name: f"ros2_control {rc.name!r}" for rc in robot.ros2_controls for cj in rc.joints})
    referenced.update({j.mimic.joint: f"mimic of joint {j.name!r}" for j in robot.joints if j.mimic is not None})
    for joint in reversed(robot.topological_joints()):
        if joint.type is not JointType.FIXED or joint.dont_collapse:
            continue
        if joint.name in referenced:
            ctx.info(
                "merge-skipped",
                f"fixed joint kept: {referenced[joint.name]} refers to it",
                element=f"joint {joint.name!r}",
                loc=joint.src,
            )
            continue
        _merge(robot, joint, ctx)
        merged += 1
    if merged:
        ctx.info("merged-fixed", f"{merged} fixed joint(s) merged", element=f"robot {robot.name!r}")
    return robot


def _merge(robot: Robot, joint: Joint, ctx: PassContext) -> None:
    links = robot.link_map()
    parent: Link = links[joint.parent]
    child: Link = links[joint.child]
    t = pose_matrix(joint.origin)
    parent.inertial = combine_inertials(parent.inertial, child.inertial, t)
    for visual in child.visuals:
        visual.origin = _compose(t, visual.origin)
        parent.visuals.append(visual)
    for collision in child.collisions:
        collision.origin = _compose(t, collision.origin)
        # The child's surface parameters stay with its colliders, not with the parent's.
        collision.contact = child.collision_contact(collision)
        parent.collisions.append(collision)
    for other in robot.joints:
        if other.parent == child.name:
            other.parent = parent.name
            other.origin = _compose(t, other.origin)
    for frame in robot.fixed_frames:
        if frame.parent == child.name:
            frame.parent = parent.name
            frame.origin = _compose(t, frame.origin)
    for sensor in robot.sensors:
        if sensor.parent == child.name:
            sensor.parent = parent.name
            sensor.origin = _compose(t, sensor.origin)
            if sensor.parent_joint == joint.name:
                sensor.parent_joint = None
    for loop in robot.loop_joints:
        for side in (loop.link1, loop.link2):
            if side.link == child.name:
                side.link = parent.name
                side.origin = _compose(t, side.origin)
    parent.extensions.extend(child.extensions)
    robot.joints.remove(joint)
    robot.links.remove(child)
    # Gazebo blocks about the child now describe (part of) the parent.
    for ext in robot.extensions:
        retarget_extension(ext, "link", {child.name: parent.name}, {child.name})
    frame_origin = joint.origin if joint.origin is not None else Pose()
    robot.fixed_frames.append(
        FixedFrame(
            name=child.name,
            parent=parent.name,
            origin=Pose(xyz=frame_origin.xyz, rpy=frame_origin.rpy),
            display_name=child.display_name,
            src=child.src,
        )
    )
    ctx.info(
        "merged-link",
        f"merged into {parent.name!r} through fixed joint {joint.name!r}; kept as a fixed frame",
        element=f"link {child.name!r}",
        loc=joint.src,
    )
