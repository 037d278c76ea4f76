"""Default drive gains derived per joint from the inertia it moves and its effort limit.

One constant (the old 100 N·m/rad, 1 N·m·s/rad) is too stiff for a finger and too weak and
underdamped for a quadruped's knee carrying a quarter of the body. Each joint instead gets a PD
loop with natural frequency ``f`` and damping ratio ``zeta`` on the inertia it carries:

    I_eff = armature + sum over the links it moves of (max principal moment + m·d^2)
          + (M / legs)·r^2           for a leg joint of a floating robot: the body's share, which
                                     the leg lifts, r the foot's distance from the joint

(d: the link's centre of mass from the joint, at the default pose; the largest moment and the
distance rather than the axis make it the most the joint can meet as the joints beyond it move)
    kp    = I_eff·(2 pi f)^2, then at most effort / E_SAT (an error of E_SAT rad saturates it)
    kd    = 2·zeta·sqrt(kp·I_eff), at least kp·range / (SPEED_MARGIN·velocity limit)

(the second term: a PD loop's speed settles where kd·v = kp·error, so a step across the joint's whole
range is driven at no more than SPEED_MARGIN = 2 times its velocity limit; without it, random control
drove panda_joint7 at 19.7 times its limit in MuJoCo, issue 35)
with ``f`` = 4 Hz, ``zeta`` = 1 (critically damped: the robot settles without rocking) and
``E_SAT`` = 0.2 rad. A revolute joint's kp is also at least ``g·sum(m·d) / HOLD_ERROR``: the most
gravity torque the moved links can put on it, held within ``HOLD_ERROR`` = 0.005 rad (a finger's
inertia is tiny next to the lever arm of a hand held out; without this floor fixed hands and small
arms sagged ~0.2 rad in Newton; at 0.05 rad arms sagged 0.02-0.05 rad in MuJoCo, where
mujoco_menagerie's sag 0.004-0.008, issue 35). The effort cap still wins: a motor cannot give more.
Prismatic joints use the moved mass and N/m. docs/isaac.md shows the numbers for Spirit and Go2.

No dead actuator: a joint whose links weigh grams (Allegro's URDF has no inertials: 1 g links) got
kp near 0. kp is at least ``effort / FLOOR_ERROR`` (the motor's limit at an error of FLOOR_ERROR =
1 rad) wherever the effort is known, but never above ``I_eff·(2 pi F_MAX)^2`` (F_MAX = 20 Hz), which
keeps the loop stable at MuJoCo's 2 ms step on an almost weightless link. A joint whose actuator
cannot lift its links (``min(kp·range, effort)`` below the gravity torque) is named in the warning
``default-gains-dead``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Collection, Mapping
from dataclasses import dataclass
from typing import Any, Protocol

from robodesc.emit.common.stance import Stance
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Joint, Robot
from robodesc.ir.principal import principal_moments, tensor_rows
from robodesc.ir.rigid import Frame, apply, link_frames, pose_frame
from robodesc.ir.rules import lookup

NATURAL_FREQUENCY = 4.0  # Hz
DAMPING_RATIO = 1.0
E_SAT = 0.2  # rad (or m): the error at which the default stiffness reaches the effort limit
HOLD_ERROR = 0.005  # rad: the most a revolute joint may sag under gravity at its default stiffness
FLOOR_ERROR = 1.0  # rad (or m): the error at which the floor stiffness reaches the effort limit
SPEED_MARGIN = 2.0  # the most a joint is driven over its velocity limit by a full-range step
F_MAX = 20.0  # Hz: the floor never makes a loop faster than this
GRAVITY = 9.81  # m/s²


@dataclass(slots=True, frozen=True)
class JointGains:
    stiffness: float  # SI
    damping: float
    inertia: float  # I_eff, kg·m² (kg for a prismatic joint)
    capped: bool  # the effort limit bounded the stiffness
    gravity_torque: float = 0.0  # g·Σm·d, N·m: the most gravity can load the joint with (revolute)
    weak: bool = False  # gravity_torque exceeds the effort limit: the joint cannot hold its links out
    dead: bool = False  # the actuator cannot move the joint against gravity over its range (or kp is 0)
    floor: bool = False  # the gravity floor set the stiffness (above the inertia's, capped or not)


def derived_gains(
    robot: Robot, stance: Stance, floating: bool, stiffness: Mapping[str, float] | None = None
) -> dict[str, JointGains]:
    """Gains for every actuated 1-DOF joint. ``stiffness`` (by joint name) are the user's: kd is then
    derived from them."""
    frames = link_frames(robot, stance.positions)
    moved = _MovedLinks(robot, frames)
    total = robot.total_mass()
    leg_of = {name: leg for leg in (stance.legs if floating else []) for name in leg.joints}
    omega = 2.0 * math.pi * NATURAL_FREQUENCY
    out: dict[str, JointGains] = {}
    for joint in robot.actuated_joints():
        if joint.type.dof != 1:
            continue
        jf = frames[joint.parent] @ pose_frame(joint.origin)
        inertia = moved.inertia(joint, jf.translation)
        leg = leg_of.get(joint.name)
        torque = 0.0
        if joint.type.is_angular:
            torque = GRAVITY * moved.moment(joint.child, jf.translation)
        if leg is not None and stance.legs:
            foot = frames[leg.foot]
            point = _add(foot.translation, apply(foot.rotation, leg.foot_point))
            share = total / len(stance.legs)
            inertia += share * (_distance_sq(point, jf.translation) if joint.type.is_angular else 1.0)
            if joint.type.is_angular:
                # A leg in its stance does not swing its links out: its load is the robot's share
                # (M / legs, the leg's own links included) standing on the foot, the ground pushing
                # up there with share·g: ((foot - joint) × z)·axis of torque, none about a yaw axis.
                # The worst case over the joints beyond (arms) made Romeo's legs "weak" and 4x
                # stiffer, and it tipped over.
                r = (point[0] - jf.translation[0], point[1] - jf.translation[1])
                ax = apply(jf.rotation, joint.effective_axis)
                norm = math.sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]) or 1.0
                torque = GRAVITY * share * abs(r[1] * ax[0] - r[0] * ax[1]) / norm
        inertia += joint.armature or 0.0
        effort = joint.limit.effort if joint.limit is not None and joint.limit.effort else None
        weak = effort is not None and effort > 0 and torque > effort
        if stiffness is not None and joint.name in stiffness:
            kp, capped, floored = stiffness[joint.name], False, False
        else:
            kp = inertia * omega * omega
            capped = effort is not None and effort > 0 and kp > effort / E_SAT
            if capped:
                kp = float(effort) / E_SAT  # type: ignore[arg-type]
            # The gravity floor, bounded by what the motor can give at the hold error.
            floor_kp = (min(torque, effort) if weak and effort else torque) / HOLD_ERROR
            floored = floor_kp > kp
            if floored:
                kp, capped = floor_kp, False  # the floor, not the effort cap, set it
            # The floor against a dead actuator, bounded by what the loop's inertia takes stably.
            if effort:
                fastest = inertia * (2.0 * math.pi * F_MAX) ** 2
                kp = max(kp, min(float(effort) / FLOOR_ERROR, fastest))
        kd = 2.0 * DAMPING_RATIO * math.sqrt(max(kp, 0.0) * inertia)
        if stiffness is None or joint.name not in stiffness:
            kd = max(kd, _speed_damping(joint, kp))
        dead = not weak and _dead(joint, kp, torque)
        out[joint.name] = JointGains(kp, kd, inertia, capped, torque, weak, dead, floored)
    return out


def _speed_damping(joint: Joint, kp: float) -> float:
    """The damping at which a step across the joint's whole range is driven no faster than
    SPEED_MARGIN times its velocity limit: a PD loop's speed settles where kd·v = kp·error."""
    limit = joint.limit
    if limit is None or not limit.velocity or limit.lower is None or limit.upper is None:
        return 0.0
    if joint.type.value == "continuous":
        return 0.0
    span = max(limit.upper - limit.lower, 0.0)
    return kp * span / (SPEED_MARGIN * float(limit.velocity))


