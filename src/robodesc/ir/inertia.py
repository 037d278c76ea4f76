"""Inertia tensor arithmetic with numpy, for the passes that combine and move tensors.

The validity check and the principal axes live in :mod:`robodesc.ir.principal` (no numpy), so that
verifying and emitting a robot does not import numpy; ``inertia_problem`` is re-exported here."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from robodesc.ir.geometry import Inertia
from robodesc.ir.principal import inertia_problem as inertia_problem

Mat3 = NDArray[np.float64]


def tensor(inertia: Inertia) -> Mat3:
    i = inertia
    return np.array([[i.ixx, i.ixy, i.ixz], [i.ixy, i.iyy, i.iyz], [i.ixz, i.iyz, i.izz]])


def from_tensor(m: Mat3) -> Inertia:
    return Inertia(
        ixx=float(m[0, 0]),
        iyy=float(m[1, 1]),
        izz=float(m[2, 2]),
        ixy=float(m[0, 1]),
        ixz=float(m[0, 2]),
        iyz=float(m[1, 2]),
    )


def rotate(m: Mat3, rotation: Mat3) -> Mat3:
    """Express a tensor given in frame B in frame A, where ``rotation`` maps B to A."""
    out: Mat3 = rotation @ m @ rotation.T
    return out


def parallel_axis(m: Mat3, mass: float, offset: NDArray[np.float64]) -> Mat3:
    """Tensor about a point displaced by ``offset`` from the centre of mass."""
    d = np.asarray(offset, dtype=float)
    out: Mat3 = m + mass * (float(d @ d) * np.eye(3) - np.outer(d, d))
    return out


def balance(m: Mat3, margin: float = 1e-6) -> tuple[Mat3, float]:
    """Make a computed tensor strictly satisfy the triangle inequality.

    A flat or thin shape (a decal, a plate) gives principal moments with A + B = C up to rounding,
    and consumers (MuJoCo's ``A + B >= C`` check) refuse a rounding error's worth of violation.
    Adding ``delta * I`` keeps the principal axes and raises every moment by ``delta``, which restores
    ``A + B >= C (1 + margin)`` for ``delta = C (1 + margin) - A - B``. Returns the tensor and ``delta``
    (0 when nothing was needed).
    """
    eig = np.linalg.eigvalsh(m)
    a, b, c = (float(x) for x in eig)
    delta = c * (1.0 + margin) - a - b
    if delta <= 0:
        return m, 0.0
    out: Mat3 = m + delta * np.eye(3)
    return out, delta
