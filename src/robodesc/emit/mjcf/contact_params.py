"""Contact in MJCF: a collision geom's ``friction``, ``solref`` and ``solimp`` from the IR's
contact (Gazebo's ODE vocabulary, SI; docs/contact.md).

- ``friction="slide torsion roll"``: ``mu`` (MuJoCo has one isotropic coefficient: a different
  ``mu2`` or an ``fdir1`` is a warning), ``torsional`` and ``rolling`` (m), MuJoCo's defaults
  (0.005, 0.0001) where not given.
- ``solref`` in MuJoCo's positive form (time constant, damping ratio), from ``kp`` and ``kd``:
  MuJoCo's contact is a mass-spring-damper in the constraint's own units (acceleration), so N/m
  and N·s/m become a natural frequency and a damping ratio through the mass a contact carries,
  taken as the robot's mass shared by its links that carry contact parameters (a quadruped's toes:
  a quarter each): ``omega = sqrt(kp / m)``, ``dampratio = kd / (2 sqrt(kp m))``. MuJoCo's
  reference acceleration has damping ``b = 2 / (dmax timeconst)`` and stiffness ``k = d / (dmax^2
  timeconst^2 dampratio^2)`` (its "Solver parameters"), so at full impedance ``b = 2 dampratio
  omega`` and ``k = omega^2`` need ``timeconst = 1 / (dampratio omega)`` (= 2 m / kd): not the
  spring's period 2 pi / omega, which would make the contact (2 pi dampratio)^2 times softer. The
  positive form, rather than MuJoCo's direct (negative) stiffness and damping, because it stays
  valid whatever the timestep: MuJoCo clamps a time constant below two timesteps. ``kd`` not
  given is SDF's default, 1 N·s/m.
- ``min_depth``, ``max_vel``: MuJoCo's soft contacts always penetrate a little and correct at the
  rate solref sets; there is no allowed depth or correction speed to write (left out).
- ``friction_combine``: MuJoCo takes the larger friction of two geoms, or the higher priority
  geom's friction, solref and solimp. ``min`` (ODE's rule, ``--preset gazebo_parity``) writes
  ``priority="1"`` on every collision geom of the robot; ``max`` is MuJoCo's rule (nothing written).
- ``restitution``: MuJoCo has none for hard contacts; a bounce comes from an underdamped solref.
  Restitution 0 (the common case) is a damping ratio of at least 1; anything else is a warning.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

from robodesc.emit.mjcf.context import MjcfContext, num
from robodesc.ir.contact import Contact
from robodesc.ir.model import Link

TORSION = 0.005  # MuJoCo's default torsional friction (m)
ROLL = 0.0001  # MuJoCo's default rolling friction (m)


def contact_mass(ctx: MjcfContext) -> float:
    """The mass one contact carries: the robot's, shared by its links that carry contact parameters."""
    bearing = [
        link
        for link in ctx.robot.links
        if link.contact is not None or any(c.contact is not None for c in link.collisions)
    ]
    return max(ctx.robot.total_mass(), 1e-6) / max(len(bearing), 1)


# MuJoCo's default time step (s): robodesc's MJCF writes none.
MUJOCO_TIMESTEP = 0.002

# SDF's default contact damping (N·s/m), which Gazebo's ODE applies when kd is not given.
SDF_KD = 1.0


def solref(kp: float, kd: float | None, mass: float, no_bounce: bool) -> tuple[float, float]:
    """MuJoCo's (timeconst, dampratio) for a spring ``kp`` (N/m) and damper ``kd`` (N·s/m) on
    ``mass`` (kg): the pair whose reference acceleration is ``-(kd v + kp x) / mass``. Without a
    bounce (restitution 0) the damping ratio is at least 1."""
    omega = math.sqrt(kp / mass)
    ratio = (kd if kd is not None and kd > 0 else SDF_KD) / (2.0 * math.sqrt(kp * mass))
    if no_bounce:
        ratio = max(ratio, 1.0)
    return 1.0 / (ratio * omega), ratio


def apply_contact(ctx: MjcfContext, el: ET.Element, link: Link, contact: Contact | None, label: str) -> None:
    if ctx.options.friction_combine == "min":
        # The robot's surface wins against priority-0 geoms (a scene's floor): ODE's minimum when
        # the floor grips at least as much, and the robot's own solref rather than a mix with it.
        el.set("priority", "1")
    if contact is None:
        return
    c = contact
    if c.mu is not None or c.torsional is not None or c.rolling is not None:
        slide = c.mu if c.mu is not None else 1.0
        el.set(
            "friction",
            f"{num(slide)} {num(c.torsional if c.torsional is not None else TORSION)} "
            f"{num(c.rolling if c.rolling is not None else ROLL)}",
        )
    if c.mu2 is not None and c.mu is not None and c.mu2 != c.mu:
        ctx.warn(
            "contact-not-representable",
            f"mu2 {c.mu2:g}: MuJoCo's friction is isotropic, mu {c.mu:g} is used",
            label,
            c.src,
        )
    if c.fdir1 is not None:
        ctx.warn("contact-not-representable", "fdir1: MuJoCo has no friction direction; left out", label, c.src)
    if c.kp is not None and c.kp > 0:
        timeconst, ratio = solref(c.kp, c.kd, contact_mass(ctx), c.restitution == 0)
        el.set("solref", f"{num(timeconst)} {num(ratio)}")
        if timeconst < 2 * MUJOCO_TIMESTEP:
            ctx.warn(
                "contact-too-stiff-for-timestep",
                f"kp {c.kp:g} N/m, kd {(c.kd if c.kd is not None else SDF_KD):g} N·s/m give a contact time constant of "
                f"{timeconst:.3g} s; MuJoCo clamps it to two steps (0.004 s at its default 2 ms step), a softer "
                f"contact, unless the step is {timeconst / 2:.2g} s or less",
                label,
                c.src,
            )
    if c.restitution:
        ctx.warn(
            "contact-not-representable",
            f"restitution {c.restitution:g}: MuJoCo has no coefficient of restitution (an underdamped solref bounces)",
            label,
            c.src,
        )
