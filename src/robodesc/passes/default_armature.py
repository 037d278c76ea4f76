"""Armature (reflected rotor inertia, kg·m²) for actuated revolute joints the source gives none.

A motor's rotor, seen through its gearbox, adds ``J_rotor·N²`` to the inertia a joint moves. URDF
has no word for it, and without it a light distal joint (a wrist, a finger) has almost nothing to
move: under random control fr3's joint 7 whipped at 201 rad/s against menagerie's 24 (issue 35).
The presets that simulate (``mjcf``, ``isaac_sim``) therefore estimate it from the one motor number
a URDF does give, the effort limit:

    armature = ARMATURE_PER_EFFORT · effort^1.5        (effort in N·m)

A gear motor's torque grows with its rotor's size faster than linearly and its reflected inertia
with the square of the gear ratio; the exponent and the constant are fitted to the class values
hand-tuned models use: mujoco_menagerie's Unitree Go1 (0.01 at 23.7 N·m; the formula gives 0.0115),
Franka (0.1 for every joint, 12–87 N·m: 0.004–0.08), UR5e (0.1, 28–150 N·m: 0.015–0.18), and
Quad-SDK's Spirit motors (J_rotor·N² = 4.4e-3 at 21 N·m and 1.8e-2 at 40 N·m: 0.0096, 0.025).
Joints with no effort limit and prismatic joints (a screw's lead is unknown) get none and are listed.

Source values always win (``Joint.armature`` set by the URDF's ``<dynamics armature>`` or by the
``armature`` pass's rules, which run before this one); ``--no-default-armature`` turns it off.
"""

from __future__ import annotations

from robodesc.ir.model import Robot
from robodesc.passes.context import PassContext

NAME = "default_armature"

ARMATURE_PER_EFFORT = 1e-4  # kg·m² per (N·m)^1.5
EXPONENT = 1.5


def estimate(effort: float) -> float:
    """The reflected rotor inertia (kg·m²) of a motor with this peak torque (N·m)."""
    return float(f"{ARMATURE_PER_EFFORT * effort**EXPONENT:.3g}")


def default_armature(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    set_: list[str] = []
    skipped: list[str] = []
    for joint in robot.actuated_joints():
        if joint.armature is not None or joint.type.dof != 1:
            continue
        effort = joint.limit.effort if joint.limit is not None else None
        if not joint.type.is_angular or effort is None or effort <= 0:
            skipped.append(joint.name)
            continue
        joint.armature = estimate(effort)
        set_.append(f"{joint.name} {joint.armature:g}")
    if set_:
        ctx.info(
            "armature-default",
            f"armature estimated from the effort limit ({ARMATURE_PER_EFFORT:g}·effort^{EXPONENT:g} kg·m², "
            f"docs/passes.md; --no-default-armature turns it off) for {len(set_)} joint(s): {', '.join(set_)}",
            element=f"robot {robot.name!r}",
        )
    if skipped:
        ctx.info(
            "armature-default-skipped",
            f"no armature estimated (prismatic, or no effort limit) for {len(skipped)} joint(s): {', '.join(skipped)}",
            element=f"robot {robot.name!r}",
        )
    return robot
