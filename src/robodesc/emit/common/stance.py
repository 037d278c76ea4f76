"""The default pose of a floating robot, and the height it spawns at (docs/isaac.md, "The default pose").

A floating robot spawned with every joint at zero usually cannot stand: a quadruped's legs are
straight (or, clamped into their limits, bent the wrong way) and it tips over. When the user gives
no initial joint positions, the pose is chosen in this order:

1. a pose the source names (:mod:`robodesc.emit.common.named_pose`: SRDF ``group_state``,
   ros2_control ``initial_value``), when it is a stance (:func:`stance_defect`): the feet the robot
   has at zero are its lowest points there too, and a biped's soles are as level as at zero (iCub's
   ``half_sitting`` pitches them 3.6°, and it tipped over from it where its zero pose stands);
2. the legged heuristic (:func:`legged_pose`): legs are found as chains from the root to the lowest
   links; in each, the first two joints that pitch about the robot's lateral axis (hip, knee) are
   bent so that the foot (where it stands: :func:`_foot_point`) sits straight under the hip at 75 % of the leg's reach, a third pitch joint
   (ankle) keeps the sole as it was at zero, every other joint stays at zero. Robots with three legs
   or more only: a biped's balance depends on where its centre of mass is, which this does not model;
3. zeros, with a warning.

Positions are clamped into the limits. The spawn height puts the lowest collision point of the
robot at that pose 5 mm above the ground.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

from robodesc.emit.common.named_pose import named_pose
from robodesc.ir.geometry import Box, Capsule, Cylinder, Mesh, Pose, Sphere, Vec3
from robodesc.ir.model import Joint, JointType, Link, Robot
from robodesc.ir.rigid import Frame, apply, joint_motion, link_frames, pose_frame, resolve_mimic
from robodesc.meshes.buffers import MeshReadError
from robodesc.meshes.data import MeshCache

# Leg reach at the stance, as a fraction of the straight leg: a quadruped crouches (Isaac Lab's own
# Go1/A1 configs stand at ~73 %).
REACH_QUADRUPED = 0.75
CLEARANCE = 0.005  # m between the lowest collision point and the ground at spawn
# A joint pitches when its axis lies within this angle of the robot's lateral (y) axis.
_PITCH_COS = math.cos(math.radians(30.0))
_KNEE_SAMPLES = 181
# A named pose is a stance when every foot's lowest point is within this of the robot's lowest point
FOOT_BAND = 0.01  # m
# and, on two legs, each sole is within this of its tilt at zero (where URDF soles are flat).
SOLE_TILT = math.radians(1.0)
SOLE_BAND = 0.002  # m: a mesh foot's vertices this close to its lowest one are its sole


@dataclass(slots=True, frozen=True)
class Leg:
    foot: str  # the link at the end of the chain (the lowest link of the leg)
    joints: tuple[str, ...]  # its 1-DOF joints, root to foot
    foot_point: Vec3  # a point of the foot (its lowest collider's centre), in the foot's frame


@dataclass(slots=True)
class Stance:
    positions: dict[str, float]  # every 1-DOF joint, mimic followers included
    source: str  # what chose it: "init_joint_pos", "SRDF group_state ...", "legged heuristic", "zeros"
    legs: list[Leg] = field(default_factory=list)
    lowest_z: float | None = None  # lowest collision point, in the root frame, at this pose
    skipped: str | None = None  # a named pose not used, and why (for the finding)


def limits(joint: Joint) -> tuple[float, float]:
    lim = joint.limit
    if joint.type is JointType.CONTINUOUS or lim is None or lim.lower is None or lim.upper is None:
        return (-math.pi, math.pi) if joint.type.is_angular else (-math.inf, math.inf)
    return (lim.lower, lim.upper) if lim.lower <= lim.upper else (0.0, 0.0)


def clamp(joint: Joint, q: float) -> float:
    lo, hi = limits(joint)
    return min(max(q, lo), hi)


def complete(robot: Robot, given: Mapping[str, float]) -> dict[str, float]:
    """Every 1-DOF joint's position: ``given`` clamped into the limits, 0 (clamped) otherwise,
    mimic followers from their leaders."""
    actuated = {j.name: clamp(j, given.get(j.name, 0.0)) for j in robot.actuated_joints() if j.type.dof == 1}
    joints = robot.joint_map()  # once: asked per joint, it made a 50,000-joint chain quadratic
    return {k: v for k, v in resolve_mimic(robot, actuated).items() if k in joints}


def choose_stance(robot: Robot, given: Mapping[str, float] | None) -> Stance:
    """The pose of a floating robot: the user's, else the source's, else the heuristic's, else zeros."""
    meshes = MeshCache()
    pose = None if given else named_pose(robot)
    skipped = None
    if pose is not None and (why := stance_defect(robot, complete(robot, pose.positions), meshes)) is not None:
        skipped, pose = f"{pose.source}: {why}", None
    if given:
        stance = Stance(complete(robot, given), "init_joint_pos")
    elif pose is not None:
        stance = Stance(complete(robot, pose.positions), pose.source)
    elif (found := legged_pose(robot, meshes)) is not None:
        stance = Stance(complete(robot, found[0]), "legged heuristic", legs=found[1])
    else:
        stance = Stance(complete(robot, {}), "zeros")
    stance.skipped = skipped
    if not stance.legs:
        stance.legs = find_legs(robot, stance.positions, meshes)
    stance.lowest_z = lowest_point(robot, stance.positions, meshes)
    return stance


