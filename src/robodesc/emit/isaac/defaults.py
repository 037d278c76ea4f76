"""What the Isaac folder uses where the user gave no value: the default pose, the spawn height and
the drive gains (docs/isaac.md, "Defaults that stand").

For a floating robot the pose comes from :func:`robodesc.emit.common.stance.choose_stance` and the
spawn height from its lowest collision point; gains come from
:func:`robodesc.emit.common.gains.derived_gains` for every robot. What was chosen is said in
findings. The results are written into :class:`IsaacSettings` as per-joint tables, so the USD, the
importer settings and the Isaac Lab module all carry the same numbers.
"""

from __future__ import annotations

import re
from collections.abc import Collection

from robodesc.emit.common.gains import fill_default_gains, sig4
from robodesc.emit.common.stance import CLEARANCE, Stance, choose_stance, complete
from robodesc.emit.isaac.settings import IsaacSettings
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot
from robodesc.ir.rules import lookup

STAGE = "emit:isaac_defaults"


def apply_defaults(
    robot: Robot, settings: IsaacSettings, given: Collection[str], findings: Findings
) -> dict[str, float]:
    """Fill the pose, spawn height and gains the user did not give; return the initial position of
    every 1-DOF joint (rad or m), which the USD's joint state and drive targets start from."""
    wanted = {
        j.name: value
        for j in robot.joints
        if j.type.dof == 1
        and settings.init_joint_pos
        and (value := lookup(settings.init_joint_pos, j.name, "init_joint_pos")) is not None
    }
    floating = not settings.fix_base
    if floating:
        stance = choose_stance(robot, wanted or None)
        _report_pose(robot, stance, findings)
        if "init_joint_pos" not in given and not wanted:
            settings.init_joint_pos = {re.escape(name): value for name, value in _actuated(robot, stance).items()}
        if "init_pos" not in given and robot.placement is None and stance.lowest_z is not None:
            x, y, _ = settings.init_pos
            settings.init_pos = (x, y, sig4(CLEARANCE - stance.lowest_z))
    else:
        stance = Stance(complete(robot, wanted), "init_joint_pos" if wanted else "zeros")
    if settings.target_type != "none" and not ("stiffness" in given and "damping" in given):
        fill_default_gains(robot, settings, given, stance, floating, findings, STAGE)
    return stance.positions


def _actuated(robot: Robot, stance: Stance) -> dict[str, float]:
    return {j.name: stance.positions[j.name] for j in robot.actuated_joints() if j.name in stance.positions}


def _report_pose(robot: Robot, stance: Stance, findings: Findings) -> None:
    element = f"robot {robot.name!r}"
    bent = {k: v for k, v in _actuated(robot, stance).items() if v != 0.0}
    shown = ", ".join(f"{k} {v:.3g}" for k, v in list(bent.items())[:12]) + (" ..." if len(bent) > 12 else "")
    height = "" if stance.lowest_z is None else f"; lowest collision point {-stance.lowest_z:.3f} m below the root"
    if stance.skipped:
        findings.warn(
            "default-pose-not-stance",
            f"the named pose {stance.skipped}; not used as the default pose, which comes from {stance.source}",
            element=element,
            stage=STAGE,
        )
    if stance.source == "zeros":
        findings.warn(
            "default-pose-zeros",
            "floating robot with no named pose and no legs the heuristic recognises: it starts with every "
            f"joint at 0 (clamped into its limits) and may not stand; give --init-joint-pos{height}",
            element=element,
            stage=STAGE,
        )
        return
    legs = f", {len(stance.legs)} legs ({', '.join(leg.foot for leg in stance.legs)})" if stance.legs else ""
    findings.info(
        "default-pose",
        f"initial joint positions from {stance.source}{legs}: {shown or 'all 0'}{height}",
        element=element,
        stage=STAGE,
    )
