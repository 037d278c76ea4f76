"""A planar four-bar linkage (crank-rocker) built with robodesc's Python composition API.

The tree is ground → crank → coupler and ground → rocker; a loop joint closes coupler to rocker.
Every pose is given in the composition (world) frame; the builder derives the joint origins.
``examples/four_bar.yaml`` is the same robot in the YAML format.

Run ``PYTHONPATH=src python examples/four_bar.py`` to print a summary.
"""

from __future__ import annotations

import math

from robodesc.frontends.compose import builder as rb
from robodesc.frontends.compose.shapes import box, cylinder
from robodesc.frontends.compose.units import deg
from robodesc.ir.model import Robot

# Pivots on the ground, and the two moving pivots at the zero pose (x, z in metres, y = 0).
CRANK_PIVOT = (0.0, 0.0)
ROCKER_PIVOT = (0.4, 0.0)
CRANK_TIP = (0.0, 0.1)
ROCKER_TIP = (0.4, 0.3)
BAR = 0.02  # bar cross-section (m)
DENSITY = 2700.0  # aluminium, kg/m³


def _bar(a: tuple[float, float], b: tuple[float, float]) -> rb.Part:
    """A box from pivot ``a`` to pivot ``b``, in the frame of a link that sits at ``a``."""
    dx, dz = b[0] - a[0], b[1] - a[1]
    length = math.hypot(dx, dz)
    # Rotating +x about +y by -atan2(dz, dx) points it from a towards b.
    pitch = -math.atan2(dz, dx)
    return rb.Part(
        box(length, BAR, BAR),
        origin=rb.pose(xyz=(dx / 2, 0.0, dz / 2), rpy=(0.0, pitch, 0.0)),
        density=DENSITY,
        color="#c0c8d0",
    )


def build() -> Robot:
    b = rb.RobotBuilder("four_bar", fixed_base=True)
    b.link("ground", box(0.5, 0.06, 0.02), mass=5.0, color="#404040", pose=(0.2, 0.0, -0.02), frame="world")
    b.link("crank", _bar(CRANK_PIVOT, CRANK_TIP), pose=(CRANK_PIVOT[0], 0.0, CRANK_PIVOT[1]), frame="world")
    b.link("coupler", _bar(CRANK_TIP, ROCKER_TIP), pose=(CRANK_TIP[0], 0.0, CRANK_TIP[1]), frame="world")
    b.link("rocker", _bar(ROCKER_PIVOT, ROCKER_TIP), pose=(ROCKER_PIVOT[0], 0.0, ROCKER_PIVOT[1]), frame="world")
    b.link("crank_hub", cylinder(0.02, 0.03), mass=0.05, color="#a03030")

    b.joint("crank_joint", "revolute", "ground", "crank", axis="y", limits=deg(-180, 180), effort=5, velocity=6)
    b.joint("coupler_joint", "continuous", "crank", "coupler", axis="y")
    b.joint("rocker_joint", "continuous", "ground", "rocker", axis="y")
    b.joint("hub_mount", "fixed", "crank", "crank_hub", origin=rb.pose(rpy=(90, 0, 0), unit="deg"))
    # Isaac builds only spherical loop joints; in a planar linkage the extra freedom is idle.
    b.loop_joint(
        "coupler_rocker",
        "coupler",
        "rocker",
        type="spherical",
        origin1=(ROCKER_TIP[0], 0.0, ROCKER_TIP[1]),
        origin2=(ROCKER_TIP[0], 0.0, ROCKER_TIP[1]),
        frame="world",
    )
    b.actuator("crank_joint", interface="hardware_interface/EffortJointInterface", reduction=30)
    return b.build()


if __name__ == "__main__":
    robot = build()
    print(f"{robot.name}: {len(robot.links)} links, {len(robot.joints)} joints, {len(robot.loop_joints)} loop joint")
    for joint in robot.joints:
        print(f"  {joint.name}: {joint.type.value} {joint.parent} -> {joint.child} at {joint.origin}")