def stance_defect(robot: Robot, q: Mapping[str, float], meshes: MeshCache | None = None) -> str | None:
    """Why the robot cannot stand in pose ``q`` (a named pose), judged by the feet it has at zero;
    None when it can, or when it has no legs to judge by (a floating arm keeps its named pose).

    The feet found at zero must be the lowest points at ``q`` too (within :data:`FOOT_BAND`), and on
    two legs each sole must be as level as at zero (within :data:`SOLE_TILT`): a biped stands on
    its soles' faces, a robot with three legs or more on foot points whose tilt does not matter."""
    meshes = meshes or MeshCache()
    zero = complete(robot, {})
    legs = find_legs(robot, zero, meshes)
    if not legs:
        return None
    frames = link_frames(robot, q)
    lowest = lowest_point(robot, q, meshes)
    for leg in legs:
        z = _link_lowest(robot.link(leg.foot), frames[leg.foot], meshes, exact=True)
        if z is None or lowest is None or z > lowest + FOOT_BAND:
            return f"foot {leg.foot!r} is not among the lowest points (it is {(z or 0.0) - (lowest or 0.0):.3f} m up)"
    if len(legs) == 2:
        frames0 = link_frames(robot, zero)
        for leg in legs:
            up, up0 = frames[leg.foot].rotation[2], frames0[leg.foot].rotation[2]
            tilt = math.acos(max(-1.0, min(1.0, _dot(up, up0))))
            if tilt > SOLE_TILT:
                return f"sole {leg.foot!r} is tilted {math.degrees(tilt):.1f}° from its zero pose (a biped stands on level soles)"
    return None


# ---- legs ------------------------------------------------------------------------------------


def _collision_links(robot: Robot) -> set[str]:
    return {link.name for link in robot.links if link.collisions}