def _dead(joint: Joint, kp: float, torque: float) -> bool:
    """The stiffness cannot lift what the joint moves: kp times the joint's range is below the gravity
    torque on it (or kp is zero). A motor too weak for the load (its effort below the torque) is
    ``weak``, said apart."""
    if kp <= 0.0:
        return True
    limit = joint.limit
    if not joint.type.is_angular or torque <= 0.0:
        return False
    continuous = joint.type.value == "continuous" or limit is None or limit.lower is None or limit.upper is None
    span = math.pi if continuous else max(limit.upper - limit.lower, 0.0)  # type: ignore[operator,union-attr]
    return kp * span < torque


def fill_default_gains(
    robot: Robot,
    settings: HasGains,
    given: Collection[str],
    stance: Stance,
    floating: bool,
    findings: Findings,
    stage: str,
) -> None:
    """Set ``settings.stiffness``/``damping`` (those the user did not give) to per-joint tables of
    derived gains, with the old constants as the fallback for multi-DOF joints; say so in a finding."""
    user_kp = None
    if "stiffness" in given:
        user_kp = {j.name: lookup(settings.stiffness, j.name, "stiffness") or 0.0 for j in robot.actuated_joints()}
    gains = derived_gains(robot, stance, floating, user_kp)
    if not gains:
        return
    # The tables name every joint; the old constants stay as the fallback for multi-DOF joints.
    if "stiffness" not in given:
        settings.stiffness = {**{re.escape(n): sig4(g.stiffness) for n, g in gains.items()}, ".*": 100.0}
    if "damping" not in given:
        settings.damping = {**{re.escape(n): sig4(g.damping) for n, g in gains.items()}, ".*": 1.0}
    rows = ", ".join(
        f"{n} {sig4(g.stiffness):g}/{sig4(g.damping):g} (I {g.inertia:.3g}{_why(g)})" for n, g in gains.items()
    )
    findings.info(
        "default-gains",
        f"drive gains derived per joint (kp = I_eff·(2π·{NATURAL_FREQUENCY:g} Hz)², at most effort/{E_SAT:g}; "
        f"kd = 2·{DAMPING_RATIO:g}·√(kp·I_eff), at least kp·range/({SPEED_MARGIN:g}·velocity limit)); kp/kd SI: {rows}",
        element=f"robot {robot.name!r}",
        stage=stage,
    )
    weak = {n: g for n, g in gains.items() if g.weak}
    if weak:
        listed = ", ".join(
            f"{n} (gravity up to {g.gravity_torque:.3g} N·m, effort {_effort(robot, n):.3g} N·m)"
            for n, g in weak.items()
        )
        findings.warn(
            "default-gains-weak",
            f"joints whose effort limit is below the gravity torque of the links they move, at their worst: "
            f"the default stiffness is capped at effort/{HOLD_ERROR:g} rad and they may sag: {listed}",
            element=f"robot {robot.name!r}",
            stage=stage,
        )
    dead = [n for n, g in gains.items() if g.dead]
    if dead:
        listed = ", ".join(
            f"{n} (kp {sig4(gains[n].stiffness):g}, gravity up to {gains[n].gravity_torque:.3g} N·m)" for n in dead
        )
        findings.warn(
            "default-gains-dead",
            f"actuators that cannot move their joint against gravity (kp times the joint's range is below the gravity torque of the links it moves): {listed}; give --stiffness, or an effort limit",
            element=f"robot {robot.name!r}",
            stage=stage,
        )


