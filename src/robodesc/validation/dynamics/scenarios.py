"""The scenarios, engine-neutral: what to set up, how long to run, and the documented thresholds.

Every engine runner receives one :class:`Setup` (home pose, gains, spawn height, friction) computed
here from the IR, so the engines differ only in what they read from the output and how they solve
it. Thresholds are loose where engines legitimately differ (contact models, solvers) and tight where
they read the same numbers from the same kind of file (an output against its source in one engine).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robodesc.ir.geometry import Box, Capsule, Cylinder, Mesh, Sphere
from robodesc.ir.model import JointType, Robot
from robodesc.ir.rigid import Frame, link_frames, pose_frame
from robodesc.ir.rules import lookup

# Gains when the compile was given none: the USD drives' defaults (emit/usd/options.py), so every
# engine holds the pose with the drives a USD consumer would get. SI, per rad or per m.
DEFAULT_STIFFNESS = 100.0
DEFAULT_DAMPING = 1.0

Gain = float | Mapping[str, float]


@dataclass(frozen=True, slots=True)
class Thresholds:
    """Documented in docs/dynamics.md; a change here is a change there."""

    # hold: a joint "holds" when it ends within this of its target (rad or m) after the run.
    hold_drift: float = 0.05
    # Engines agree on a hold when their final joint positions differ by less than this.
    hold_agree: float = 0.02
    # drop: engines agree when settled base heights and tilts differ by less than these.
    drop_height_agree: float = 0.03  # m
    drop_tilt_agree: float = math.radians(10.0)  # rad
    upright_tilt: float = math.radians(30.0)  # rad: "stands" in the table
    # slide: a block sticks when it moves less than this in the run, slides when more than slide_min.
    stick_max: float = 0.01  # m
    slide_min: float = 0.05  # m
    # friction read back from an output against the source's (relative).
    friction_rel: float = 1e-3
    # output against its source in the same engine (joint trajectories during hold; rad or m).
    source_traj: float = 1e-3
    # A drive saturates when its peak effort reaches this share of the joint's effort limit (an
    # engine clamps at the limit itself; 0.99 keeps a float's rounding from hiding it).
    saturated: float = 0.99
    # Two engines read the same robot's total mass when within this (relative); a drop that settles
    # apart with masses that differ more is reported as a mass difference, not a contact one.
    mass_rel: float = 0.01


@dataclass(slots=True)
class DynamicsOptions:
    """What ``validate --dynamics`` runs. ``pose`` plugs in a standing pose (issue 29's default
    pose goes here); ``stiffness``/``damping`` are the compile's gains (SI, number or regex table)."""

    duration: float = 1.0  # s, every scenario
    timestep: float = 0.001  # s: MuJoCo and Drake; Newton uses the same
    drop_clearance: float = 0.05  # m: the lowest collider starts this far above the plane
    pose: Mapping[str, float] | None = None  # REGEX -> value, like --init-joint-pos
    stiffness: Gain | None = None
    damping: Gain | None = None
    engines: tuple[str, ...] = ()  # empty: every engine that reads one of the given files
    thresholds: Thresholds = field(default_factory=Thresholds)
    package_paths: Mapping[str, str] = field(default_factory=dict)
    newton_python: str | None = None  # the Newton venv's interpreter (default: the consumer tier's)
    physx_python: str | None = None  # an interpreter with ovphysx (default: validation.physx_python's search)
    # The base the compiled files have (robodesc.emit.common.base.choose_base, which
    # ``validate --dynamics`` fills): True welds it, and the drop is not run; None: judged by the feet.
    fix_base: bool | None = None
    # What chose the pose and gains when the caller gave none (``validate --dynamics`` fills them
    # with the Isaac folder's defaults, robodesc.check_dynamics.default_stance); shown in the report.
    defaults: str | None = None
    # Record the dropped root's pose at every trajectory sample (``Run.root``), for the clips of
    # ``validate --video``; off, the runners read nothing more than the verdicts need.
    record: bool = False
    # Called with a line before each engine runs (``validate --dynamics`` prints it on a terminal).
    progress: Callable[[str], None] | None = None
    # A world to stand the robot in (``validate --dynamics --world``): the "stand" scenario.
    world: WorldStand | None = None
    # A file's own name -> the source's, for a file that names links and joints otherwise and keeps
    # no displayName: Isaac Sim 6's import of robodesc's Isaac URDF names them as that URDF does,
    # sanitized (Spirit's joint "0" is "a0"). PhysX's worker reads it.
    names: Mapping[str, str] = field(default_factory=dict)