def find_legs(robot: Robot, q: Mapping[str, float], meshes: MeshCache | None = None) -> list[Leg]:
    """Chains from the root to the lowest colliding links that have two pitch joints (hip, knee):
    what the robot stands on. Wheels and casters (one pitch joint) are not legs."""
    frames = link_frames(robot, q)
    meshes = meshes or MeshCache()
    parent = robot.parent_joint()
    colliding = _collision_links(robot)
    children = robot.child_joints()
    # A foot candidate: a colliding link with no colliding link below it.
    below: dict[str, bool] = {}

    def has_collider_below(name: str) -> bool:
        if name not in below:
            below[name] = any(j.child in colliding or has_collider_below(j.child) for j in children.get(name, []))
        return below[name]

    lows: dict[str, float] = {}
    for name in colliding:
        if not has_collider_below(name) and name != robot.root.name:
            z = _link_lowest(robot.link(name), frames[name], meshes, exact=False)
            if z is not None:
                lows[name] = z
    if not lows:
        return []
    bottom = min(lows.values())
    top = max(f.translation[2] for f in frames.values())
    tolerance = max(0.02, 0.1 * (top - bottom))
    legs: dict[tuple[str, ...], Leg] = {}
    for foot, z in sorted(lows.items(), key=lambda item: item[1]):
        if z > bottom + tolerance:
            continue
        chain: list[Joint] = []
        link = foot
        while link in parent:
            joint = parent[link]
            if joint.type.dof == 1 and joint.mimic is None:
                chain.append(joint)
            link = joint.parent
        chain.reverse()
        names = tuple(j.name for j in chain)
        # Two colliders at the end of one chain (a shin and its toe) are one leg: the lower one.
        if names not in legs and len(_pitch_joints(chain, frames, robot)) >= 2:
            legs[names] = Leg(foot, names, _foot_point(robot.link(foot), frames[foot], meshes))
    # A chain that another leg's chain continues is that leg's (a shin's own collider link hanging
    # off the knee: Romeo's KneePitchCollision_shape), not a leg of its own.
    found = sorted(
        (leg for names, leg in legs.items() if not any(len(o) > len(names) and o[: len(names)] == names for o in legs)),
        key=lambda leg: leg.foot,
    )
    return found if len(found) >= 2 else []


def _joint_frame(robot: Robot, joint: Joint, frames: Mapping[str, Frame]) -> Frame:
    return frames[joint.parent] @ pose_frame(joint.origin)


def _pitch_joints(chain: list[Joint], frames: Mapping[str, Frame], robot: Robot) -> list[Joint]:
    out = []
    for joint in chain:
        if not joint.type.is_angular:
            continue
        axis = apply(_joint_frame(robot, joint, frames).rotation, joint.effective_axis)
        norm = math.sqrt(sum(a * a for a in axis))
        if norm > 0 and abs(axis[1]) / norm >= _PITCH_COS:
            out.append(joint)
    return out


def lowest_collider(link: Link, frame: Frame, meshes: MeshCache) -> int:
    """The index of the link's lowest collider with the link at ``frame``: a foot's sole or toe."""

    def low(i: int) -> float:
        c = link.collisions[i]
        z = _shape_lowest(c.geometry, frame @ pose_frame(c.origin), False, meshes)
        return math.inf if z is None else z

    return min(range(len(link.collisions)), key=low)


def foot_colliders(robot: Robot, stance: Stance) -> dict[str, int]:
    """Each leg's foot link and the index of its collider that touches the ground in the stance."""
    frames = link_frames(robot, stance.positions)
    meshes = MeshCache()
    return {
        leg.foot: lowest_collider(robot.link(leg.foot), frames[leg.foot], meshes)
        for leg in stance.legs
        if robot.link(leg.foot).collisions
    }


