"""The names the ``massless`` pass (passes/massless.py) and its group maths (massless_groups.py)
share: kept apart so the light pass need not import the maths, and the maths not the pass."""

from __future__ import annotations

from robodesc.ir.model import Link

NAME = "massless"
# kg: the token mass validation recognises (robodesc.validation.options.TOKEN_MASS); PhysX, Newton
# and MuJoCo accept it.
PLACEHOLDER_MASS = 1e-3
# m: the placeholder's radius of gyration. 1e-3 kg x (0.03 m)² = 9e-7 kg·m², far above Newton's
# 1e-10 kg·m² floor (a1's 1e-6 kg, 1.7e-13 kg·m² base from its tiny box was "corrected").
PLACEHOLDER_GYRATION = 0.03


def massless_link(link: Link) -> bool:
    """No mass of its own: no ``<inertial>``, no mass, or a zero one (a negative mass is invalid,
    repair_inertia's business)."""
    inertial = link.inertial
    return inertial is None or inertial.mass is None or inertial.mass == 0
