"""Rotations, rigid frames and forward kinematics in plain Python floats.

The emitters need a few dozen 3x3 products per robot. Doing them with numpy would make every
``robodesc compile`` pay numpy's import (about 0.1 s, more than converting a small robot), and
numpy's small-matrix products go through BLAS kernels that round differently on different CPUs.
Plain floats cost microseconds here and give the same bits everywhere.
:mod:`robodesc.ir.transforms` wraps these as numpy arrays for validation and tests.

Convention: URDF's fixed-axis roll-pitch-yaw, ``R = Rz(yaw) Ry(pitch) Rx(roll)``; quaternions are
(w, x, y, z).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from robodesc.ir.geometry import Pose, Vec3
from robodesc.ir.model import Joint, JointType, Robot

Mat3 = tuple[Vec3, Vec3, Vec3]
Quat = tuple[float, float, float, float]
# Anything indexable as m[i][j], i, j < 3: a Mat3, nested lists, a numpy array.
Rows = Sequence[Sequence[float]]

IDENTITY: Mat3 = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
ZERO: Vec3 = (0.0, 0.0, 0.0)


def rpy_rotation(rpy: Vec3) -> Mat3:
    r, p, y = rpy
    cr, sr = math.cos(r), math.sin(r)
    cp, sp = math.cos(p), math.sin(p)
    cy, sy = math.cos(y), math.sin(y)
    return (
        (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
        (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
        (-sp, cp * sr, cp * cr),
    )


def rotation_rpy(m: Rows) -> Vec3:
    """Inverse of :func:`rpy_rotation`; pitch in [-pi/2, pi/2]."""
    sp = max(-1.0, min(1.0, -float(m[2][0])))
    pitch = math.asin(sp)
    if abs(sp) < 1.0 - 1e-12:
        roll = math.atan2(float(m[2][1]), float(m[2][2]))
        yaw = math.atan2(float(m[1][0]), float(m[0][0]))
    else:  # gimbal lock: put everything in yaw
        roll = 0.0
        yaw = math.atan2(-float(m[0][1]), float(m[1][1]))
    return (roll, pitch, yaw)


def unit(v: Sequence[float]) -> Vec3:
    """``v`` scaled to length 1; ValueError for a zero or non-finite length."""
    x, y, z = float(v[0]), float(v[1]), float(v[2])
    norm = math.sqrt(x * x + y * y + z * z)
    if not math.isfinite(norm) or norm == 0.0:
        raise ValueError("vector has zero or non-finite length")
    return (x / norm, y / norm, z / norm)


def axis_angle_rotation(axis: Sequence[float], angle: float) -> Mat3:
    x, y, z = unit(axis)
    c, s = math.cos(angle), math.sin(angle)
    t = 1.0 - c
    return (
        (t * x * x + c, t * x * y - s * z, t * x * z + s * y),
        (t * x * y + s * z, t * y * y + c, t * y * z - s * x),
        (t * x * z - s * y, t * y * z + s * x, t * z * z + c),
    )


def matmul(a: Rows, b: Rows) -> Mat3:
    rows = []
    for i in range(3):
        a0, a1, a2 = float(a[i][0]), float(a[i][1]), float(a[i][2])
        rows.append(
            (
                a0 * b[0][0] + a1 * b[1][0] + a2 * b[2][0],
                a0 * b[0][1] + a1 * b[1][1] + a2 * b[2][1],
                a0 * b[0][2] + a1 * b[1][2] + a2 * b[2][2],
            )
        )
    return (rows[0], rows[1], rows[2])


def apply(m: Rows, v: Sequence[float]) -> Vec3:
    x, y, z = v[0], v[1], v[2]
    return (
        m[0][0] * x + m[0][1] * y + m[0][2] * z,
        m[1][0] * x + m[1][1] * y + m[1][2] * z,
        m[2][0] * x + m[2][1] * y + m[2][2] * z,
    )


def transpose(m: Rows) -> Mat3:
    return ((m[0][0], m[1][0], m[2][0]), (m[0][1], m[1][1], m[2][1]), (m[0][2], m[1][2], m[2][2]))


def determinant(m: Rows) -> float:
    return float(
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    )


def rotation_quat(m: Rows) -> Quat:
    """Unit quaternion (w, x, y, z) with w >= 0 for a rotation matrix (Shepperd's method: the
    largest of w, x, y, z is found first, so no division by a small number)."""
    m00, m01, m02 = (float(v) for v in m[0][:3])
    m10, m11, m12 = (float(v) for v in m[1][:3])
    m20, m21, m22 = (float(v) for v in m[2][:3])
    tr = m00 + m11 + m22
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        w, x, y, z = 0.25 * s, (m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s
    elif m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        w, x, y, z = (m21 - m12) / s, 0.25 * s, (m01 + m10) / s, (m02 + m20) / s
    elif m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        w, x, y, z = (m02 - m20) / s, (m01 + m10) / s, 0.25 * s, (m12 + m21) / s
    else:
        s = math.sqrt(1.0 + m22 - m00 - m11) * 2
        w, x, y, z = (m10 - m01) / s, (m02 + m20) / s, (m12 + m21) / s, 0.25 * s
    n = math.sqrt(w * w + x * x + y * y + z * z)
    if w < 0:
        n = -n
    return (w / n, x / n, y / n, z / n)


def quat_rotation(q: Quat) -> Mat3:
    w, x, y, z = q
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return (
        (1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)),
        (2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)),
        (2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)),
    )


@dataclass(slots=True, frozen=True)
class Frame:
    """A rigid transform: ``p -> rotation @ p + translation``."""

    rotation: Mat3 = IDENTITY
    translation: Vec3 = ZERO

    def __matmul__(self, other: Frame) -> Frame:
        """This transform after ``other`` (other's frame expressed in this one's parent)."""
        t = apply(self.rotation, other.translation)
        a = self.translation
        return Frame(matmul(self.rotation, other.rotation), (a[0] + t[0], a[1] + t[1], a[2] + t[2]))

    def rotated(self, rotation: Rows) -> Frame:
        """The same origin with axes turned by ``rotation`` (given in this frame)."""
        return Frame(matmul(self.rotation, rotation), self.translation)

    def quat(self) -> Quat:
        return rotation_quat(self.rotation)

    def matrix(self) -> list[list[float]]:
        """Homogeneous 4x4, row-major."""
        r, t = self.rotation, self.translation
        return [[*r[0], t[0]], [*r[1], t[1]], [*r[2], t[2]], [0.0, 0.0, 0.0, 1.0]]


def pose_frame(pose: Pose | None) -> Frame:
    if pose is None:
        return Frame()
    rotation = IDENTITY if pose.rpy == ZERO else rpy_rotation(pose.rpy)
    return Frame(rotation, pose.xyz)


def joint_motion(joint: Joint, q: float) -> Frame:
    """Transform of the child frame relative to the joint frame at position ``q``."""
    if joint.type.is_angular:
        return Frame(axis_angle_rotation(joint.effective_axis, q))
    if joint.type is JointType.PRISMATIC:
        x, y, z = unit(joint.effective_axis)
        return Frame(IDENTITY, (x * q, y * q, z * q))
    return Frame()


def resolve_mimic(robot: Robot, q: Mapping[str, float]) -> dict[str, float]:
    """Complete ``q`` with the positions of mimic joints (``multiplier * q_leader + offset``)."""
    joints = robot.joint_map()
    out = dict(q)

    def value(name: str, depth: int = 0) -> float:
        if name in out:
            return out[name]
        joint = joints.get(name)
        if joint is None:  # a dangling mimic leader (the verifier reports it): treat as at zero
            return 0.0
        if joint.mimic is None or depth > len(joints):
            return 0.0
        m = joint.mimic
        v = (m.multiplier if m.multiplier is not None else 1.0) * value(m.joint, depth + 1) + (
            m.offset if m.offset is not None else 0.0
        )
        out[name] = v
        return v

    for joint in robot.joints:
        if joint.type.dof == 1:
            value(joint.name)
    return out


def link_frames(robot: Robot, q: Mapping[str, float] | None = None) -> dict[str, Frame]:
    """Root-frame transform of every link for joint positions ``q`` (missing = 0).

    Mimic joints follow their leaders. The root link sits at the identity."""
    qs = resolve_mimic(robot, q or {})
    out: dict[str, Frame] = {link.name: Frame() for link in robot.root_links()}
    for joint in robot.topological_joints():
        local = pose_frame(joint.origin)
        position = qs.get(joint.name, 0.0)
        if position:  # at 0 every joint's motion is the identity
            local = local @ joint_motion(joint, position)
        out[joint.child] = out[joint.parent] @ local
    return out