def _foot_point(link: Link, frame: Frame, meshes: MeshCache) -> Vec3:
    """Where the foot stands, in its link's frame: the centre of a sphere or box (a point foot
    rolls about its centre; a sole's middle), the lower end of a capsule's or cylinder's axis (a
    shin that ends on the ground: its middle is not under the hip), the sole of a mesh; at
    the pose ``frame`` was taken at (a mesh: the middle of its vertices within ``SOLE_BAND`` of the lowest). Of the link's lowest collider (a shin's sphere toe, not the
    shin's box)."""
    if not link.collisions:
        return (0.0, 0.0, 0.0)
    collision = link.collisions[lowest_collider(link, frame, meshes)]
    local = pose_frame(collision.origin)
    geometry = collision.geometry
    if isinstance(geometry, Capsule | Cylinder):
        ends = [local @ pose_frame(Pose(xyz=(0.0, 0.0, s * geometry.length / 2))) for s in (-1.0, 1.0)]
        return min(ends, key=lambda end: (frame @ end).translation[2]).translation
    if isinstance(geometry, Mesh) and geometry.path:
        try:
            data = meshes.get(str(geometry.path), geometry.scale)
        except (MeshReadError, OSError):
            return local.translation
        f = frame @ local
        a, b, c = f.rotation[2]
        pts = data.points
        heights = [a * pts[k] + b * pts[k + 1] + c * pts[k + 2] for k in range(0, len(pts), 3)]
        # The middle of what touches: every vertex within SOLE_BAND of the lowest (a flat sole's
        # corners average to its centre; a pointed foot has one vertex there).
        lowest = min(heights)
        near = [3 * i for i, h in enumerate(heights) if h <= lowest + SOLE_BAND]
        mid = tuple(sum(pts[k + axis] for k in near) / len(near) for axis in range(3))
        return (local @ pose_frame(Pose(xyz=(mid[0], mid[1], mid[2])))).translation
    return local.translation


# ---- the legged heuristic ------------------------------------------------------------------------


def legged_pose(robot: Robot, meshes: MeshCache | None = None) -> tuple[dict[str, float], list[Leg]] | None:
    """Hip and knee of every leg bent so the foot is under the hip (module docstring); None when the
    robot has no legs, or a leg cannot reach such a pose within its limits."""
    q = complete(robot, {})
    legs = find_legs(robot, q, meshes)
    # A biped balances its centre of mass over two feet, which this heuristic does not model:
    # bent knees tipped every iCub over in Newton, where the straight zero pose stands. Bipeds
    # keep their named pose (talos' half_sitting) or zeros, with the warning.
    if len(legs) < 3:
        return None
    reach = REACH_QUADRUPED
    joints = robot.joint_map()
    for leg in legs:
        solved = _solve_leg(robot, leg, q, reach, joints)
        if solved is None:
            return None
        q.update(solved)
    return q, legs


def _solve_leg(
    robot: Robot, leg: Leg, q: dict[str, float], reach: float, joints: Mapping[str, Joint]
) -> dict[str, float] | None:
    path = _path(robot, leg.foot)
    chain = [joints[n] for n in leg.joints]
    pitch = _pitch_joints(chain, link_frames(robot, q), robot)
    hip, knee = pitch[0], pitch[1]
    ankle = pitch[2] if len(pitch) >= 3 else None
    frames0 = _chain_frames(path, q)
    sign = {j.name: math.copysign(1.0, apply(frames0[j.name].rotation, j.effective_axis)[1]) for j in pitch}
    # The leg's own forward: its first joint's x (ANYmal's hind HAA frames are yawed half a turn).
    facing = -1.0 if apply(frames0[chain[0].name].rotation, (1.0, 0.0, 0.0))[0] < -1e-6 else 1.0
    # One turn at most: a continuous knee or a +-2 pi range would offer the same bend twice.
    lo, hi = max(limits(knee)[0], -math.pi), min(limits(knee)[1], math.pi)
    candidates: list[tuple[float, float, dict[str, float]]] = []
    for i in range(_KNEE_SAMPLES):
        qk = lo + (hi - lo) * i / (_KNEE_SAMPLES - 1)
        trial = {**q, knee.name: qk, hip.name: 0.0}
        if ankle is not None:
            trial[ankle.name] = 0.0
        # Two rounds: the ankle that keeps the sole level moves the foot point a little.
        length = 0.0
        for _ in range(2):
            qh, length = _hip_angle(path, leg, trial, hip)
            trial[hip.name] = qh
            if ankle is not None:
                trial[ankle.name] = -(sign[hip.name] * qh + sign[knee.name] * qk) * sign[ankle.name]
        moved = [hip] + ([ankle] if ankle is not None else [])
        if not all(limits(j)[0] - 1e-9 <= trial[j.name] <= limits(j)[1] + 1e-9 for j in moved):
            continue
        frames = _chain_frames(path, trial)
        knee_x = frames[knee.name].translation[0]
        foot_x = frames[""].translation[0]
        # Ties between the two knee directions go to the knee behind the foot (dog-like legs),
        # "behind" as the leg is built: along its first joint's own x. ANYmal C's hind hips are its front ones
        # turned half a turn, and its hind knees point forward (as its SRDF and Isaac Lab's config bend
        # them); in the robot's frame all four knees bent backward.
        candidates.append((length, 0.0 if (knee_x - foot_x) * facing <= 0.0 else 1.0, trial))
    if not candidates:
        return None
    target = reach * max(c[0] for c in candidates)
    best = min(candidates, key=lambda c: (round(abs(c[0] - target), 3), c[1]))
    # Microradians: mirror-image legs read the same in every file, whatever the last bits of FK.
    return {j.name: round(best[2][j.name], 6) for j in pitch[:3]}


