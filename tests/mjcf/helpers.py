"""Small checks of an MJCF output against the IR (the full validator is robodesc.validation)."""

from __future__ import annotations

import re
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import mujoco
import numpy as np

from robodesc.ir.model import JointType, Robot
from robodesc.ir.rigid import link_frames, pose_frame, rpy_rotation

ROOT = Path(__file__).resolve().parents[2]


@contextmanager
def warnings_into(sink: list[str]) -> Iterator[None]:
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(lambda msg: sink.append(str(msg)))
    try:
        yield
    finally:
        mujoco.set_mju_user_warning(previous)


def load_clean(path: str | Path) -> Any:
    """MjModel of ``path``, after one mj_forward; fails on any MuJoCo warning."""
    warnings: list[str] = []
    with warnings_into(warnings):
        model = mujoco.MjModel.from_xml_path(str(path))
        data = mujoco.MjData(model)
        mujoco.mj_forward(model, data)
    assert not warnings, warnings
    assert not np.any(np.isnan(data.qacc))
    return model


def normalised(text: str) -> str:
    """Mesh references that point into the checkout, with the checkout's place taken out."""
    return re.sub(r'file="[^"]*?/(examples|tests)/', r'file="<ROOT>/\1/', text)


def check_mass_and_fk(robot: Robot, model: Any, seed: int = 0) -> None:
    """Per-body mass and inertia (about the COM, world-aligned at zero pose) and FK at random q."""
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    for link in robot.links:
        bid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, link.name)
        if bid < 0:
            assert link.name == "world"
            continue
        inertial = link.inertial
        if inertial is None or inertial.mass is None:
            continue
        assert model.body_mass[bid] == inertial.mass
        if inertial.inertia is None:
            continue
        i = inertial.inertia
        tensor = np.array([[i.ixx, i.ixy, i.ixz], [i.ixy, i.iyy, i.iyz], [i.ixz, i.iyz, i.izz]])
        if inertial.origin is not None and inertial.origin.rpy != (0.0, 0.0, 0.0):
            r = np.asarray(rpy_rotation(inertial.origin.rpy))
            tensor = r @ tensor @ r.T
        mat = np.zeros(9)
        mujoco.mju_quat2Mat(mat, model.body_iquat[bid])
        r_inertia = mat.reshape(3, 3)  # principal frame -> body frame
        got = r_inertia @ np.diag(model.body_inertia[bid]) @ r_inertia.T
        np.testing.assert_allclose(got, tensor, rtol=1e-9, atol=1e-12 * max(1.0, np.abs(tensor).max()))
    rng = np.random.default_rng(seed)
    for _ in range(5):
        q: dict[str, float] = {}
        for joint in robot.joints:
            if joint.type.dof != 1 or joint.mimic is not None:
                continue
            lo, hi = -1.0, 1.0
            if joint.limit is not None and joint.type is not JointType.CONTINUOUS:
                lo = joint.limit.lower if joint.limit.lower is not None else lo
                hi = joint.limit.upper if joint.limit.upper is not None else hi
            q[joint.name] = float(rng.uniform(lo, hi))
        frames = link_frames(robot, q)
        data.qpos[:] = model.qpos0
        for name, value in q.items():
            jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
            data.qpos[model.jnt_qposadr[jid]] = value
        for joint in robot.joints:  # mimic followers: MuJoCo's equality holds them only when simulated
            if joint.mimic is not None and joint.type.dof == 1:
                m = joint.mimic
                value = (m.multiplier or 1.0) * q.get(m.joint, 0.0) + (m.offset or 0.0)
                frames = link_frames(robot, {**q, joint.name: value})
                jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint.name)
                data.qpos[model.jnt_qposadr[jid]] = value
        mujoco.mj_kinematics(model, data)
        root_id = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, robot.root.name)
        base = np.eye(4)
        if root_id > 0:
            base[:3, :3] = data.xmat[root_id].reshape(3, 3)
            base[:3, 3] = data.xpos[root_id]
        for link in robot.links:
            bid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, link.name)
            if bid < 0:
                continue
            want = base @ np.array(frames[link.name].matrix())
            np.testing.assert_allclose(data.xpos[bid], want[:3, 3], atol=1e-9)
            np.testing.assert_allclose(data.xmat[bid].reshape(3, 3), want[:3, :3], atol=1e-9)


__all__ = ["ROOT", "check_mass_and_fk", "load_clean", "normalised", "pose_frame"]


def stand_from_home(scene: str | Path, seconds: float) -> tuple[float, np.ndarray]:
    """Step ``scene`` from its ``home`` keyframe: the lowest up·z of the root over the run, and the
    root's final position."""
    model = mujoco.MjModel.from_xml_path(str(scene))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home"))
    worst = 1.0
    for _ in range(int(seconds / model.opt.timestep)):
        mujoco.mj_step(model, data)
        worst = min(worst, float(data.xmat[1].reshape(3, 3)[2, 2]))
    assert np.isfinite(data.qpos).all()
    return worst, data.qpos[:3].copy()
