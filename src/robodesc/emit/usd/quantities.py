"""Numbers the USD emitter derives from the IR: joint frames, mass properties, unit conversions.

Plain floats (no numpy, no pxr): tests and validation reuse them, and a robot of primitives
converts without importing numpy.
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass

from robodesc.ir.geometry import Inertial, Vec3
from robodesc.ir.principal import rotate_tensor, symmetric_eigen, tensor_rows
from robodesc.ir.rigid import Mat3, Quat, rotation_quat, rpy_rotation, unit

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
    rotation: Mat3 | None


def axis_frame(axis: Vec3) -> AxisFrame:
    try:
        a = unit(axis)
    except ValueError:
        raise ValueError("joint axis has zero length") from None
    token = _PRINCIPAL.get(a)
    if token is not None:
        return AxisFrame(token, None)
    return AxisFrame("X", rotation_x_to(a))


def rotation_x_to(a: Vec3) -> Mat3:
    """The shortest rotation taking +X onto the unit vector ``a`` (a half turn about Z for -X).

    Rodrigues' formula with ``v = x × a = (0, -az, ay)`` and ``c = x · a = ax``:
    ``R = I + [v]× + [v]×² / (1 + c)``."""
    c, ay, az = a[0], a[1], a[2]
    if c < -1.0 + 1e-12:
        return ((-1.0, 0.0, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, 1.0))
    f = 1.0 / (1.0 + c)
    return (
        (1.0 - (az * az + ay * ay) * f, -ay, -az),
        (ay, 1.0 - ay * ay * f, -ay * az * f),
        (az, -az * ay * f, 1.0 - az * az * f),
    )


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
    m = tensor_rows(inertial.inertia)
    if origin is not None and origin.rpy != (0.0, 0.0, 0.0):
        m = rotate_tensor(m, rpy_rotation(origin.rpy))
    problem = None
    flat = [x for row in m for x in row]
    if not all(math.isfinite(x) for x in flat):
        return MassProperties(mass, com, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0), "inertia has a non-finite value")
    if not any(flat):
        problem = "inertia tensor is zero"
    if _is_diagonal(m):
        # Keep diagonal tensors exact and in axis order: no eigen-solver noise, no axis shuffling.
        diag = (m[0][0], m[1][1], m[2][2])
        quat: Quat = (1.0, 0.0, 0.0, 0.0)
    else:
        diag, axes = symmetric_eigen(m)
        quat = rotation_quat(axes)
    if problem is None and min(diag) < 0:
        problem = f"inertia tensor has a negative principal moment ({min(diag):.6g})"
    return MassProperties(mass, com, diag, quat, problem)


_F32 = struct.Struct("<f")
_U32 = struct.Struct("<I")


def to_float32(x: float) -> float:
    """The float32 nearest ``x``, as a Python float."""
    return float(_F32.unpack(_F32.pack(x))[0])


def _next_float32_up(x: float) -> float:
    """The next float32 above the float32 ``x`` (x >= 0)."""
    bits = _U32.unpack(_F32.pack(x))[0]
    return float(_F32.unpack(_U32.pack(bits + 1))[0])


# How far inside the triangle inequality a boundary tensor is moved: consumers rebuild the tensor
# from float32 moments and a float32 rotation (Newton: R diag(I) R^T in float32) and MuJoCo then
# re-diagonalises it, which moves the moments by a few 1e-7 of the largest (1e-6 also stays inside
# the 1e-6 inertia tolerance of robodesc's own usd-core validation).
TRIANGLE_MARGIN = 1e-6
# A violation up to this fraction of the largest moment is rounding of a boundary tensor; a larger
# one is the source's (the verifier reports it and repair_inertia fixes it).
TRIANGLE_ROUNDING = 1e-5


def float32_moments(diag: Vec3) -> Vec3:
    """Principal moments as the float32 values the file will hold, each pair's sum above the third
    by ``TRIANGLE_MARGIN`` of it.

    A tensor on the triangle inequality's boundary (a flat body, or one whose source moments were
    computed as A + B = C) breaks it once rounded to float32 and rebuilt by a consumer
    (allegro_right_hand: A + B - C = -1.9e-11, and MuJoCo refuses the model). The two smaller
    moments grow by at most a few millionths until the inequality holds with that margin; a tensor
    that breaks it by more than rounding is left as it is.
    """
    moments = [to_float32(x) for x in diag]
    if not all(math.isfinite(x) and x > 0 for x in moments):
        return (moments[0], moments[1], moments[2])
    order = sorted(range(3), key=lambda i: moments[i])
    a, b, c = (moments[i] for i in order)
    need = c * (1.0 + TRIANGLE_MARGIN)
    if a + b < need and c - (a + b) <= TRIANGLE_ROUNDING * c:
        scale = need / (a + b)  # both by the same fraction: a few millionths at most
        a, b = to_float32(a * scale), to_float32(b * scale)
        while a + b < need:  # float32 rounding may leave it a step short
            a, b = _next_float32_up(a), _next_float32_up(b)
        moments[order[0]], moments[order[1]] = a, b
    return (moments[0], moments[1], moments[2])


def _is_diagonal(m: Mat3) -> bool:
    return m[0][1] == 0.0 and m[0][2] == 0.0 and m[1][2] == 0.0


# Rotation from a USD camera (looks down -Z, +Y up) to a ROS/URDF sensor frame (+X forward, +Z up).
CAMERA_FROM_SENSOR: Mat3 = ((0.0, 0.0, -1.0), (-1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
