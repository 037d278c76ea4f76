"""Write the joint damping and friction a URDF leaves unsaid as the zeros Gazebo (ODE) simulates.

An unspecified ``<dynamics>`` is 0 in ODE and DART, but a simulator that fills its own default
differs: PhysX joints get about 0.1 through Isaac's importer. Under ``--preset gazebo_parity`` the
IR says 0 explicitly, so every target writes the number Gazebo used (docs/contact.md).
"""

from __future__ import annotations

from robodesc.ir.model import Dynamics, JointType, Robot
from robodesc.passes.context import PassContext

NAME = "explicit_damping"


def explicit_damping(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    filled = []
    for joint in robot.joints:
        if joint.type not in (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC) or joint.mimic:
            continue
        dynamics = joint.dynamics or Dynamics()
        if dynamics.damping is None or dynamics.friction is None:
            dynamics.damping = 0.0 if dynamics.damping is None else dynamics.damping
            dynamics.friction = 0.0 if dynamics.friction is None else dynamics.friction
            joint.dynamics = dynamics
            filled.append(joint.name)
    if filled:
        ctx.info(
            "explicit-damping",
            f"joint damping/friction the source leaves unsaid written as 0, as Gazebo simulates them: "
            f"{len(filled)} joint(s) ({', '.join(filled[:4])}{' ...' if len(filled) > 4 else ''})",
            element=f"robot {robot.name!r}",
        )
    return robot
