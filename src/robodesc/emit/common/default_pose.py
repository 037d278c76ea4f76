"""The pose a target starts a robot in where the user gave none, shared by the targets that choose
one (the Isaac folder's initial state, MJCF's home keyframe): the given joints, else for a floating
robot its stance (emit/common/stance.py), said in a finding, with the spawn height it needs, and for
a welded one the pose its source names (an SRDF group_state, ros2_control initial values)."""

from __future__ import annotations

import re
from collections.abc import Mapping

from robodesc.emit.common.gains import sig4
from robodesc.emit.common.named_pose import named_pose
from robodesc.emit.common.stance import CLEARANCE, Stance, choose_stance, complete
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot
from robodesc.ir.rules import lookup


def given_positions(robot: Robot, init_joint_pos: Mapping[str, float] | None) -> dict[str, float]:
    """The 1-DOF joints the user's ``init_joint_pos`` table names, by joint name."""
    if not init_joint_pos:
        return {}
    return {
        j.name: value
        for j in robot.joints
        if j.type.dof == 1 and (value := lookup(init_joint_pos, j.name, "init_joint_pos")) is not None
    }


def default_pose(robot: Robot, wanted: Mapping[str, float], floating: bool, findings: Findings, stage: str) -> Stance:
    """A floating robot's stance (the wanted joints, else a named pose, the legged heuristic or zeros),
    reported; a fixed robot's wanted joints, else the pose its source names (SRDF, ros2_control: an
    arm's home, as for legs; Panda's zero pose is outside joint 4's range and was clamped), else zeros."""
    if not floating:
        if wanted:
            return Stance(complete(robot, wanted), "init_joint_pos")
        named = named_pose(robot)
        if named is None:
            return Stance(complete(robot, {}), "zeros")
        stance = Stance(complete(robot, named.positions), named.source)
        report_pose(robot, stance, findings, stage)
        return stance
    stance = choose_stance(robot, wanted or None)
    report_pose(robot, stance, findings, stage)
    return stance


def pose_table(robot: Robot, stance: Stance) -> dict[str, float]:
    """The stance as an ``init_joint_pos`` table (escaped names) of the actuated joints."""
    return {re.escape(name): value for name, value in actuated_positions(robot, stance).items()}


def spawn_height(stance: Stance) -> float | None:
    """The root height that puts the stance's lowest collision point CLEARANCE above the ground."""
    return None if stance.lowest_z is None else sig4(CLEARANCE - stance.lowest_z)


def actuated_positions(robot: Robot, stance: Stance) -> dict[str, float]:
    return {j.name: stance.positions[j.name] for j in robot.actuated_joints() if j.name in stance.positions}


def report_pose(robot: Robot, stance: Stance, findings: Findings, stage: str) -> None:
    """Info for a chosen pose; a warning when nothing better than zeros was found."""
    element = f"robot {robot.name!r}"
    bent = {k: v for k, v in actuated_positions(robot, stance).items() if v != 0.0}
    shown = ", ".join(f"{k} {v:.3g}" for k, v in list(bent.items())[:12]) + (" ..." if len(bent) > 12 else "")
    height = "" if stance.lowest_z is None else f"; lowest collision point {-stance.lowest_z:.3f} m below the root"
    if stance.skipped:
        findings.warn(
            "default-pose-not-stance",
            f"the named pose {stance.skipped}; not used as the default pose, which comes from {stance.source}",
            element=element,
            stage=stage,
        )
    if stance.source == "zeros":
        findings.warn(
            "default-pose-zeros",
            "floating robot with no named pose and no legs the heuristic recognises: it starts with every "
            f"joint at 0 (clamped into its limits) and may not stand; give --init-joint-pos{height}",
            element=element,
            stage=stage,
        )
        return
    legs = f", {len(stance.legs)} legs ({', '.join(leg.foot for leg in stance.legs)})" if stance.legs else ""
    findings.info(
        "default-pose",
        f"initial joint positions from {stance.source}{legs}: {shown or 'all 0'}{height}",
        element=element,
        stage=stage,
    )
