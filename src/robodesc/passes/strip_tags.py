"""Remove non-URDF and simulator-specific content, kind by kind.

Kinds (``PassOptions.strip``): ``gazebo`` (``<gazebo>`` blocks, at robot level and inside any
element), ``transmission``, ``ros2_control``, ``dont_collapse`` (the joint attribute), ``contact``
(link-level ``<contact>``) and ``surface`` (collision-level ``<surface>``). One finding per kind
stripped, with the count.
"""

from __future__ import annotations

import math

from robodesc.ir.geometry import Extension
from robodesc.ir.model import Robot
from robodesc.passes.context import PassContext
from robodesc.passes.options import STRIP_KINDS

NAME = "strip_tags"


def _drop(exts: list[Extension], tag: str) -> int:
    before = len(exts)
    exts[:] = [e for e in exts if e.tag != tag]
    return before - len(exts)


def _all_extension_lists(robot: Robot) -> list[list[Extension]]:
    out = [robot.extensions]
    for link in robot.links:
        out.append(link.extensions)
        out.extend(v.extensions for v in link.visuals)
        out.extend(c.extensions for c in link.collisions)
    out.extend(j.extensions for j in robot.joints)
    out.extend(s.extensions for s in robot.sensors)
    out.extend(m.extensions for m in robot.materials)
    return out


def _initial_values(robot: Robot) -> dict[str, float]:
    """ros2_control's ``initial_value`` of each joint's position state interface."""
    out: dict[str, float] = {}
    for control in robot.ros2_controls:
        for joint in control.joints:
            for state in joint.state_interfaces:
                text = state.params.get("initial_value")
                if state.name != "position" or text is None:
                    continue
                try:
                    value = float(text)
                except ValueError:
                    continue
                if math.isfinite(value):
                    out[joint.name] = value
    return out


def strip_tags(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    kinds = ctx.options.strip
    counts: dict[str, int] = dict.fromkeys(STRIP_KINDS, 0)
    if "gazebo" in kinds:
        counts["gazebo"] = sum(_drop(exts, "gazebo") for exts in _all_extension_lists(robot))
    if "transmission" in kinds:
        counts["transmission"] = len(robot.transmissions)
        robot.transmissions = []
        counts["transmission"] += _drop(robot.extensions, "transmission")
    if "ros2_control" in kinds:
        counts["ros2_control"] = len(robot.ros2_controls)
        # The start pose is the robot's data, not ROS plumbing: it outlives the block.
        robot.initial_positions.update(_initial_values(robot))
        robot.ros2_controls = []
    if "dont_collapse" in kinds:
        for joint in robot.joints:
            if joint.dont_collapse is not None:
                counts["dont_collapse"] += 1
                joint.dont_collapse = None
    if "contact" in kinds:
        counts["contact"] = sum(_drop(link.extensions, "contact") for link in robot.links)
    if "surface" in kinds:
        counts["surface"] = sum(_drop(c.extensions, "surface") for link in robot.links for c in link.collisions)
    what = {
        "gazebo": "<gazebo> block",
        "transmission": "<transmission>",
        "ros2_control": "<ros2_control>",
        "dont_collapse": "dont_collapse attribute",
        "contact": "link-level <contact>",
        "surface": "collision-level <surface>",
    }
    for kind in STRIP_KINDS:
        if counts[kind]:
            ctx.info(f"stripped-{kind}", f"removed {counts[kind]} {what[kind]}(s)", element=f"robot {robot.name!r}")
    return robot
