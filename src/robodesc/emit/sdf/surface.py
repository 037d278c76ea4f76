"""Contact in SDF: a collision's ``<surface>``, as Gazebo Harmonic (and Classic's ODE) reads it.

The IR's vocabulary is ODE's, so this is the identity mapping, in SDF's element names:
``friction/ode/mu``, ``mu2``, ``fdir1``; ``friction/torsional/coefficient`` with a ``patch_radius``
(the IR keeps their product, m: written as coefficient 1 with that radius); ``bounce``;
``contact/ode/kp``, ``kd``, ``min_depth``, ``max_vel``. Rolling friction has no ODE element:
left out with a warning.
"""

from __future__ import annotations

from typing import Any

from lxml import etree

from robodesc.emit.common.numbers import fmt, fmt_vec
from robodesc.ir.contact import Contact
from robodesc.ir.diagnostics import Findings

E = etree.SubElement


def add_surface(collision: Any, contact: Contact | None, findings: Findings, label: str) -> None:
    """Append ``<surface>`` to the ``<collision>`` element when the source gave any contact parameter."""
    if contact is None or not contact.given():
        return
    surface = E(collision, "surface")
    c = contact
    if c.mu is not None or c.mu2 is not None or c.fdir1 is not None or c.torsional is not None:
        friction = E(surface, "friction")
        if c.torsional is not None:
            torsional = E(friction, "torsional")
            E(torsional, "coefficient").text = "1"
            E(torsional, "patch_radius").text = fmt(c.torsional)
        if c.mu is not None or c.mu2 is not None or c.fdir1 is not None:
            ode = E(friction, "ode")
            for tag, value in (("mu", c.mu), ("mu2", c.mu2)):
                if value is not None:
                    E(ode, tag).text = fmt(value)
            if c.fdir1 is not None:
                E(ode, "fdir1").text = fmt_vec(c.fdir1)
    if c.restitution is not None or c.bounce_threshold is not None:
        bounce = E(surface, "bounce")
        if c.restitution is not None:
            E(bounce, "restitution_coefficient").text = fmt(c.restitution)
        if c.bounce_threshold is not None:
            E(bounce, "threshold").text = fmt(c.bounce_threshold)
    ode_contact = [("kp", c.kp), ("kd", c.kd), ("min_depth", c.min_depth), ("max_vel", c.max_vel)]
    if any(v is not None for _, v in ode_contact):
        ode = E(E(surface, "contact"), "ode")
        for tag, value in ode_contact:
            if value is not None:
                E(ode, tag).text = fmt(value)
    if c.rolling is not None:
        findings.warn(
            "contact-not-representable",
            "rolling friction has no ODE/Gazebo element in SDF; left out",
            element=label,
            loc=c.src,
            stage="emit:sdf",
        )
