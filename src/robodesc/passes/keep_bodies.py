"""Mark fixed joints whose child must stay its own body when Isaac merges fixed joints.

Isaac's importer (``merge_fixed_joints``) folds a fixed child into its parent unless the joint says
``dont_collapse="true"``. A child that carries a sensor, a fixed frame or one end of a loop joint
would lose the prim those hang on, so such joints get ``dont_collapse``. An explicit
``dont_collapse="false"`` from the input is respected (and reported).

>>> keep_bodies(robot, ctx)   # joint 'tool_mount' (fixed) → dont_collapse, its child has sensor 'cam'
"""

from __future__ import annotations

from robodesc.ir.model import JointType, Robot
from robodesc.passes.context import PassContext

NAME = "keep_bodies"


def keep_bodies(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    needs: dict[str, str] = {}
    for sensor in robot.sensors:
        needs.setdefault(sensor.parent, f"sensor {sensor.name!r}")
    for frame in robot.fixed_frames:
        needs.setdefault(frame.parent, f"fixed_frame {frame.name!r}")
    for loop in robot.loop_joints:
        for side in (loop.link1, loop.link2):
            needs.setdefault(side.link, f"loop_joint {loop.name!r}")
    for joint in robot.joints:
        if joint.type is not JointType.FIXED or joint.child not in needs:
            continue
        label = f"joint {joint.name!r}"
        if joint.dont_collapse is False:
            ctx.warn(
                "collapse-loses-prim",
                f'dont_collapse="false" kept as given, but {needs[joint.child]} hangs on link {joint.child!r} '
                "and is lost if Isaac merges this joint",
                element=label,
                loc=joint.src,
            )
        elif joint.dont_collapse is None:
            joint.dont_collapse = True
            ctx.info(
                "dont-collapse",
                f'dont_collapse="true": {needs[joint.child]} hangs on link {joint.child!r}',
                element=label,
                loc=joint.src,
            )
    return robot
