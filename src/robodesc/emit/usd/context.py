"""State threaded through the USD emitter's stages: the layer each kind of opinion goes to, prim
paths of links and joints, the mesh cache and the findings.

Opinions are authored into :mod:`robodesc.usdfile` layers, not through usd-core: the CLI must not
pay ``pxr``'s import (see that package's docstring)."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from robodesc.emit.usd.options import UsdOptions
from robodesc.ir.diagnostics import Findings, SourceLoc, UnsupportedError
from robodesc.ir.model import Robot
from robodesc.ir.rigid import Frame
from robodesc.usdfile.spec import Layer, Prim

if TYPE_CHECKING:
    from robodesc.meshes.data import MeshCache

STAGE = "emit:usd"

# Children of the robot prim that robodesc itself creates.
JOINTS_SCOPE = "joints"
LOOPS_SCOPE = "loop_joints"
LOOKS_SCOPE = "Looks"
CONTACT_SCOPE = "PhysicsMaterials"
RESERVED_ROBOT_CHILDREN = (JOINTS_SCOPE, LOOPS_SCOPE, LOOKS_SCOPE, CONTACT_SCOPE)
RESERVED_LINK_CHILDREN = ("visuals", "collisions")

# Layer roles (single-file output sends them all to one layer).
GEOMETRY = "geometry"
MATERIALS = "materials"
PHYSICS = "physics"
ROLES = (GEOMETRY, MATERIALS, PHYSICS)

# Sdf's identifier rule for prim names, in its ASCII form (robodesc's sanitizer produces ASCII).
_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


def is_identifier(name: str) -> bool:
    return _IDENTIFIER.match(name) is not None


@dataclass
class UsdContext:
    robot: Robot
    options: UsdOptions
    findings: Findings
    # Folder of the layer(s) being written, for relative texture paths.
    layer_dir: str
    # Role -> layer; single-file output maps every role to the same layer.
    layers: dict[str, Layer] = field(default_factory=dict)
    _meshes: MeshCache | None = None
    _mesh_roots: list[str] | None = None
    robot_path: str = ""
    link_paths: dict[str, str] = field(default_factory=dict)
    joint_paths: dict[str, str] = field(default_factory=dict)
    # World (robot-frame) pose of every link at q = 0.
    link_poses: dict[str, Frame] = field(default_factory=dict)

    @property
    def meshes(self) -> MeshCache:
        # Imported on first use: mesh reading needs numpy, a robot of primitives does not.
        if self._meshes is None:
            from robodesc.meshes.data import MeshCache

            self._meshes = MeshCache()
        return self._meshes

    @property
    def mesh_roots(self) -> list[str]:
        """The folders mesh files may be read from (``meshes/roots.py``, the rule of --copy-meshes)."""
        if self._mesh_roots is None:
            from robodesc.meshes.roots import allowed_roots

            self._mesh_roots = allowed_roots(self.robot)
        return self._mesh_roots

    def define(self, role: str, path: str, type_name: str = "") -> Prim:
        """``def`` the prim at ``path`` in the role's layer (with this type when one is given)."""
        prim = self.layers[role].prim(path, type_name)
        prim.specifier = "def"
        if type_name:
            prim.type_name = type_name
        return prim

    def over(self, role: str, path: str) -> Prim:
        """The prim's spec in the role's layer: the existing one, else a new ``over``."""
        return self.layers[role].prim(path, specifier="over")

    def warn(self, code: str, message: str, element: str = "", loc: SourceLoc | None = None) -> None:
        self.findings.warn(code, message, element=element, loc=loc, stage=STAGE)


def check_identifier(name: str, element: str, loc: SourceLoc | None) -> str:
    if not is_identifier(name):
        raise UnsupportedError(
            f"{name!r} is not a valid USD prim name (letters, digits and '_', not starting with a digit); "
            "run the sanitize_names pass before emitting USD (the robodesc pipeline does)",
            element=element,
            loc=loc,
        )
    return name


class UsedNames(set[str]):
    """Prim names taken under one parent, and per fallback stem the smallest index that may still be
    free: names are only ever added, so it never goes down, and the n-th unnamed visual costs one
    look-up instead of n (5,000 unnamed visuals of one link took 3.3 s of 7 in naming alone)."""

    def __init__(self) -> None:
        super().__init__()
        self.next_index: dict[str, int] = {}


def unique_name(base: str, used: set[str], fallback: str) -> str:
    """A valid identifier for an optional IR name (visual, collision, material): ``base`` when it is
    one and still free, else ``fallback`` with the smallest free counter."""
    if base and is_identifier(base) and base not in used:
        used.add(base)
        return base
    stem = fallback
    index = used.next_index.get(stem, 0) if isinstance(used, UsedNames) else 0
    while f"{stem}_{index}" in used:
        index += 1
    name = f"{stem}_{index}"
    used.add(name)
    if isinstance(used, UsedNames):
        used.next_index[stem] = index + 1
    return name


def set_display_name(prim: Prim, display_name: str | None) -> None:
    if display_name:
        prim.display_name = display_name


def set_pose(prim: Prim, m: Frame, scale: tuple[float, float, float] | None = None) -> None:
    """translate (double3) + orient (quatd) [+ scale (float3)]; identity parts are skipped.

    The orient is double precision: for a rotation under ~5e-4 rad a quatf's real part rounds to
    exactly 1, and usd-core (GfRotation takes the angle from acos(w)) then evaluates the identity."""
    order = []
    t = m.translation
    if t[0] or t[1] or t[2]:
        prim.attr("xformOp:translate", "double3", (float(t[0]), float(t[1]), float(t[2])))
        order.append("xformOp:translate")
    q = m.quat()
    if q != (1.0, 0.0, 0.0, 0.0):
        prim.attr("xformOp:orient", "quatd", q)
        order.append("xformOp:orient")
    if scale is not None:
        prim.attr("xformOp:scale", "float3", scale)
        order.append("xformOp:scale")
    if order:
        prim.attr("xformOpOrder", "token[]", order, uniform=True)


def set_full_pose(prim: Prim, m: Frame) -> None:
    t = m.translation
    prim.attr("xformOp:translate", "double3", (float(t[0]), float(t[1]), float(t[2])))
    prim.attr("xformOp:orient", "quatd", m.quat())
    prim.attr("xformOpOrder", "token[]", ["xformOp:translate", "xformOp:orient"], uniform=True)
