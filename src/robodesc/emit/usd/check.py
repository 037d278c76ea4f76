"""How a USD output is checked: usd-core's UsdPhysics parser (and MuJoCo's USD importer where it is
installed) read it back and the numbers are compared with the IR."""

from __future__ import annotations

from robodesc.emit.common.target import CheckRequest, Emitted
from robodesc.ir.model import Robot
from robodesc.validation.report import ValidationReport


def check_usd(robot: Robot, emitted: Emitted, request: CheckRequest) -> ValidationReport | None:
    from robodesc.validation.mujoco_usd import validate_usd  # the consumer loads only when a check runs

    if "usd" not in emitted.files:
        return None
    report = validate_usd(robot, emitted.files["usd"], request.options)
    if "world" in emitted.files and "world_expect" in emitted.extra:
        from robodesc.validation.world_check import check_usd_world

        check_usd_world(emitted.files["world"], emitted.files["usd"], emitted.extra["world_expect"], report)
    return report
