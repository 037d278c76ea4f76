"""Joint positions the source itself names as the robot's start: an SRDF ``group_state`` beside the
input, or ros2_control's ``initial_value``.

These win over any heuristic (docs/isaac.md, "The default pose"): the robot's authors chose them.
An SRDF is not part of the IR (no frontend reads it), so it is looked up here, next to the file the
robot was read from: ``<dir>/*.srdf`` and ``<dir>/../srdf/*.srdf`` (the ROS package layout, which
example-robot-data follows). It is read with ElementTree, which neither fetches external entities
nor expands nested entities past expat's amplification limit, and only up to 2 MB.
"""

from __future__ import annotations

import glob
import math
import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass

from robodesc.ir.model import Robot

# The names robot packages give a standing or home pose, preferred in this order; when an SRDF has
# none of them, its first group_state is taken.
PREFERRED_STATES = ("standing", "stand", "half_sitting", "home", "ready", "default", "init", "neutral")
_MAX_SRDF_BYTES = 2_000_000


@dataclass(slots=True, frozen=True)
class NamedPose:
    positions: dict[str, float]  # by IR joint name
    source: str  # for the finding: "SRDF group_state 'standing' (go1.srdf)"


def named_pose(robot: Robot) -> NamedPose | None:
    """ros2_control ``initial_value`` first (it is in the IR), then an SRDF group_state."""
    return ros2_control_pose(robot) or srdf_pose(robot)


def ros2_control_pose(robot: Robot) -> NamedPose | None:
    """``<state_interface name="position"><param name="initial_value">`` of every joint that has one.
    Also read from ``robot.initial_positions``, where strip_tags keeps them when it drops the
    ``<ros2_control>`` block (the isaac_sim preset does)."""
    joints = {j.name for j in robot.joints if j.type.dof == 1}
    found: dict[str, float] = {k: v for k, v in robot.initial_positions.items() if k in joints}
    for control in robot.ros2_controls:
        for cj in control.joints:
            for state in cj.state_interfaces:
                text = state.params.get("initial_value")
                if state.name == "position" and text is not None and cj.name in joints:
                    value = _number(text)
                    if value is not None:
                        found[cj.name] = value
    return NamedPose(found, "ros2_control initial_value") if found else None


def srdf_pose(robot: Robot) -> NamedPose | None:
    if not robot.source_file:
        return None
    by_name = {j.name: j.name for j in robot.joints if j.type.dof == 1}
    # After sanitize_names an IR name may differ from the source's; the SRDF uses the source's.
    by_name.update({j.display_name: j.name for j in robot.joints if j.type.dof == 1 and j.display_name})
    for path in _srdf_candidates(robot):
        root = _read(path)
        if root is None:
            continue
        states = {s.get("name", ""): s for s in root.iter("group_state")}
        order = [n for n in PREFERRED_STATES if n in states] + list(states)
        for state_name in order:
            positions: dict[str, float] = {}
            named = 0
            for joint in states[state_name].iter("joint"):
                named += 1
                name = by_name.get(joint.get("name", ""))
                value = _number((joint.get("value") or "").split()[0] if joint.get("value") else "")
                if name is not None and value is not None:
                    positions[name] = value
            # A state written for a sibling model (solo.srdf for solo12) still fits when most of
            # its joints are this robot's; a state for another robot does not.
            if positions and len(positions) * 2 >= named:
                return NamedPose(positions, f"SRDF group_state {state_name!r} ({os.path.basename(path)})")
    return None


def _srdf_candidates(robot: Robot) -> list[str]:
    """SRDF files beside the input or in its package's ``srdf/``: the one named like the input
    first, then those whose ``<robot name>`` is the robot's, then the rest."""
    source = os.path.abspath(str(robot.source_file))
    here = os.path.dirname(source)
    files = sorted({*glob.glob(os.path.join(here, "*.srdf")), *glob.glob(os.path.join(here, "..", "srdf", "*.srdf"))})
    stem = os.path.basename(source).split(".")[0]
    names = {robot.name, robot.display_name}

    def rank(path: str) -> tuple[int, str]:
        if os.path.basename(path).split(".")[0] == stem:
            return (0, path)
        root = _read(path)
        return (1 if root is not None and root.get("name") in names else 2, path)

    return sorted(files, key=rank)


def _read(path: str) -> ET.Element | None:
    try:
        if os.path.getsize(path) > _MAX_SRDF_BYTES:
            return None
        return ET.parse(path).getroot()
    except (OSError, ET.ParseError):
        return None


def _number(text: str) -> float | None:
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None
