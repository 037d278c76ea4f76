"""Rigid transforms and forward kinematics over the IR, as numpy arrays.

Validation, the passes and the tests compute with numpy; the numbers come from
:mod:`robodesc.ir.rigid` (plain floats, what the emitters use), so every stage agrees on one
convention: URDF's fixed-axis roll-pitch-yaw, ``R = Rz(yaw) @ Ry(pitch) @ Rx(roll)``.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from numpy.typing import NDArray

from robodesc.ir import rigid
from robodesc.ir.geometry import Pose, Vec3
from robodesc.ir.model import Robot
from robodesc.ir.rigid import resolve_mimic as resolve_mimic

Mat = NDArray[np.float64]


def rpy_to_matrix(rpy: Vec3) -> Mat:
    return np.array(rigid.rpy_rotation(rpy))


def matrix_to_rpy(m: Mat) -> Vec3:
    """Inverse of :func:`rpy_to_matrix`; pitch in [-pi/2, pi/2]."""
    return rigid.rotation_rpy(np.asarray(m)[:3, :3].tolist())


def pose_matrix(pose: Pose | None) -> Mat:
    return np.array(rigid.pose_frame(pose).matrix())


def matrix_pose(m: Mat) -> Pose:
    xyz = (float(m[0, 3]), float(m[1, 3]), float(m[2, 3]))
    return Pose(xyz=xyz, rpy=matrix_to_rpy(m[:3, :3]))


def axis_angle_matrix(axis: Vec3, angle: float) -> Mat:
    return np.array(rigid.axis_angle_rotation(axis, angle))


def matrix_to_quat_wxyz(m: Mat) -> tuple[float, float, float, float]:
    """Unit quaternion (w, x, y, z) with w >= 0 for a rotation matrix."""
    return rigid.rotation_quat(np.asarray(m)[:3, :3].tolist())


def quat_wxyz_to_matrix(q: tuple[float, float, float, float]) -> Mat:
    return np.array(rigid.quat_rotation(q))


def forward_kinematics(robot: Robot, q: Mapping[str, float] | None = None) -> dict[str, Mat]:
    """World (root-frame) transform of every link for joint positions ``q`` (missing = 0).

    Mimic joints follow their leaders. The root link sits at the identity.
    """
    return {name: np.array(frame.matrix()) for name, frame in rigid.link_frames(robot, q).items()}
