"""How an SDF output is checked: Drake's strict parser reads it and the numbers are compared with
the IR. Drake models kinematic trees only, so a robot with loop joints is checked as its tree."""

from __future__ import annotations

import dataclasses

from robodesc.emit.common.target import CheckRequest, Emitted
from robodesc.ir.model import Robot
from robodesc.validation.report import Status, ValidationReport


def check_sdf(robot: Robot, emitted: Emitted, request: CheckRequest) -> ValidationReport | None:
    from robodesc.emit.sdf.emitter import build_sdf
    from robodesc.validation.drake_sdf import validate_sdf  # the consumer loads only when a check runs

    if emitted.text is None:
        return None
    text = emitted.text
    options = emitted.extra.get("sdf_options")
    copies = options is not None and bool(options.copy_poses)
    if robot.loop_joints or copies:
        # Drake checks the tree, and one copy of the robot: its joints are looked up by name, which
        # several copies share (the copies are the first one's elements, copied).
        text = build_sdf(
            robot, dataclasses.replace(emitted.extra["sdf_options"], loop_joints=False, copy_poses=[])
        ).text
    report = validate_sdf(
        robot,
        text,
        request.options,
        link_names=emitted.extra.get("link_names"),
        joint_names=emitted.extra.get("joint_names"),
    )
    for loop in robot.loop_joints:
        report.add(
            "loop-joint",
            Status.SKIP,
            f"loop_joint {loop.name!r}",
            "Drake models kinematic trees only; the tree was checked without this closure",
        )
    return report
