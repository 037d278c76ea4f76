"""Links without mass, given URDF's meaning in targets that cannot carry a massless body.

URDF lets a link have no ``<inertial>`` (or a zero mass): it has no mass of its own and is carried by
what it is fixed to. Gazebo lumps such a link into its fixed parent. A UsdPhysics reader cannot be
told "no mass": a rigid body without ``physics:mass`` gets one from its colliders at 1000 kg/m³
(PhysX gives 1 kg to one without colliders), and ``physics:mass = 0`` means the same "compute it".
MuJoCo and Drake refuse a massless body that moves.

The links are taken in *fixed groups*: the links joined by fixed joints, which move as one rigid body.

- ``mass_from_colliders``: a group that moves (its top link hangs on a moving joint) and has no mass
  at all would be a dead body: each of its links with geometry gets the mass of that geometry at
  ``density`` (warning ``mass-from-geometry``, naming the link). A group with mass, or the root's
  group (welded or floating, its mass is the source's), never gets a mass from its geometry.
- ``placeholder_masses``: every link still massless gets :data:`PLACEHOLDER_MASS` at its origin.
  In a group with mass it is taken from the group's heaviest link, whose inertial becomes the old
  one minus the placeholders (mass, centre and tensor), so the group's total mass, centre of mass and
  inertia are the source's exactly and no reader lumps anything differently. Only a group with no
  mass to borrow from (the root's, or a moving one without geometry) adds the placeholder (a warning
  says how much).
"""

from __future__ import annotations

from typing import Any

from robodesc.ir.model import Robot
from robodesc.passes.context import PassContext
from robodesc.passes.massless_common import NAME, PLACEHOLDER_GYRATION, PLACEHOLDER_MASS, massless_link

__all__ = ["NAME", "PLACEHOLDER_GYRATION", "PLACEHOLDER_MASS", "massless", "massless_link"]


def massless(robot: Robot, ctx: PassContext) -> Robot:
    """The pass. A robot whose every link has a mass has nothing to do, and does not load the group
    maths (numpy: a USD compile of a small robot must not pay for it, tests/foundation/test_rigid_math)."""
    ctx.stage = NAME
    if not any(massless_link(link) for link in robot.links):
        return robot
    from robodesc.passes.massless_groups import apply

    return apply(robot, ctx)


def __getattr__(name: str) -> Any:
    # fixed_groups, carried_by, FixedGroup: the group maths, loaded on first use.
    if name in ("fixed_groups", "carried_by", "FixedGroup"):
        from robodesc.passes import massless_groups

        return getattr(massless_groups, name)
    raise AttributeError(name)
