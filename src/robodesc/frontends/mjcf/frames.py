"""Rigid frames of the compiled model as the IR's poses.

A MuJoCo body's joints turn about anchors inside the body; an IR joint turns about its own frame's
origin, which is its child link's frame. So the IR link of a body whose last joint is anchored at
``p`` sits at ``p`` (same axes), and everything the body holds is moved by ``-p`` into it:
:attr:`BodyMap.content` is that transform, from MuJoCo body coordinates to IR link coordinates.
"""

from __future__ import annotations

from collections.abc import Sequence

from robodesc.ir.geometry import Pose
from robodesc.ir.rigid import IDENTITY, Frame, quat_rotation, rotation_quat, rotation_rpy, transpose

ZERO = (0.0, 0.0, 0.0)


def frame(pos: Sequence[float], quat: Sequence[float] | None = None) -> Frame:
    """A frame from MuJoCo's ``pos`` and ``quat`` (w, x, y, z)."""
    rotation = (
        IDENTITY if quat is None else quat_rotation((float(quat[0]), float(quat[1]), float(quat[2]), float(quat[3])))
    )
    return Frame(rotation, (float(pos[0]), float(pos[1]), float(pos[2])))


def inverse(f: Frame) -> Frame:
    r = transpose(f.rotation)
    t = f.translation
    back = Frame(r)
    moved = back @ Frame(IDENTITY, t)
    return Frame(r, (-moved.translation[0], -moved.translation[1], -moved.translation[2]))


def translation(p: Sequence[float]) -> Frame:
    return Frame(IDENTITY, (float(p[0]), float(p[1]), float(p[2])))


def pose(f: Frame) -> Pose | None:
    """The IR pose of ``f``; None for the identity (the input said nothing to move)."""
    xyz = tuple(_clean(v) for v in f.translation)
    rpy = tuple(_clean(v) for v in rotation_rpy(f.rotation))
    out = Pose(xyz=xyz, rpy=rpy)  # type: ignore[arg-type]
    return None if out.is_identity() else out


def quat(f: Frame) -> tuple[float, float, float, float]:
    return rotation_quat(f.rotation)


def _clean(v: float) -> float:
    # Rounding noise of a quaternion product (1e-17) is written as 0, so identities stay identities.
    return 0.0 if abs(v) < 1e-14 else float(v)
