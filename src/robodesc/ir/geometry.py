"""Poses, shapes, inertials and materials: the leaves of the IR."""

from __future__ import annotations

from dataclasses import dataclass, field

from robodesc.ir.diagnostics import SourceLoc

Vec3 = tuple[float, float, float]
RGBA = tuple[float, float, float, float]

ZERO3: Vec3 = (0.0, 0.0, 0.0)


@dataclass(slots=True)
class Pose:
    """A URDF ``<origin>``: translation ``xyz`` (m) then fixed-axis roll-pitch-yaw ``rpy`` (rad)."""

    xyz: Vec3 = ZERO3
    rpy: Vec3 = ZERO3
    src: SourceLoc | None = None

    def is_identity(self) -> bool:
        return self.xyz == ZERO3 and self.rpy == ZERO3


@dataclass(slots=True)
class Box:
    size: Vec3
    src: SourceLoc | None = None


@dataclass(slots=True)
class Cylinder:
    """Axis along local Z, centred on the origin."""

    radius: float
    length: float
    src: SourceLoc | None = None


@dataclass(slots=True)
class Sphere:
    radius: float
    src: SourceLoc | None = None


@dataclass(slots=True)
class Capsule:
    """Axis along local Z; ``length`` is the cylinder part, without the two caps (Isaac's convention)."""

    radius: float
    length: float
    src: SourceLoc | None = None


@dataclass(slots=True)
class Mesh:
    """A mesh file.

    ``uri`` is what the input wrote. ``path`` is the absolute file it resolves to (``None`` when it
    could not be resolved). ``package`` is ``(name, path inside the package)`` when the reference
    went through a ROS package, so that emitters can write ``package://`` back.
    """

    uri: str
    scale: Vec3 | None = None
    path: str | None = None
    package: tuple[str, str] | None = None
    src: SourceLoc | None = None


Geometry = Box | Cylinder | Sphere | Capsule | Mesh


@dataclass(slots=True)
class Inertia:
    """The 3x3 symmetric inertia tensor about the centre of mass, in the inertial frame (kg·m²)."""

    ixx: float
    iyy: float
    izz: float
    ixy: float = 0.0
    ixz: float = 0.0
    iyz: float = 0.0
    src: SourceLoc | None = None

    def as_tuple(self) -> tuple[float, float, float, float, float, float]:
        return (self.ixx, self.iyy, self.izz, self.ixy, self.ixz, self.iyz)


@dataclass(slots=True)
class Inertial:
    """``mass`` and ``inertia`` stay ``None`` when the input did not give them."""

    mass: float | None = None
    origin: Pose | None = None
    inertia: Inertia | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class Material:
    """A named colour and/or texture.

    In a visual, a material with only a ``name`` refers to a robot-level definition.
    ``texture`` keeps the URI as written; ``texture_path`` is the resolved file.
    """

    name: str
    color: RGBA | None = None
    texture: str | None = None
    texture_path: str | None = None
    display_name: str | None = None
    src: SourceLoc | None = None
    extensions: list[Extension] = field(default_factory=list)

    def is_reference(self) -> bool:
        return self.color is None and self.texture is None


@dataclass(slots=True)
class Extension:
    """An element robodesc does not model, kept verbatim.

    ``xml`` is the serialized element. ``anchor`` is ``(kind, name)`` of the modelled element it
    followed in the input (``("link", "body")``), or ``None`` when it came first; emitters put it back
    after that element. ``reference`` is the ``reference=`` attribute of a ``<gazebo>`` block, kept
    apart so renaming a link or joint can follow it.
    """

    tag: str
    xml: str
    anchor: tuple[str, str] | None = None
    reference: str | None = None
    src: SourceLoc | None = None
