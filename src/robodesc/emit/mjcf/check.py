"""How an MJCF output is checked: MuJoCo loads robot.xml and scene.xml; the numbers are compared
with the IR (masses, inertias, FK, joints, damping, armature, actuators and their gains, mimic and
loop equalities); the scene runs mujoco_menagerie's model test (validation/mujoco_mjcf.py); with a
world, MuJoCo's ground under the terrain's points is the placed one (validation/world_check.py)."""

from __future__ import annotations

import os
import re
import tempfile

from robodesc.emit.common.target import CheckRequest, Emitted
from robodesc.ir.model import Robot
from robodesc.validation.report import ValidationReport


def check_mjcf(robot: Robot, emitted: Emitted, request: CheckRequest) -> ValidationReport | None:
    from robodesc.validation.mujoco_mjcf import validate_mjcf  # MuJoCo loads only when a check runs

    if "mjcf" not in emitted.files:
        return None
    robot_file, scene = emitted.files["mjcf"], emitted.files.get("scene")
    if scene is None:
        return validate_mjcf(robot, robot_file, None, request.options, expected_drives=emitted.extra.get("drives"))
    # The scene includes robot.xml by its final name, and the robot is still staged under another:
    # check a copy of the scene, beside it, that includes the staged file.
    with open(scene, encoding="utf-8") as handle:
        text = handle.read()
    fd, probe = tempfile.mkstemp(prefix=".robodesc-scene-", suffix=".xml", dir=os.path.dirname(scene))
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as handle:
            # One robot is included; several copies are attached from one <model> asset.
            staged = os.path.basename(robot_file)
            text = re.sub(r'<include file="[^"]*"/>', f'<include file="{staged}"/>', text, count=1)
            handle.write(re.sub(r'(<model name="[^"]*" file=)"[^"]*"', rf'\1"{staged}"', text, count=1))
        report = validate_mjcf(robot, robot_file, probe, request.options, expected_drives=emitted.extra.get("drives"))
        if emitted.extra.get("world_probes"):
            from robodesc.validation.world_check import check_mjcf_ground

            check_mjcf_ground(probe, emitted.extra["world_probes"], report)
        report.rename(os.path.basename(probe), os.path.basename(scene))
    finally:
        os.unlink(probe)
    return report
