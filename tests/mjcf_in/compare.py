"""The same model in MuJoCo: a source MJCF against robodesc's MJCF of it (MJCF -> IR -> MJCF).

Compared where body merging cannot change the answer: the total mass, the whole robot's centre of
mass and inertia about the world origin, and every joint's world anchor and axis, at random joint
positions (the IR's zero is the source's ``ref``, so the written model gets ``q - ref``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import mujoco
import numpy as np

HINGE, SLIDE, BALL, FREE = (
    int(mujoco.mjtJoint.mjJNT_HINGE),
    int(mujoco.mjtJoint.mjJNT_SLIDE),
    int(mujoco.mjtJoint.mjJNT_BALL),
    int(mujoco.mjtJoint.mjJNT_FREE),
)


@dataclass
class Summary:
    mass: float
    com: np.ndarray
    inertia: np.ndarray  # about the world origin, world axes
    anchors: dict[str, np.ndarray]
    axes: dict[str, np.ndarray]


def random_q(model: Any, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """Joint name -> qpos slice: hinges and slides within range (else ±1), balls random, frees as placed."""
    out: dict[str, np.ndarray] = {}
    for j in range(model.njnt):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) or f"joint{j}"
        kind = int(model.jnt_type[j])
        adr = int(model.jnt_qposadr[j])
        if kind in (HINGE, SLIDE):
            lo, hi = model.jnt_range[j] if model.jnt_limited[j] else (-1.0, 1.0)
            out[name] = np.array([rng.uniform(lo, hi)])
        elif kind == BALL:
            q = rng.normal(size=4)
            out[name] = q / np.linalg.norm(q)
        else:
            out[name] = model.qpos0[adr : adr + 7].copy()
    return out


def summary(
    model: Any, q: dict[str, np.ndarray], ref_of: dict[str, float] | None = None, bodies: set[str] | None = None
) -> Summary:
    """``bodies``: count only these (the massless links between a body's joints get MuJoCo's minimum
    mass from the MJCF emitter, with a warning: not the source's)."""
    data = mujoco.MjData(model)
    for j in range(model.njnt):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) or f"joint{j}"
        adr = int(model.jnt_qposadr[j])
        kind = int(model.jnt_type[j])
        if name in q and kind != FREE:
            value = q[name].copy()
            if ref_of is not None and kind in (HINGE, SLIDE):
                value = value - ref_of.get(name, 0.0)
            data.qpos[adr : adr + len(value)] = value
    mujoco.mj_kinematics(model, data)
    kept = [
        b
        for b in range(1, model.nbody)
        if bodies is None or mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b) in bodies
    ]
    masses = model.body_mass[kept]
    total = float(masses.sum())
    com = (data.xipos[kept] * masses[:, None]).sum(axis=0) / total
    inertia = np.zeros((3, 3))
    for b in kept:
        rot = data.ximat[b].reshape(3, 3)
        c = data.xipos[b]
        m = model.body_mass[b]
        inertia += rot @ np.diag(model.body_inertia[b]) @ rot.T + m * (c @ c * np.eye(3) - np.outer(c, c))
    anchors, axes = {}, {}
    for j in range(model.njnt):
        if int(model.jnt_type[j]) == FREE:
            continue
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) or f"joint{j}"
        anchors[name] = data.xanchor[j].copy()
        axes[name] = data.xaxis[j].copy()
    return Summary(total, com, inertia, anchors, axes)


def refs(model: Any) -> dict[str, float]:
    out = {}
    for j in range(model.njnt):
        if int(model.jnt_type[j]) in (HINGE, SLIDE):
            name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) or f"joint{j}"
            out[name] = float(model.qpos0[int(model.jnt_qposadr[j])])
    return out


def place_root(model: Any, q: dict[str, np.ndarray]) -> None:
    """Free joints at the source's own placement (qpos0)."""
    for j in range(model.njnt):
        if int(model.jnt_type[j]) == FREE:
            name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) or f"joint{j}"
            adr = int(model.jnt_qposadr[j])
            q[name] = model.qpos0[adr : adr + 7].copy()


