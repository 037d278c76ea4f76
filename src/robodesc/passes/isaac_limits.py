"""Lowering for Isaac's URDF importer, which rejects revolute and prismatic joints without
``<limit>`` and has crashed on an empty root link (no inertial, no geometry).

- A revolute joint without limit gets [-π, π], a prismatic one [-1, 1] m; effort and velocity get
  ``DEFAULT_EFFORT``/``DEFAULT_VELOCITY`` when missing. Continuous joints stay continuous.
- A range with no width (``lower >= upper``) gets the same placeholder range: CAD exporters write
  ``<limit lower="0" upper="0" effort="0" velocity="0"/>`` for "not set" (SolidWorks, on the double
  pendulums and Stretch's gripper fingers), MuJoCo reads such a range as no limit, and Newton's
  MuJoCo backend refuses the file ("range[0] should be smaller than range[1]").
- Effort and velocity both 0, on any joint (continuous too), are that exporter's "not set" as well:
  a drive with no force, and a [0, 0] force range Newton's MuJoCo backend refuses; they get the
  defaults.
- An empty root link gets a tiny inertial (0.001 kg, 1e-6 kg·m² diagonal at its origin).
Each change is a finding.
"""

from __future__ import annotations

import math

from robodesc.ir.geometry import Inertia, Inertial, Pose
from robodesc.ir.model import JointType, Limit, Robot
from robodesc.passes.context import PassContext

NAME = "isaac_limits"
DEFAULT_EFFORT = 1000.0  # N·m or N
DEFAULT_VELOCITY = 100.0  # rad/s or m/s


def isaac_limits(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    for joint in robot.joints:
        lim0 = joint.limit
        if lim0 is not None and lim0.effort == 0 and lim0.velocity == 0:
            # An exporter's "not set": Isaac's drive would give no force, and Newton's MuJoCo
            # backend refuses the [0, 0] force range (double_pendulum_continuous).
            lim0.effort, lim0.velocity = DEFAULT_EFFORT, DEFAULT_VELOCITY
            ctx.warn(
                "limit-completed",
                f"effort and velocity are 0 (an exporter's 'not set'; a drive with no force): given effort "
                f"{DEFAULT_EFFORT:g}, velocity {DEFAULT_VELOCITY:g}",
                element=f"joint {joint.name!r}",
                loc=lim0.src,
            )
        if not joint.type.needs_limit:
            continue
        label = f"joint {joint.name!r}"
        span = math.pi if joint.type is JointType.REVOLUTE else 1.0
        if joint.limit is None:
            joint.limit = Limit(lower=-span, upper=span, effort=DEFAULT_EFFORT, velocity=DEFAULT_VELOCITY)
            ctx.warn(
                "limit-added",
                f"{joint.type.value} joint without <limit> (Isaac rejects it): given [{-span:g}, {span:g}], "
                f"effort {DEFAULT_EFFORT:g}, velocity {DEFAULT_VELOCITY:g}",
                element=label,
                loc=joint.src,
            )
            continue
        lim = joint.limit
        if lim.lower is not None and lim.upper is not None and lim.lower >= lim.upper:
            ctx.warn(
                "limit-widened",
                f"range [{lim.lower:g}, {lim.upper:g}] has no width (an exporter's 'not set'; MuJoCo reads it "
                f"as no limit, Newton's MuJoCo backend refuses it): given [{-span:g}, {span:g}]",
                element=label,
                loc=lim.src,
            )
            lim.lower, lim.upper = -span, span
        added = []
        if joint.limit.effort is None:
            joint.limit.effort = DEFAULT_EFFORT
            added.append(f"effort {DEFAULT_EFFORT:g}")
        if joint.limit.velocity is None:
            joint.limit.velocity = DEFAULT_VELOCITY
            added.append(f"velocity {DEFAULT_VELOCITY:g}")
        if added:
            ctx.warn("limit-completed", "<limit> completed: " + ", ".join(added), element=label, loc=joint.limit.src)
    for root in robot.root_links():
        if root.inertial is None and not root.visuals and not root.collisions:
            root.inertial = Inertial(mass=0.001, origin=Pose(), inertia=Inertia(ixx=1e-6, iyy=1e-6, izz=1e-6))
            ctx.warn(
                "empty-root-link",
                "root link has no inertial and no geometry (crashes Isaac's importer): given 0.001 kg, 1e-6 kg·m² diagonal",
                element=f"link {root.name!r}",
                loc=root.src,
            )
    return robot