def _effort(robot: Robot, name: str) -> float:
    limit = robot.joint(name).limit
    return float(limit.effort) if limit is not None and limit.effort is not None else math.inf


def sig4(value: float) -> float:
    """Four significant digits: the files stay readable, and mirror-image joints whose inertias
    differ in the last bits share an actuator group."""
    return float(f"{value:.4g}")


class HasGains(Protocol):
    stiffness: Any
    damping: Any


# Subtrees with more massive links than this are summed with numpy: a chain's joints each move every
# link beyond them, n²/2 terms in all (1.25e9 for 50,000 links). Smaller ones keep the exact sums
# (robots of a few hundred links: the numbers are those before this change, bit for bit).
_VECTOR_FROM = 512


class _MovedLinks:
    """Every link a joint moves that has a mass, as a slice of one walk of the tree: (mass, its
    centre of mass in the world, its largest principal moment or None), computed once per link.

    The walk pops the last child first, so each subtree is one contiguous slice, in the order a walk
    started at its root visits it (the sums are the same, term by term, as summing per joint)."""

    def __init__(self, robot: Robot, frames: Mapping[str, Frame]) -> None:
        children = robot.child_joints()
        links = robot.link_map()
        self.rows: list[tuple[float, tuple[float, float, float], float | None]] = []
        order: list[str] = []
        before: list[int] = []  # rows before each link of the walk
        stack = [link.name for link in robot.root_links()]
        seen: set[str] = set()
        while stack:
            name = stack.pop()
            if name in seen or name not in frames:
                continue
            seen.add(name)
            order.append(name)
            before.append(len(self.rows))
            stack.extend(j.child for j in children.get(name, []))
            link = links.get(name)
            if link is None or link.inertial is None or not link.inertial.mass:
                continue
            com = (frames[name] @ pose_frame(link.inertial.origin)).translation
            moment = None
            if link.inertial.inertia is not None:
                moment = max(principal_moments(tensor_rows(link.inertial.inertia)))
            self.rows.append((link.inertial.mass, com, moment))
        before.append(len(self.rows))
        # A subtree is the links from its root to the root's position plus its size in the walk.
        position = {name: i for i, name in enumerate(order)}
        size = dict.fromkeys(order, 1)
        for name in reversed(order):
            size[name] += sum(size[j.child] for j in children.get(name, []) if j.child in position)
        self.start = {name: before[i] for name, i in position.items()}
        self.end = {name: before[i + size[name]] for name, i in position.items()}
        self._arrays: Any = None

    def _slice(self, child: str) -> tuple[int, int]:
        if child not in self.start:
            return 0, 0
        return self.start[child], self.end[child]

    def _vectors(self) -> Any:
        import numpy as np

        if self._arrays is None:
            self._arrays = (
                np.array([r[0] for r in self.rows]),
                np.array([r[1] for r in self.rows]).reshape(-1, 3),
                np.array([r[2] or 0.0 for r in self.rows]),
            )
        return self._arrays

    def inertia(self, joint: Joint, origin: tuple[float, float, float]) -> float:
        """The largest moment of inertia the joint can meet as the joints beyond it move: each link's
        largest principal moment plus m·d², d its centre of mass's distance from the joint (not from
        the axis), so an arm's yaw joint is not left soft because the arm happens to point up at the
        start. Mass, for a prismatic joint."""
        a, b = self._slice(joint.child)
        if b - a > _VECTOR_FROM:
            mass, com, moment = self._vectors()
            if not joint.type.is_angular:
                return float(mass[a:b].sum())
            d2 = ((com[a:b] - origin) ** 2).sum(axis=1)
            return float((mass[a:b] * d2 + moment[a:b]).sum())
        total = 0.0
        angular = joint.type.is_angular
        for m, com_, top in self.rows[a:b]:
            if not angular:
                total += m
                continue
            total += m * _distance_sq(com_, origin)
            if top is not None:
                total += top
        return total

    def moment(self, child: str, origin: tuple[float, float, float]) -> float:
        """sum(m·d) over the links the joint moves, d each centre of mass's distance from the joint:
        the largest gravity torque (divided by g) they can put on it, whatever the joints beyond it do."""
        a, b = self._slice(child)
        if b - a > _VECTOR_FROM:
            import numpy as np

            mass, com, _ = self._vectors()
            # Multiply and sum, not ``@``: a dot product goes to BLAS, whose worker threads spin on a
            # busy machine (a 50,000-link chain sat in exec_blas for minutes).
            return float((mass[a:b] * np.sqrt(((com[a:b] - origin) ** 2).sum(axis=1))).sum())
        return sum(m * math.sqrt(_distance_sq(c, origin)) for m, c, _ in self.rows[a:b])


def _distance_sq(point: tuple[float, float, float], origin: tuple[float, float, float]) -> float:
    d = (point[0] - origin[0], point[1] - origin[1], point[2] - origin[2])
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2]


def _add(a: tuple[float, float, float], b: tuple[float, float, float]) -> tuple[float, float, float]:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _why(g: JointGains) -> str:
    """What set a derived stiffness beyond the inertia's: the effort cap or the gravity floor."""
    if g.floor:
        return ", gravity floor"
    return ", effort-capped" if g.capped else ""
