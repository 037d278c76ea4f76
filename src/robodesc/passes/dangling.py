"""Repairs driven by the verifier's findings: an element that names what does not exist is dropped,
and an undeclared ``world`` parent becomes the root link, each with a warning naming what changed.

They run right after the frontend (``pipeline.verify_source``), before the option-driven passes:
what they repair leaves the robot whole again, so the rest of the compile sees a verified tree."""

from __future__ import annotations

import re

from robodesc.ir.diagnostics import Finding, Findings, Severity
from robodesc.ir.model import Link, Robot

# Verifier errors about an element that names something absent, or a shape that cannot exist: the
# element is dropped (with a warning) and the rest of the robot is compiled as written.
_LABEL = re.compile(r"^(\w+) '(.*)'$")
_SHAPE = re.compile(r"^link '(.*)' (visual|collision) (\d+)$")


def add_world_root(robot: Robot, errors: list[Finding], findings: Findings) -> bool:
    """Joints whose parent is an undeclared link ``world``: Gazebo and Drake read it as the world
    (the robot welded or jointed to the ground), urdfdom refuses it. Add that link, empty, as the
    root, and say so."""
    world_joints = [f for f in errors if f.code == "dangling-link" and f.message.startswith("parent link 'world' ")]
    if not world_joints or any(link.name == "world" for link in robot.links):
        return False
    robot.links.insert(0, Link(name="world", src=world_joints[0].loc))
    findings.add(
        Severity.WARNING,
        "world-link",
        "parent link 'world' is not declared: added as an empty root link, as Gazebo and Drake read it "
        "(urdfdom refuses the file)",
        element=world_joints[0].element,
        loc=world_joints[0].loc,
        stage="verify",
    )
    return True


def drop_dangling(robot: Robot, errors: list[Finding], findings: Findings) -> list[Finding]:
    """Drop the elements these errors are about where the robot stays whole without them; return
    the errors that remain. Each drop is a warning naming the element and what was lost."""
    fatal: list[Finding] = []
    shapes: set[tuple[str, str, int]] = set()
    for f in errors:
        what = _dropped(robot, f, shapes)
        if what is None:
            fatal.append(f)
            continue
        findings.add(Severity.WARNING, f.code, f"{f.message}; {what}", element=f.element, loc=f.loc, stage=f.stage)
    for link in robot.links:
        link.visuals = [x for i, x in enumerate(link.visuals) if (link.name, "visual", i) not in shapes]
        link.collisions = [x for i, x in enumerate(link.collisions) if (link.name, "collision", i) not in shapes]
    return fatal


def _dropped(robot: Robot, f: Finding, shapes: set[tuple[str, str, int]]) -> str | None:
    if f.code == "bad-geometry":
        shape = _SHAPE.match(f.element)
        if shape is None:
            return None
        shapes.add((shape.group(1), shape.group(2), int(shape.group(3))))
        return f"this {shape.group(2)} was dropped (no consumer can build it)"
    label = _LABEL.match(f.element)
    if label is None:
        return None
    kind, name = label.group(1), label.group(2)
    if kind == "joint" and f.code in ("dangling-mimic", "bad-mimic"):
        for joint in robot.joints:
            if joint.name == name:
                joint.mimic = None
        return "its <mimic> was dropped: the joint moves on its own (urdfdom and Gazebo ignore such a mimic)"
    if kind == "transmission" and f.code == "dangling-joint":
        robot.transmissions = [t for t in robot.transmissions if t.name != name]
        return "the transmission was dropped (ros_control would refuse it)"
    if kind == "ros2_control" and f.code == "dangling-joint":
        joints = {j.name for j in robot.joints}
        for rc in robot.ros2_controls:
            if rc.name == name:
                rc.joints = [cj for cj in rc.joints if cj.name in joints]
        return "that <joint> entry was dropped from the ros2_control block"
    if kind == "sensor" and f.code in ("dangling-joint", "dangling-link"):
        robot.sensors = [x for x in robot.sensors if x.name != name]
        return "the sensor was dropped"
    if kind == "fixed_frame" and f.code == "dangling-link":
        robot.fixed_frames = [x for x in robot.fixed_frames if x.name != name]
        return "the fixed frame was dropped"
    if kind == "loop_joint" and f.code == "dangling-link":
        robot.loop_joints = [x for x in robot.loop_joints if x.name != name]
        return "the loop joint was dropped"
    return None