def compare(source: Any, written: Any, samples: int = 5, seed: int = 0, tol: float = 1e-6) -> list[str]:
    """Differences between the two models (empty: the same), as messages."""
    rng = np.random.default_rng(seed)
    problems: list[str] = []
    source_refs = refs(source)
    names = {mujoco.mj_id2name(source, mujoco.mjtObj.mjOBJ_BODY, i) for i in range(source.nbody)}
    for _ in range(samples):
        q = random_q(source, rng)
        a = summary(source, q)
        # The written model's root: wherever it is placed, compare relative to its root body.
        b = summary(written, q, source_refs, names)
        shift = _root_shift(source, written)
        if abs(a.mass - b.mass) > tol * max(a.mass, 1.0):
            problems.append(f"mass {a.mass} vs {b.mass}")
        if np.abs(a.com - (b.com - shift)).max() > tol:
            problems.append(f"com {a.com} vs {b.com - shift}")
        inertia_b = _shift_inertia(b.inertia, b.mass, b.com, b.com - shift)
        if np.abs(a.inertia - inertia_b).max() > tol * max(np.abs(a.inertia).max(), 1.0):
            problems.append(f"inertia {a.inertia.round(6).tolist()} vs {inertia_b.round(6).tolist()}")
        for name, anchor in a.anchors.items():
            if name not in b.anchors:
                problems.append(f"joint {name} missing")
                continue
            if np.abs(anchor - (b.anchors[name] - shift)).max() > tol:
                problems.append(f"joint {name} anchor {anchor} vs {b.anchors[name] - shift}")
            if np.abs(a.axes[name] - b.axes[name]).max() > tol:
                problems.append(f"joint {name} axis {a.axes[name]} vs {b.axes[name]}")
        if problems:
            break
    return problems


def _root_shift(source: Any, written: Any) -> np.ndarray:
    """Where the written model puts its root, less where the source does (a floating robot's home height)."""
    data_a, data_b = mujoco.MjData(source), mujoco.MjData(written)
    mujoco.mj_kinematics(source, data_a)
    mujoco.mj_kinematics(written, data_b)
    return np.asarray(data_b.xpos[1] - data_a.xpos[1]) if _rooted(source) and _rooted(written) else np.zeros(3)


def _rooted(model: Any) -> bool:
    return model.nbody > 1 and int(model.body_parentid[1]) == 0


def _shift_inertia(inertia: np.ndarray, mass: float, com_from: np.ndarray, com_to: np.ndarray) -> np.ndarray:
    """An inertia about the origin of a body whose centre moves from ``com_from`` to ``com_to``."""
    about_com = inertia - mass * (com_from @ com_from * np.eye(3) - np.outer(com_from, com_from))
    return about_com + mass * (com_to @ com_to * np.eye(3) - np.outer(com_to, com_to))


def mesh_geom_frames(model: Any) -> list[tuple[np.ndarray, np.ndarray, float]]:
    """World position, rotation and volume-free size (the AABB's half diagonal) of every mesh geom
    at qpos0: where MuJoCo puts the (recentred) mesh."""
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    out = []
    for g in range(model.ngeom):
        if int(model.geom_type[g]) == int(mujoco.mjtGeom.mjGEOM_MESH):
            out.append((data.geom_xpos[g].copy(), data.geom_xmat[g].reshape(3, 3).copy(), float(model.geom_rbound[g])))
    return out


def unmatched_meshes(source: Any, written: Any, shift: np.ndarray | None = None, tol: float = 1e-5) -> int:
    """How many of the source's mesh geoms have no written mesh geom at the same place, axes and size."""
    theirs = mesh_geom_frames(written)
    offset = np.zeros(3) if shift is None else shift
    missing = 0
    for pos, rot, size in mesh_geom_frames(source):
        if not any(
            np.abs(pos - (p - offset)).max() < tol and np.abs(rot - r).max() < tol and abs(size - s) < tol
            for p, r, s in theirs
        ):
            missing += 1
    return missing