@dataclass(slots=True)
class WorldStand:
    """The stand on a world (``validate --dynamics --world``), placed once by the driver: the world
    files each engine reads (kind -> path: MJCF's scene.xml, USD's world stage), where the root
    starts (x, y, z at the home pose, yaw), each foot's sole (its lowest point at the home pose, in
    the foot link's frame), the links with contact sensors, and the ground's height at any x, y
    (NaN over none; the terrain as USD and SDF keep it). ``heightfields``: each terrain as a grid
    file (.npz: z, x0, y0, step, the frame's x, y, z, yaw) and the USD prim it replaces, for Newton,
    whose MuJoCo solver collides a triangle mesh as its convex hull."""

    files: dict[str, str]
    spawn: tuple[float, float, float, float]
    soles: dict[str, tuple[float, float, float]]
    ground: Callable[[NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]]
    sensors: tuple[str, ...] = ()
    heightfields: list[dict[str, Any]] = field(default_factory=list)
    duration: float = 2.0  # s: a dropped robot settles on its feet within 1 s, the sensors are read after

    def as_dict(self) -> dict[str, Any]:
        return {
            "spawn": list(self.spawn),
            "feet": list(self.soles),
            "sensors": list(self.sensors),
            "heightfields": self.heightfields,
            "duration": self.duration,
        }


@dataclass(slots=True)
class Setup:
    """What every engine is given: the same numbers, from the IR."""

    pose: dict[str, float]  # every actuated 1-DOF joint (mimics excluded)
    gains: dict[str, tuple[float, float]]  # joint -> (kp, kd), SI
    # The base floats and the robot stands on three or more links: the drop scenario applies (stands()).
    floating: bool
    stand_height: float  # m: root height at which the lowest collider touches z = 0 at the pose
    friction: float | None  # the source's collider friction (None: not given, engine default)
    # The links the robot stands on at the home pose (feet, wheels), when it stands: the slide's
    # material and the drop floor's friction are theirs, as the ground touches nothing else.
    feet: tuple[str, ...] = ()
    # Mimic joints: follower -> leader. An output that cannot carry a mimic (SDF before 1.11) has
    # already warned at compile time; a trajectory that differs there is that warning, not a new fault.
    mimics: dict[str, str] = field(default_factory=dict)
    # Each mimic follower's position at the home pose (multiplier x leader + offset): every engine
    # starts it there, as the mimic constraint will hold it. Left at 0 with its leader posed, the
    # constraint starts violated and each engine corrects it its own way: PhysX ran tiago_pro's arms
    # away from a 0.15 rad gripper mismatch (docs/dynamics.md).
    followers: dict[str, float] = field(default_factory=dict)
    # Each driven joint's effort limit (N·m or N) where the source gives one > 0: the saturation
    # columns divide the peak drive effort by it.
    effort: dict[str, float] = field(default_factory=dict)
    # kg: the sum of the source's <inertial> masses (None: not known).
    mass: float | None = None
    duration: float = 1.0
    timestep: float = 0.001
    drop_clearance: float = 0.05
    record: bool = False  # DynamicsOptions.record
    world: WorldStand | None = None
    names: dict[str, str] = field(default_factory=dict)  # DynamicsOptions.names
    # Armature the source run is given (joint -> kg·m²): what the compared file adds to a source
    # that has none (the mjcf preset's default armature, docs/passes.md), so the source comparison
    # measures the writing, not that documented default.
    source_armature: dict[str, float] = field(default_factory=dict)

    def start(self) -> dict[str, float]:
        """Every joint a scenario positions at its start: the home pose and the followers of it."""
        return {**self.followers, **self.pose}

    def as_dict(self) -> dict[str, Any]:
        return {
            "world": self.world.as_dict() if self.world is not None else None,
            "pose": self.pose,
            "start": self.start(),
            "gains": {k: list(v) for k, v in self.gains.items()},
            "stand_height": self.stand_height,
            "friction": self.friction,
            "feet": list(self.feet),
            "mass": self.mass,
            "duration": self.duration,
            "timestep": self.timestep,
            "drop_clearance": self.drop_clearance,
            # Only when asked: the report's setup (info["setup"]) stays as it was without them.
            **({"record": True} if self.record else {}),
            **({"names": self.names} if self.names else {}),
            **({"source_armature": self.source_armature} if self.source_armature else {}),
        }


