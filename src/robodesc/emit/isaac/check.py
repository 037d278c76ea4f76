"""How the Isaac folder is checked: its URDF through MuJoCo (as every folder holding a URDF), and its
USD, the file Isaac Sim opens, in PhysX, the engine Isaac Sim runs (skipped without a PhysX
interpreter)."""

from __future__ import annotations

from robodesc.emit.common.target import CheckRequest, Emitted
from robodesc.emit.urdf import check_urdf
from robodesc.ir.model import Robot
from robodesc.validation.report import ValidationReport


def check_isaac(robot: Robot, emitted: Emitted, request: CheckRequest) -> ValidationReport | None:
    from robodesc.validation.physx_usd import validate_usd_physx  # the consumer loads only when a check runs

    report = check_urdf(robot, emitted, request)
    usd = emitted.files.get("usd")
    if usd is None or not request.options.physx:
        return report
    physx = validate_usd_physx(robot, usd, request.options, target="isaac")
    if report is None:
        return physx
    if "physx" in physx.info:
        report.consumer = f"{report.consumer} + {physx.consumer}"
    report.extend(physx)
    return report
