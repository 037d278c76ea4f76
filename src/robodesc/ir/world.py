"""The world around a robot: the ground, static bodies beside it, and the physics it runs under.

A world is read once (frontends/world) and every target writes the same one in its own terms
(docs/worlds.md): the decision of what the robot stands on is made before the emitters."""

from __future__ import annotations

from dataclasses import dataclass, field

from robodesc.ir.diagnostics import SourceLoc
from robodesc.ir.geometry import Box, Cylinder, Mesh, Pose, Sphere, Vec3


@dataclass(slots=True)
class HeightImage:
    """A height image (8- or 16-bit grey PNG): black is the lowest point, white ``size[2]`` above it;
    it spans ``size[0]`` by ``size[1]`` metres centred on its body's origin (Gazebo's heightmap)."""

    path: str
    size: Vec3
    src: SourceLoc | None = None


WorldShape = Box | Cylinder | Sphere | Mesh | HeightImage


@dataclass(slots=True)
class Plane:
    """An infinite plane through the body's origin, its normal ``normal`` (SDF's ``<plane>``)."""

    normal: Vec3 = (0.0, 0.0, 1.0)
    src: SourceLoc | None = None


@dataclass(slots=True)
class Surface:
    """Coulomb friction in ODE's two directions, as SDF's ``<surface><friction><ode>`` says it."""

    mu: float | None = None
    mu2: float | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class WorldCollider:
    """One collider of a static body: its shape in the body's frame, and its surface."""

    name: str
    shape: WorldShape | Plane
    origin: Pose = field(default_factory=Pose)
    surface: Surface | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class StaticBody:
    """A static model of the world (terrain, a wall, the ground plane), placed in the world frame.

    ``pose`` is the model's pose composed with its link's (SDF poses of one static link)."""

    name: str
    pose: Pose = field(default_factory=Pose)
    colliders: list[WorldCollider] = field(default_factory=list)
    src: SourceLoc | None = None


@dataclass(slots=True)
class Include:
    """An ``<include>`` of the world: a model URI, where it resolved to (None: not found), its pose."""

    uri: str
    name: str | None = None
    pose: Pose | None = None
    path: str | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class WorldPhysics:
    """What the world asks of the engine. ``None``: the world does not say (each engine's default)."""

    step: float | None = None
    iterations: int | None = None
    gravity: Vec3 | None = None
    engine: str | None = None  # the SDF physics type (ode, dart, bullet)
    src: SourceLoc | None = None


@dataclass(slots=True)
class CordField:
    """A field of compliant cords (Quad-SDK's "underbrush": vines): ``count`` chains of ``segments``
    capsules on spherical joints, each hanging from a kinematic anchor placed at random (``seed``)
    over ``area`` (x0, y0, x1, y1) at a height in ``anchor_height`` (low, high). ``stiffness`` and
    ``damping`` act at every joint (N·m/rad, N·m·s/rad); ``mass`` is one cord's (kg)."""

    name: str
    count: int
    length: float
    segments: int
    radius: float
    stiffness: float
    damping: float
    anchor_height: tuple[float, float]
    area: tuple[float, float, float, float]
    seed: int = 0
    mass: float | None = None  # None: the capsules' volume at 1000 kg/m³
    src: SourceLoc | None = None

    @property
    def cord_mass(self) -> float:
        if self.mass is not None:
            return self.mass
        import math

        return 1000.0 * math.pi * self.radius**2 * self.length


@dataclass(slots=True)
class World:
    """A world: its static bodies, includes and physics. ``file`` is the world file (or terrain)."""

    name: str
    file: str
    physics: WorldPhysics = field(default_factory=WorldPhysics)
    bodies: list[StaticBody] = field(default_factory=list)
    includes: list[Include] = field(default_factory=list)
    cords: list[CordField] = field(default_factory=list)
    src: SourceLoc | None = None
