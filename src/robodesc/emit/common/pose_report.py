"""The finding that says which default pose a floating robot starts from, shared by the targets
that choose one (the Isaac folder, MJCF's home keyframe)."""

from __future__ import annotations

from robodesc.emit.common.stance import Stance
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot


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
