"""Two IR robots the same: masses, inertia about each COM (in the link frame), COM, joint types and
limits, and forward kinematics of every link at random joint values (relative to the root)."""

from __future__ import annotations

import math
import random

import numpy as np

from robodesc.ir.inertia import tensor
from robodesc.ir.model import JointType, Robot
from robodesc.ir.transforms import forward_kinematics, pose_matrix, resolve_mimic

TOL = 1e-9


def _limits(robot: Robot, name: str) -> tuple[float, float]:
    joint = robot.joint(name)
    lim = joint.limit
    if joint.type is JointType.CONTINUOUS or lim is None:
        return -math.pi, math.pi
    lo = lim.lower if lim.lower is not None else -math.pi
    hi = lim.upper if lim.upper is not None else math.pi
    return max(lo, -math.pi), min(hi, math.pi)


def differences(a: Robot, b: Robot, *, samples: int = 5, seed: int = 0) -> tuple[list[str], float]:
    """What differs between ``a`` and ``b`` (empty: the same), and the largest FK error seen (m)."""
    out: list[str] = []
    if {link.name for link in a.links} != {link.name for link in b.links}:
        return [f"links differ: {sorted({x.name for x in a.links} ^ {x.name for x in b.links})}"], math.inf
    if {j.name for j in a.joints} != {j.name for j in b.joints}:
        return [f"joints differ: {sorted({x.name for x in a.joints} ^ {x.name for x in b.joints})}"], math.inf
    for link in a.links:
        other = b.link(link.name)
        ma, ca, ia = _mass(link.inertial)
        mb, cb, ib = _mass(other.inertial)
        if abs(ma - mb) > TOL * max(1.0, ma):
            out.append(f"link {link.name!r}: mass {ma} vs {mb}")
        elif ma > 0 and (
            np.max(np.abs(ca - cb)) > TOL or np.max(np.abs(ia - ib)) > TOL * max(1.0, float(np.max(np.abs(ia))))
        ):
            out.append(
                f"link {link.name!r}: COM or inertia differ ({np.max(np.abs(ca - cb)):.3g}, {np.max(np.abs(ia - ib)):.3g})"
            )
    for joint in a.joints:
        other = b.joint(joint.name)
        if joint.type is not other.type:
            out.append(f"joint {joint.name!r}: {joint.type.value} vs {other.type.value}")
            continue
        if joint.type.dof == 1:
            for key in ("lower", "upper", "effort", "velocity"):
                va = getattr(joint.limit, key) if joint.limit is not None else None
                vb = getattr(other.limit, key) if other.limit is not None else None
                if (va is None) != (vb is None) or (va is not None and abs(va - vb) > TOL * max(1.0, abs(va))):
                    out.append(f"joint {joint.name!r}: limit {key} {va} vs {vb}")
    rng = random.Random(seed)
    worst = 0.0
    root_a, root_b = a.root.name, b.root.name
    for _ in range(samples):
        q = {j.name: rng.uniform(*_limits(a, j.name)) for j in a.actuated_joints() if j.type.dof == 1}
        q = resolve_mimic(a, q)
        fa, fb = forward_kinematics(a, q), forward_kinematics(b, q)
        inv_a, inv_b = np.linalg.inv(fa[root_a]), np.linalg.inv(fb[root_b])
        for name in fa:
            err = float(np.max(np.abs(inv_a @ fa[name] - inv_b @ fb[name])))
            worst = max(worst, err)
            if err > TOL:
                out.append(f"link {name!r}: FK differs by {err:.3g}")
                return out, worst
    return out, worst


def _mass(inertial: object) -> tuple[float, np.ndarray, np.ndarray]:
    from robodesc.ir.geometry import Inertial

    if not isinstance(inertial, Inertial) or not inertial.mass:
        return 0.0, np.zeros(3), np.zeros((3, 3))
    frame = pose_matrix(inertial.origin)
    inertia = (
        np.zeros((3, 3)) if inertial.inertia is None else frame[:3, :3] @ tensor(inertial.inertia) @ frame[:3, :3].T
    )
    return inertial.mass, frame[:3, 3], inertia
