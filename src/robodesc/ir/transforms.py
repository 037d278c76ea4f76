"""Rigid transforms and forward kinematics over the IR (numpy).

Emitters, passes and validation share these so that every stage agrees on one convention:
URDF's fixed-axis roll-pitch-yaw, ``R = Rz(yaw) @ Ry(pitch) @ Rx(roll)``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
from numpy.typing import NDArray

from robodesc.ir.geometry import Pose, Vec3
from robodesc.ir.model import Joint, JointType, Robot

Mat = NDArray[np.float64]


def rpy_to_matrix(rpy: Vec3) -> Mat:
    r, p, y = rpy
    cr, sr = math.cos(r), math.sin(r)
    cp, sp = math.cos(p), math.sin(p)
    cy, sy = math.cos(y), math.sin(y)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def matrix_to_rpy(m: Mat) -> Vec3:
    """Inverse of :func:`rpy_to_matrix`; pitch in [-pi/2, pi/2]."""
    sp = -float(m[2, 0])
    sp = max(-1.0, min(1.0, sp))
    pitch = math.asin(sp)
    if abs(sp) < 1.0 - 1e-12:
        roll = math.atan2(float(m[2, 1]), float(m[2, 2]))
        yaw = math.atan2(float(m[1, 0]), float(m[0, 0]))
    else:  # gimbal lock: put everything in yaw
        roll = 0.0
        yaw = math.atan2(-float(m[0, 1]), float(m[1, 1]))
    return (roll, pitch, yaw)


def pose_matrix(pose: Pose | None) -> Mat:
    out = np.eye(4)
    if pose is not None:
        out[:3, :3] = rpy_to_matrix(pose.rpy)
        out[:3, 3] = pose.xyz
    return out


def matrix_pose(m: Mat) -> Pose:
    xyz = (float(m[0, 3]), float(m[1, 3]), float(m[2, 3]))
    return Pose(xyz=xyz, rpy=matrix_to_rpy(m[:3, :3]))


def axis_angle_matrix(axis: Vec3, angle: float) -> Mat:
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    x, y, z = a
    c, s = math.cos(angle), math.sin(angle)
    t = 1.0 - c
    return np.array(
        [
            [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
        ]
    )


def matrix_to_quat_wxyz(m: Mat) -> tuple[float, float, float, float]:
    """Unit quaternion (w, x, y, z) with w >= 0 for a rotation matrix."""
    tr = float(m[0, 0] + m[1, 1] + m[2, 2])
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        w, x, y, z = 0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2]) * 2
        w, x, y, z = (m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s
    elif m[1, 1] > m[2, 2]:
        s = math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2]) * 2
        w, x, y, z = (m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s
    else:
        s = math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1]) * 2
        w, x, y, z = (m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s
    q = np.array([w, x, y, z], dtype=float)
    q /= np.linalg.norm(q)
    if q[0] < 0:
        q = -q
    return (float(q[0]), float(q[1]), float(q[2]), float(q[3]))


def quat_wxyz_to_matrix(q: tuple[float, float, float, float]) -> Mat:
    w, x, y, z = q
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def joint_motion(joint: Joint, q: float) -> Mat:
    """Transform of the child frame relative to the joint frame at position ``q``."""
    out = np.eye(4)
    if joint.type.is_angular:
        out[:3, :3] = axis_angle_matrix(joint.effective_axis, q)
    elif joint.type is JointType.PRISMATIC:
        a = np.asarray(joint.effective_axis, dtype=float)
        out[:3, 3] = a / np.linalg.norm(a) * q
    return out


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


def forward_kinematics(robot: Robot, q: Mapping[str, float] | None = None) -> dict[str, Mat]:
    """World (root-frame) transform of every link for joint positions ``q`` (missing = 0).

    Mimic joints follow their leaders. The root link sits at the identity.
    """
    qs = resolve_mimic(robot, q or {})
    out: dict[str, Mat] = {link.name: np.eye(4) for link in robot.root_links()}
    for joint in robot.topological_joints():
        parent = out[joint.parent]
        local = pose_matrix(joint.origin) @ joint_motion(joint, qs.get(joint.name, 0.0))
        out[joint.child] = parent @ local
    return out
