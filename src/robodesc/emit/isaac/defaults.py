"""What the Isaac folder uses where the user gave no value: the default pose, the spawn height and
the drive gains (docs/isaac.md, "Defaults that stand").

For a floating robot the pose comes from :func:`robodesc.emit.common.stance.choose_stance` and the
spawn height from its lowest collision point; gains come from
:func:`robodesc.emit.common.gains.derived_gains` for every robot. What was chosen is said in
findings. The results are written into :class:`IsaacSettings` as per-joint tables, so the USD, the
importer settings and the Isaac Lab module all carry the same numbers.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Collection, Mapping

from robodesc.emit.common.default_pose import default_pose, given_positions, pose_table, spawn_height
from robodesc.emit.common.gains import fill_default_gains
from robodesc.emit.common.source_drives import apply_source_gains
from robodesc.emit.isaac.settings import IsaacSettings
from robodesc.ir.diagnostics import Findings, Severity
from robodesc.ir.model import Robot

STAGE = "emit:isaac_defaults"


def _raise_welded(robot: Robot, settings: IsaacSettings, q: dict[str, float], findings: Findings) -> None:
    """A welded robot with colliders below z = 0 at its start pose is raised until none is: Isaac Lab's
    scenes put a ground plane at z = 0, and a hand welded at the origin (Allegro's thumb, 4.6 cm
    below) started inside it and pushed on it every step."""
    from robodesc.emit.common.gains import sig4
    from robodesc.emit.common.stance import CLEARANCE, lowest_point

    x, y, z = settings.init_pos
    lowest = lowest_point(robot, q)
    if lowest is None or z + lowest >= 0.0:
        return
    settings.init_pos = (x, y, sig4(CLEARANCE - lowest))
    findings.info(
        "isaac-welded-raised",
        f"welded robot with colliders {-(z + lowest):.3g} m below the ground plane at its start pose: raised to "
        f"z = {settings.init_pos[2]:g} m, so none starts inside it; --init-pos places it otherwise",
        element=f"robot {robot.name!r}",
        stage=STAGE,
    )


def apply_defaults(
    robot: Robot, settings: IsaacSettings, given: Collection[str], findings: Findings
) -> dict[str, float]:
    """Fill the pose, spawn height and gains the user did not give; return the initial position of
    every 1-DOF joint (rad or m), which the USD's joint state and drive targets start from."""
    wanted = given_positions(robot, settings.init_joint_pos)
    floating = not settings.fix_base
    stance = default_pose(robot, wanted, floating, findings, STAGE)
    if "init_joint_pos" not in given and not wanted and (floating or stance.source != "zeros"):
        settings.init_joint_pos = pose_table(robot, stance)
    placed = "init_pos" in given or robot.placement is not None
    if floating and not placed and (height := spawn_height(stance)) is not None:
        x, y, _ = settings.init_pos
        settings.init_pos = (x, y, height)
    if not floating and not placed:
        _raise_welded(robot, settings, stance.positions, findings)
    if settings.target_type != "none" and not ("stiffness" in given and "damping" in given):
        fill_default_gains(robot, settings, given, stance, floating, findings, STAGE)
    if settings.target_type != "none":
        apply_source_gains(robot, settings, given)  # the source's own servos (an MJCF's) over derived gains
    spawned_inside(robot, stance.positions, findings)
    return stance.positions


def spawned_inside(robot: Robot, positions: Mapping[str, float], findings: Findings) -> None:
    """``zero-outside-limits`` asks for a spawn pose inside the limits. The folder has one (the USD's
    joint state, the Isaac Lab module's ``init_state``): for each joint it starts inside them, the
    warning becomes a note saying where it starts."""
    joints = {f"joint {j.name!r}": j for j in robot.joints}
    for i, f in enumerate(findings.items):
        joint = joints.get(f.element)
        if f.code != "zero-outside-limits" or f.severity is not Severity.WARNING or joint is None:
            continue
        q, lim = positions.get(joint.name), joint.limit
        if q is None or lim is None or lim.lower is None or lim.upper is None or not lim.lower <= q <= lim.upper:
            continue
        said = f.message.split(": spawn with")[0]
        message = f"{said}; the Isaac folder spawns it at {q:g}, inside them"
        findings.items[i] = dataclasses.replace(f, severity=Severity.INFO, message=message)