def actuated(robot: Robot) -> list[str]:
    """1-DOF joints a drive moves: mimics follow their leader and get none."""
    return [j.name for j in robot.joints if j.type.dof == 1 and j.mimic is None]


def home_pose(robot: Robot, table: Mapping[str, float] | None = None) -> dict[str, float]:
    """``table`` (first matching regex) where it names a joint, else 0; clamped into the limits,
    since a drive cannot hold a target its limit refuses."""
    q: dict[str, float] = {}
    joints = robot.joint_map()
    for name in actuated(robot):
        wanted = lookup(table, name, "pose") if table else None
        value = 0.0 if wanted is None else wanted
        lim = joints[name].limit
        bounded = lim is not None and lim.lower is not None and lim.upper is not None and lim.lower <= lim.upper
        if joints[name].type is not JointType.CONTINUOUS and bounded and lim is not None:
            assert lim.lower is not None and lim.upper is not None
            value = min(max(value, lim.lower), lim.upper)
        q[name] = value
    return q


def drive_gains(robot: Robot, stiffness: Gain | None, damping: Gain | None) -> dict[str, tuple[float, float]]:
    out: dict[str, tuple[float, float]] = {}
    for name in actuated(robot):
        k = lookup(stiffness, name, "stiffness") if stiffness is not None else None
        d = lookup(damping, name, "damping") if damping is not None else None
        out[name] = (DEFAULT_STIFFNESS if k is None else k, DEFAULT_DAMPING if d is None else d)
    return out


def source_friction(robot: Robot, feet: tuple[str, ...] = ()) -> float | None:
    """The sliding friction of the robot's colliders when the source gives all of them the same one
    (docs/contact.md); None otherwise. The slide scenario puts one block of the robot's material on
    a plane. A robot that stands is judged by its feet (``feet``: Spirit's toes give 0.5 while its
    body gives none), since they are what touches the ground; a robot whose colliders differ and
    that does not stand has no single friction to compare."""
    found: set[float | None] = set()
    chosen = [link for link in robot.links if link.name in feet and link.collisions]
    for link in chosen or robot.links:
        for col in link.collisions:
            contact = link.collision_contact(col)
            found.add(contact.mu if contact is not None else None)
    if len(found) == 1:
        (value,) = found
        return float(value) if value is not None else None
    return None


def slide_angles(mu: float) -> tuple[float, float]:
    """A plane tilted where the block must stick (tan = 0.7 mu) and where it must slide (1.3 mu);
    30 % either side keeps the outcome clear of each engine's friction-cone approximation."""
    return math.atan(0.7 * mu), math.atan(1.3 * mu)


def _link_lows(robot: Robot, pose: Mapping[str, float]) -> dict[str, float]:
    """Each link's lowest collider point (z, root frame) at the pose."""
    frames = link_frames(robot, pose)
    lows: dict[str, float] = {}
    for link in robot.links:
        frame = frames.get(link.name)
        for col in link.collisions if frame is not None else []:
            assert frame is not None
            low = _lowest(frame @ pose_frame(col.origin), col.geometry)
            lows[link.name] = min(lows.get(link.name, math.inf), low)
    return lows


def stand_height(robot: Robot, pose: Mapping[str, float]) -> float:
    """Root height putting the lowest collider point at z = 0 (root upright, at the pose).

    Meshes count by their file's vertices when robodesc can read them, else by the link origin:
    an estimate for placing the robot, not a measurement (each engine reports where it settles).
    """
    lowest = min(_link_lows(robot, pose).values(), default=math.inf)
    return 0.0 if not math.isfinite(lowest) else -lowest


# Links within this of the lowest point count as touching the ground at the home pose.
FOOT_BAND = 0.01  # m


