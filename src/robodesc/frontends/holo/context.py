"""The state of one lowering (:class:`Lowering`, passed explicitly to every step) and its records:
the composition's objects flattened (:class:`Obj`), a joint as one notation spells it
(:class:`JointSpec`), and what the lowering returns (:class:`HoloResult`, :class:`HoloProp`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from robodesc.frontends.holo.parser import Block, Document, Trait, Value
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings, SourceLoc
from robodesc.ir.geometry import RGBA, Geometry, Pose, Vec3
from robodesc.ir.model import Robot
from robodesc.ir.transforms import Mat

STAGE = "compose:holo"


@dataclass(slots=True)
class HoloProp:
    """A body of the composition that is not part of the robot (a ``@grabbable`` prop, a static fixture).

    ``pose`` is in the composition's (Z-up) world frame; an SDF world writer can place it as a model.
    """

    name: str
    kind: str  # "grabbable" or "static"
    geometry: Geometry | None
    pose: Pose
    mass: float | None
    color: RGBA | None
    src: SourceLoc | None = None


@dataclass(slots=True)
class HoloResult:
    robot: Robot
    props: list[HoloProp]
    findings: Findings
    gravity: Vec3 | None = None


@dataclass(slots=True)
class Obj:
    """An object of the composition, its template applied, at its world pose."""

    name: str
    block: Block
    props: dict[str, Value]
    traits: list[Trait]
    behaviors: list[Block]
    world: Mat
    enclosing: str | None
    index: int

    @property
    def label(self) -> str:
        return f"object {self.name!r}"

    def trait(self, name: str) -> Trait | None:
        for t in self.traits:
            if t.name == name:
                return t
        return None

    def traits_named(self, name: str) -> list[Trait]:
        return [t for t in self.traits if t.name == name]


@dataclass(slots=True)
class JointSpec:
    """A joint as one of HoloScript's notations states it, before it is lowered."""

    type: str
    type_loc: SourceLoc
    parent: str | None
    parent_loc: SourceLoc | None
    params: dict[str, Value]
    loc: SourceLoc
    notation: str
    name: str | None = None
    in_degrees: set[str] = field(default_factory=set)
    # Angles (limits, mimic offset, soft limits) in radians rather than degrees: the notations of
    # HoloScript's robotics plugin and of its behavior blocks (see joints.py).
    radians: bool = False


def _identity() -> Mat:
    return np.eye(4)


@dataclass(slots=True)
class Lowering:
    """What one lowering knows so far; each step reads and extends it."""

    doc: Document
    file: str
    options: LoadOptions
    findings: Findings
    templates: dict[str, Block] = field(default_factory=dict)
    objects: dict[str, Obj] = field(default_factory=dict)
    # Original name -> the unique name of its first object, for names used more than once.
    renamed: dict[str, str] = field(default_factory=dict)
    joint_decls: list[tuple[Block, str | None]] = field(default_factory=list)
    # Joint blocks that a `robot NAME { joints { ... } }` block declares (angles in radians).
    robot_joints: set[int] = field(default_factory=set)
    # Objects drawn as a stand-in primitive whose inertia is another shape's: (kind, a, b).
    solids: dict[str, tuple[str, float, float]] = field(default_factory=dict)
    # Empty links standing for bodies the file names but does not declare.
    synthetic: set[str] = field(default_factory=set)
    # The composition's frame in robodesc's Z-up world (a rotation for a Y-up scene).
    up: Mat = field(default_factory=_identity)
    y_up: bool = False
    gravity: Vec3 | None = None
    cylinder_noted: bool = False

    def note(
        self, code: str, message: str, element: str = "", loc: SourceLoc | None = None, *, warn: bool = False
    ) -> None:
        if warn:
            self.findings.warn(code, message, element=element, loc=loc, stage=STAGE)
        else:
            self.findings.info(code, message, element=element, loc=loc, stage=STAGE)