def _path(robot: Robot, link: str) -> list[Joint]:
    """The joints from the root to ``link``."""
    parent = robot.parent_joint()
    out = []
    while link in parent:
        out.append(parent[link])
        link = parent[link].parent
    return out[::-1]


def _chain_frames(path: list[Joint], q: Mapping[str, float]) -> dict[str, Frame]:
    """Root-frame transforms along one chain: each joint's frame (before its motion) by joint name,
    and the chain's last link under ``""``. Cheaper than the whole robot's FK, and the leg search
    runs it a few hundred times."""
    frame = Frame()
    out: dict[str, Frame] = {}
    for joint in path:
        frame = frame @ pose_frame(joint.origin)
        out[joint.name] = frame
        position = q.get(joint.name, 0.0)
        if position:
            frame = frame @ joint_motion(joint, position)
    out[""] = frame
    return out


def _hip_angle(path: list[Joint], leg: Leg, q: Mapping[str, float], hip: Joint) -> tuple[float, float]:
    """The hip angle that puts the foot point straight under the hip axis, and the hip-to-foot
    distance in the plane the hip turns in."""
    frames = _chain_frames(path, {**q, hip.name: 0.0})
    jf = frames[hip.name]
    axis = _unit(apply(jf.rotation, hip.effective_axis))
    foot = frames[""]
    p = _add(foot.translation, apply(foot.rotation, leg.foot_point))
    v = _sub(p, jf.translation)
    vp = _sub(v, _scale(axis, _dot(v, axis)))
    down = _sub((0.0, 0.0, -1.0), _scale(axis, -axis[2]))
    angle = math.atan2(_dot(axis, _cross(vp, down)), _dot(vp, down))
    return angle, math.sqrt(_dot(vp, vp))


# ---- the lowest point -----------------------------------------------------------------------------


def lowest_point(
    robot: Robot,
    q: Mapping[str, float],
    meshes: MeshCache | None = None,
    *,
    root: Frame | None = None,
    exact: bool = True,
) -> float | None:
    """The lowest z of every collider at pose ``q``, in the root link's frame, or in the world with
    the root placed at ``root``; meshes by their vertices, or by their bounding box (``exact=False``)."""
    frames = link_frames(robot, q)
    meshes = meshes or MeshCache()
    best: float | None = None
    for link in robot.links:
        if link.name in frames:
            at = frames[link.name] if root is None else root @ frames[link.name]
            z = _link_lowest(link, at, meshes, exact=exact)
            if z is not None and (best is None or z < best):
                best = z
    return best


def _link_lowest(link: Link, frame: Frame, meshes: MeshCache, *, exact: bool) -> float | None:
    out: float | None = None
    for collision in link.collisions:
        f = frame @ pose_frame(collision.origin)
        z = _shape_lowest(collision.geometry, f, exact, meshes)
        if z is not None and (out is None or z < out):
            out = z
    return out


