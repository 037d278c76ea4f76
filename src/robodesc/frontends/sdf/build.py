"""SDF model -> IR: resolve every frame once (:mod:`.frames`), then write links, joints, frames and
sensors in the IR's convention.

The IR's link frame is the frame of the joint that leads to the link (URDF's convention: the child
link's frame is the joint frame at zero), or the SDF link frame for a root. So an SDF link posed
apart from its joint keeps its place: its inertial, visuals and collisions are re-expressed from the
SDF link frame into that IR frame, and FK at any joint values equals libsdformat's.
"""

from __future__ import annotations

import numpy as np

from robodesc.frontends.options import LoadOptions
from robodesc.frontends.sdf.extras import controller_gains, keep_plugins, read_sensor, warn_unread
from robodesc.frontends.sdf.frames import WORLD, Frames, Node
from robodesc.frontends.sdf.joints import joint_ends, read_joint
from robodesc.frontends.sdf.links import _clean, read_link
from robodesc.frontends.sdf.source import STAGE, read_source
from robodesc.frontends.sdf.values import loc, pose_value
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import FixedFrame, Link, LoopFrame, LoopJoint, Robot
from robodesc.ir.transforms import Mat, matrix_pose, pose_matrix


def read_sdf_model(path: str, options: LoadOptions, findings: Findings) -> Robot:
    source = read_source(path, findings, options.model_path)
    frames = Frames.build(source, findings)
    top = source.top
    robot = Robot(name=top.element.get("name") or "model", src=loc(source.file, top.element), source_file=source.file)
    nodes = list(frames.nodes.values())
    links = [n for n in nodes if n.kind == "link"]
    joints = [n for n in nodes if n.kind == "joint"]
    ends = {j.name: joint_ends(frames, j) for j in joints}
    # The joint that leads to each link: the first that names it as child; any other closes a loop.
    leading: dict[str, Node] = {}
    for j in joints:
        child = ends[j.name][1]
        if child == WORLD:
            continue
        leading.setdefault(child, j)
    ir_frame: dict[str, Mat] = {}
    for link in links:
        lead = leading.get(link.name)
        ir_frame[link.name] = frames.in_model(lead.name if lead is not None else link.name)
    for link in links:
        robot.links.append(read_link(frames, link, ir_frame[link.name], options, findings))
        warn_unread("link", link.name, link.file, link.element, findings)
    _joints(robot, frames, joints, ends, leading, ir_frame, findings)
    for frame in (n for n in nodes if n.kind == "frame"):
        attached = frames.link_of(frame.name)
        origin = _clean(matrix_pose(np.linalg.inv(ir_frame[attached]) @ frames.in_model(frame.name)))
        robot.fixed_frames.append(FixedFrame(frame.name, attached, origin, src=loc(frame.file, frame.element)))
    _sensors(robot, frames, links, joints, ends, ir_frame, findings)
    for scope in source.scopes():
        plugins = keep_plugins(robot, scope, findings)
        controller_gains(plugins, scope, robot.joint_map())
        warn_unread("model", scope.frame, scope.file, scope.element, findings)
    _placement(robot, frames, top.element, source.file, ir_frame)
    if top.static:
        robot.fixed_base = True
    return robot


def _joints(
    robot: Robot,
    frames: Frames,
    joints: list[Node],
    ends: dict[str, tuple[str, str]],
    leading: dict[str, Node],
    ir_frame: dict[str, Mat],
    findings: Findings,
) -> None:
    world_fixed = False
    for node in joints:
        parent, child = ends[node.name]
        warn_unread("joint", node.name, node.file, node.element, findings)
        if leading.get(child) is not node:
            _loop(robot, frames, node, parent, child, ir_frame, findings)
            continue
        if parent == WORLD and (node.element.get("type") or "") == "fixed":
            # Welded to the world: the IR's fixed base (the SDF target writes the weld back).
            world_fixed = True
            continue
        if parent == WORLD and WORLD not in ir_frame:
            findings.info(
                "sdf-world-link",
                "moves relative to the world: a massless link 'world' at the model's frame is its parent",
                element=f"joint {node.name!r}",
                loc=loc(node.file, node.element),
                stage=STAGE,
            )
            robot.links.append(Link(WORLD, src=loc(node.file, node.element)))
            ir_frame[WORLD] = np.eye(4)
            world_fixed = True
        made = read_joint(frames, node, parent, child, ir_frame[parent], findings)
        if len(made) == 2:
            robot.links.append(Link(made[0].child, src=made[0].src))
        robot.joints.extend(made)
    # Without a weld the model does not say: Gazebo lets it fall, but the weld of an arm is usually in
    # the world that includes it, so the targets' own base rule decides (emit/common/base.py).
    if world_fixed:
        robot.fixed_base = True


def _loop(
    robot: Robot, frames: Frames, node: Node, parent: str, child: str, ir_frame: dict[str, Mat], findings: Findings
) -> None:
    """A second joint into a link closes a kinematic loop: the IR's loop joint, its frame on each side."""
    here = loc(node.file, node.element)
    findings.warn(
        "sdf-loop-joint",
        f"{child!r} already has a parent joint: this joint closes a loop, kept as a loop joint (USD and Isaac "
        "write it; URDF and the SDF target's tree do not)",
        element=f"joint {node.name!r}",
        loc=here,
        stage=STAGE,
    )
    pose = frames.in_model(node.name)
    sides = []
    for link in (parent, child):
        origin = _clean(matrix_pose(np.linalg.inv(ir_frame[link]) @ pose)) if link in ir_frame else None
        sides.append(LoopFrame(link, origin, src=here))
    kind = (node.element.get("type") or "fixed").replace("ball", "spherical")
    robot.loop_joints.append(LoopJoint(node.name, kind, sides[0], sides[1], src=here))


def _sensors(
    robot: Robot,
    frames: Frames,
    links: list[Node],
    joints: list[Node],
    ends: dict[str, tuple[str, str]],
    ir_frame: dict[str, Mat],
    findings: Findings,
) -> None:
    for node in links:
        inv = np.linalg.inv(ir_frame[node.name])
        for el in node.element.iterfind("sensor"):
            sensor = read_sensor(frames, node, el, node.name, inv, findings)
            if sensor is not None:
                robot.sensors.append(sensor)
    names = {j.name for j in robot.joints}
    for node in joints:
        child = ends[node.name][1]
        if child not in ir_frame:
            continue
        inv = np.linalg.inv(ir_frame[child])
        for el in node.element.iterfind("sensor"):
            sensor = read_sensor(frames, node, el, child, inv, findings)
            if sensor is not None:
                if node.name not in names:
                    sensor.parent_joint = None
                robot.sensors.append(sensor)


def _placement(robot: Robot, frames: Frames, model: object, file: str, ir_frame: dict[str, Mat]) -> None:
    """The model's pose in its world, composed with its root's IR frame: where the root link stands."""
    from lxml import etree

    assert isinstance(model, etree._Element)
    pose_el = model.find("pose")
    roots = [link for link in robot.root_links() if link.name != WORLD]
    if pose_el is None and all(np.allclose(ir_frame[r.name], np.eye(4)) for r in roots[:1]):
        return
    if not roots:
        return
    placed = pose_matrix(pose_value(file, pose_el)) @ ir_frame[roots[0].name]
    if not np.allclose(placed, np.eye(4), atol=1e-12):
        robot.placement = _clean(matrix_pose(placed))
