"""Reflected rotor inertia (``Joint.armature``, kg·m²) from an ordered rule table.

The first rule whose regex matches (``re.search``) a joint's name gives its armature: a value, or
``J_rotor · N²`` from motor parameters. The table is ``PassOptions.armature``; when that is empty,
``PassOptions.armature_by_robot[robot.name]`` (how the quad_sdk preset knows Spirit's motors and
that go2 has none). Actuated joints no rule matches are reported.
"""

from __future__ import annotations

import re

from robodesc.ir.diagnostics import ConfigError
from robodesc.ir.model import Robot
from robodesc.passes.context import PassContext
from robodesc.passes.options import ArmatureRule

NAME = "armature"


def table_for(robot: Robot, ctx: PassContext) -> tuple[ArmatureRule, ...]:
    if ctx.options.armature:
        return ctx.options.armature
    return tuple(ctx.options.armature_by_robot.get(robot.name, ()))


def armature(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    rules = table_for(robot, ctx)
    if not rules:
        if ctx.options.armature_by_robot:
            known = ", ".join(sorted(ctx.options.armature_by_robot))
            ctx.info(
                "no-armature-table",
                f"no armature table for robot {robot.name!r} (tables exist for {known}); armature left unset",
                element=f"robot {robot.name!r}",
            )
        return robot
    try:
        compiled = [(re.compile(rule.pattern), rule) for rule in rules]
    except re.error as exc:
        raise ConfigError(f"armature table: bad regex: {exc}", element="option 'armature'") from None
    unmatched: list[str] = []
    for joint in robot.actuated_joints():
        for pattern, rule in compiled:
            if pattern.search(joint.name):
                joint.armature = rule.armature()
                ctx.info(
                    "armature-set",
                    f"armature {joint.armature:g} kg·m² (rule {rule.pattern!r})",
                    element=f"joint {joint.name!r}",
                    loc=joint.src,
                )
                break
        else:
            unmatched.append(joint.name)
    if unmatched:
        ctx.warn(
            "armature-unmatched",
            f"{len(unmatched)} actuated joint(s) match no armature rule: {', '.join(unmatched)}",
            element=f"robot {robot.name!r}",
        )
    return robot