def _shape_lowest(geometry: object, f: Frame, exact: bool, meshes: MeshCache) -> float | None:
    r = f.rotation
    cz = f.translation[2]
    if isinstance(geometry, Sphere):
        return cz - geometry.radius
    if isinstance(geometry, Box):
        hx, hy, hz = (s / 2 for s in geometry.size)
        return cz - abs(r[2][0]) * hx - abs(r[2][1]) * hy - abs(r[2][2]) * hz
    if isinstance(geometry, Cylinder | Capsule):
        az = abs(r[2][2])  # the shape's axis (local z) against world z
        side = geometry.radius if isinstance(geometry, Capsule) else geometry.radius * math.sqrt(max(0.0, 1 - az * az))
        return cz - az * geometry.length / 2 - side
    if isinstance(geometry, Mesh) and geometry.path:
        return _mesh_lowest(geometry, f, exact, meshes)
    return None


def _mesh_lowest(mesh: Mesh, f: Frame, exact: bool, meshes: MeshCache) -> float | None:
    try:
        data = meshes.get(str(mesh.path), mesh.scale)
    except (MeshReadError, OSError):
        return None
    a, b, c = f.rotation[2]
    if not exact:  # the box around the mesh: a bound, enough to tell feet from the rest
        (x0, y0, z0), (x1, y1, z1) = data.extent
        return f.translation[2] + min(a * x + b * y + c * z for x in (x0, x1) for y in (y0, y1) for z in (z0, z1))
    pts = data.points
    return f.translation[2] + min(a * pts[i] + b * pts[i + 1] + c * pts[i + 2] for i in range(0, len(pts), 3))


def shape_low_point(geometry: object, f: Frame, meshes: MeshCache | None = None) -> Vec3 | None:
    """A lowest point of a shape placed at ``f``, in ``f``'s parent frame: exact for primitives, the
    lowest corner of the bounding box for a mesh; None for a shape with nothing to measure."""
    r = f.rotation
    down = (r[2][0], r[2][1], r[2][2])  # the world's z in the shape's frame
    if isinstance(geometry, Sphere):
        local: Vec3 = _scale(down, -geometry.radius)
    elif isinstance(geometry, Box):
        local = tuple(-math.copysign(s / 2, d) if d else 0.0 for s, d in zip(geometry.size, down, strict=True))  # type: ignore[assignment]
    elif isinstance(geometry, Cylinder | Capsule):
        end = (0.0, 0.0, -math.copysign(geometry.length / 2, down[2]) if down[2] else 0.0)
        side = (down[0], down[1], 0.0 if isinstance(geometry, Cylinder) else down[2])
        n = math.sqrt(_dot(side, side))
        local = _sub(end, _scale(side, geometry.radius / n)) if n > 0 else end
    elif isinstance(geometry, Mesh) and geometry.path:
        try:
            data = (meshes or MeshCache()).get(str(geometry.path), geometry.scale)
        except (MeshReadError, OSError):
            return None
        lo, hi = data.extent
        local = tuple(lo[i] if down[i] > 0 else hi[i] for i in range(3))  # type: ignore[assignment]
    else:
        return None
    return (f @ pose_frame(Pose(xyz=local))).translation


# ---- small vector helpers ------------------------------------------------------------------------


def _dot(a: Vec3, b: Vec3) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a: Vec3, b: Vec3) -> Vec3:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _add(a: Vec3, b: Vec3) -> Vec3:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _sub(a: Vec3, b: Vec3) -> Vec3:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _scale(a: Vec3, s: float) -> Vec3:
    return (a[0] * s, a[1] * s, a[2] * s)


def _unit(a: Vec3) -> Vec3:
    n = math.sqrt(_dot(a, a))
    return _scale(a, 1.0 / n) if n > 0 else a
