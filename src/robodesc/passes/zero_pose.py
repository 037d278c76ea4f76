"""Report joints whose zero position lies outside their limits (go2's knees: [-2.7227, -0.83776]).

A simulator that spawns the robot at q = 0 starts those joints in violation; the fix is an initial
pose, not a changed limit, so this pass only reports.
"""

from __future__ import annotations

from robodesc.ir.model import Robot
from robodesc.passes.context import PassContext

NAME = "zero_pose"


def zero_pose(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    for joint in robot.joints:
        lim = joint.limit
        if not joint.type.needs_limit or joint.mimic is not None or lim is None:
            continue
        if lim.lower is None or lim.upper is None or lim.lower > lim.upper:
            continue
        if not lim.lower <= 0.0 <= lim.upper:
            ctx.warn(
                "zero-outside-limits",
                f"zero position lies outside the limits [{lim.lower:g}, {lim.upper:g}]: "
                "spawn with an initial pose inside them",
                element=f"joint {joint.name!r}",
                loc=lim.src or joint.src,
            )
    return robot
