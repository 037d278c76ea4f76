"""Numbers the USD emitter derives from the IR: joint frames, mass properties, unit conversions.

Pure numpy (no pxr) so tests and validation can reuse them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from robodesc.ir.geometry import Inertial, Vec3
from robodesc.ir.inertia import principal_axes, rotate, tensor
from robodesc.ir.transforms import matrix_to_quat_wxyz, rpy_to_matrix

Mat = NDArray[np.float64]
Quat = tuple[float, float, float, float]  # (w, x, y, z)

DEG = 180.0 / math.pi
# Angular gains are per degree in USD: (N·m/rad) · (rad/deg).
PER_DEGREE = math.pi / 180.0

_PRINCIPAL = {(1.0, 0.0, 0.0): "X", (0.0, 1.0, 0.0): "Y", (0.0, 0.0, 1.0): "Z"}


@dataclass(slots=True, frozen=True)
class AxisFrame:
    """How a URDF axis becomes a UsdPhysics one.

    ``token`` is the ``physics:axis`` value; ``rotation`` (None = identity) turns the joint frame so
    that this token's axis points along the URDF axis. It multiplies both localRot0 and localRot1.
    """

    token: str
    rotation: Mat | None


def axis_frame(axis: Vec3) -> AxisFrame:
    a = np.asarray(axis, dtype=float)
    norm = float(np.linalg.norm(a))
    if not math.isfinite(norm) or norm == 0.0:
        raise ValueError("joint axis has zero length")
    a = a / norm
    key = (float(a[0]), float(a[1]), float(a[2]))
    token = _PRINCIPAL.get(key)
    if token is not None:
        return AxisFrame(token, None)
    return AxisFrame("X", rotation_x_to(a))


def rotation_x_to(a: Mat) -> Mat:
    """The shortest rotation taking +X onto the unit vector ``a`` (a half turn about Z for -X)."""
    x = np.array([1.0, 0.0, 0.0])
    c = float(x @ a)
    if c < -1.0 + 1e-12:
        return np.diag([-1.0, -1.0, 1.0])
    v = np.cross(x, a)
    k = np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])
    out: Mat = np.eye(3) + k + (k @ k) / (1.0 + c)
    return out


@dataclass(slots=True, frozen=True)
class MassProperties:
    mass: float
    center_of_mass: Vec3
    diagonal_inertia: Vec3
    principal_axes: Quat
    # Why the tensor is not usable as given (zero, negative moment ...), or None.
    problem: str | None


def mass_properties(inertial: Inertial) -> MassProperties:
    """UsdPhysics mass properties in the link frame: the tensor is rotated by the inertial origin
    first, then diagonalised."""
    origin = inertial.origin
    com: Vec3 = origin.xyz if origin is not None else (0.0, 0.0, 0.0)
    mass = float(inertial.mass) if inertial.mass is not None else 0.0
    if inertial.inertia is None:
        return MassProperties(mass, com, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0), "no inertia tensor given")
    m = tensor(inertial.inertia)
    if origin is not None and origin.rpy != (0.0, 0.0, 0.0):
        m = rotate(m, rpy_to_matrix(origin.rpy))
    problem = None
    if not np.all(np.isfinite(m)):
        return MassProperties(mass, com, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0), "inertia has a non-finite value")
    if not np.any(m):
        problem = "inertia tensor is zero"
    if _is_diagonal(m):
        # Keep diagonal tensors exact and in axis order: no eigen-solver noise, no axis shuffling.
        diag = (float(m[0, 0]), float(m[1, 1]), float(m[2, 2]))
        quat: Quat = (1.0, 0.0, 0.0, 0.0)
    else:
        eig, vec = principal_axes(m)
        diag = (float(eig[0]), float(eig[1]), float(eig[2]))
        quat = matrix_to_quat_wxyz(vec)
    if problem is None and min(diag) < 0:
        problem = f"inertia tensor has a negative principal moment ({min(diag):.6g})"
    return MassProperties(mass, com, diag, quat, problem)


def _is_diagonal(m: Mat) -> bool:
    return bool(m[0, 1] == 0.0 and m[0, 2] == 0.0 and m[1, 2] == 0.0)


def camera_from_sensor() -> Mat:
    """Rotation from a USD camera (looks down -Z, +Y up) to a ROS/URDF sensor frame (+X forward,
    +Z up)."""
    return np.array([[0.0, 0.0, -1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