def feet(robot: Robot, pose: Mapping[str, float]) -> tuple[str, ...]:
    """The links within :data:`FOOT_BAND` of the lowest collider point at the pose, in link order."""
    lows = _link_lows(robot, pose)
    lowest = min(lows.values(), default=math.inf)
    return tuple(name for name, z in lows.items() if z <= lowest + FOOT_BAND) if math.isfinite(lowest) else ()


def stands(robot: Robot, pose: Mapping[str, float]) -> bool:
    """Whether the drop scenario applies: a free root (not welded to ``world``) and at least three
    links touching the ground at the home pose (feet, wheels). An arm or a biped on one sole would
    topple from any pose, and a fall is chaotic: no two engines are expected to agree on it."""
    roots = robot.root_links()
    if not roots or roots[0].name == "world":
        return False
    return len(feet(robot, pose)) >= 3


def _lowest(frame: Frame, geom: object) -> float:
    z = frame.translation[2]
    r = frame.rotation
    if isinstance(geom, Sphere):
        return z - geom.radius
    if isinstance(geom, Box):
        hx, hy, hz = (s / 2 for s in geom.size)
        return z - (abs(r[2][0]) * hx + abs(r[2][1]) * hy + abs(r[2][2]) * hz)
    if isinstance(geom, Cylinder | Capsule):
        half = geom.length / 2
        caps = geom.radius if isinstance(geom, Capsule) else geom.radius * math.hypot(r[2][0], r[2][1])
        return z - abs(r[2][2]) * half - caps
    if isinstance(geom, Mesh):
        points = _mesh_points(geom)
        return z if points is None or not len(points) else z + float(np.min(points @ np.asarray(r[2])))
    return z


def _mesh_points(mesh: Mesh) -> NDArray[np.float64] | None:
    if mesh.path is None:
        return None
    try:
        from robodesc.meshes.data import build_mesh

        data = build_mesh(mesh.path, mesh.scale)
    except Exception:  # an unreadable mesh only makes the estimate coarser
        return None
    return np.frombuffer(data.points, dtype=np.float32).reshape(-1, 3).astype(np.float64)


def follower_pose(robot: Robot, pose: Mapping[str, float]) -> dict[str, float]:
    """Mimic follower -> multiplier x its leader's home position + offset, for the followers of a
    posed 1-DOF leader (chains of followers followed to their end)."""
    out: dict[str, float] = {}
    mimics = {j.name: j.mimic for j in robot.joints if j.mimic is not None and j.type.dof == 1}
    for _ in range(len(mimics)):  # a follower of a follower resolves once its leader has
        for name, m in mimics.items():
            lead = pose.get(m.joint, out.get(m.joint))
            if name not in out and lead is not None:
                out[name] = (1.0 if m.multiplier is None else m.multiplier) * lead + (m.offset or 0.0)
    return out


def effort_limits(robot: Robot) -> dict[str, float]:
    """Driven joint -> its effort limit, for the joints whose source gives one above zero."""
    joints = robot.joint_map()
    out: dict[str, float] = {}
    for name in actuated(robot):
        lim = joints[name].limit
        if lim is not None and lim.effort is not None and lim.effort > 0 and math.isfinite(lim.effort):
            out[name] = float(lim.effort)
    return out


def make_setup(robot: Robot, options: DynamicsOptions) -> Setup:
    pose = home_pose(robot, options.pose)
    floating = options.fix_base is not True and stands(robot, pose)
    standing_on = feet(robot, pose) if floating else ()
    return Setup(
        pose=pose,
        gains=drive_gains(robot, options.stiffness, options.damping),
        floating=floating,
        stand_height=stand_height(robot, pose),
        friction=source_friction(robot, standing_on),
        feet=standing_on,
        mimics={j.name: j.mimic.joint for j in robot.joints if j.mimic is not None},
        followers=follower_pose(robot, pose),
        effort=effort_limits(robot),
        mass=sum(link.inertial.mass or 0.0 for link in robot.links if link.inertial is not None),
        duration=options.duration,
        timestep=options.timestep,
        drop_clearance=options.drop_clearance,
        record=options.record,
        world=options.world,
        names=dict(options.names),
    )
