"""The IR as the plain data the viewer page draws: links, joints, shapes, inertia, findings, repairs.

Everything is JSON-ready (numbers, strings, lists). Meshes are referenced by index into a list of
(path, scale) pairs; :mod:`robodesc.view.page` reads each once and embeds it as GLB. Poses stay
URDF's (xyz, fixed-axis rpy): the page builds the same frames the emitters write.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any

from robodesc.ir.diagnostics import Finding
from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Inertial, Material, Mesh, Pose, Sphere
from robodesc.ir.model import Joint, JointType, Robot
from robodesc.ir.principal import symmetric_eigen, tensor_rows
from robodesc.ir.rigid import rotation_quat

Json = dict[str, Any]

# Colours of what the input did not colour, and of colliders (drawn see-through over the visuals).
DEFAULT_RGBA = (0.72, 0.74, 0.78, 1.0)
COLLIDER_RGBA = (0.95, 0.55, 0.15, 0.45)

# A slider for a joint without limits (continuous, or limits not given) spans this much.
FREE_RANGE = {"angular": math.pi, "linear": 0.5}

_ELEMENT = re.compile(r"^(\w+) '(.*?)'")
_IN_MESSAGE = re.compile(r"\b(link|joint) '([^']*)'")


@dataclass(slots=True)
class MeshTable:
    """Mesh files the scene refers to, each (path, scale) once, in first-use order."""

    keys: list[tuple[str, tuple[float, float, float] | None]] = field(default_factory=list)
    uris: list[str] = field(default_factory=list)  # each key's file as the source names it
    _index: dict[tuple[str, tuple[float, float, float] | None], int] = field(default_factory=dict)

    def add(self, path: str, scale: tuple[float, float, float] | None, uri: str = "") -> int:
        key = (path, scale)
        if key not in self._index:
            self._index[key] = len(self.keys)
            self.keys.append(key)
            self.uris.append(uri or path)
        return self._index[key]


def _pose(pose: Pose | None) -> Json:
    if pose is None:
        return {"xyz": [0.0, 0.0, 0.0], "rpy": [0.0, 0.0, 0.0]}
    return {"xyz": list(pose.xyz), "rpy": list(pose.rpy)}


def _color(material: Material | None, named: dict[str, Material]) -> list[float]:
    if material is not None and material.color is None:
        material = named.get(material.name, material)
    if material is None or material.color is None:
        return list(DEFAULT_RGBA)
    return list(material.color)


def shape(geometry: Geometry, meshes: MeshTable) -> Json:
    """One shape: a primitive's sizes, or a mesh's index in ``meshes`` (``missing`` when the file
    did not resolve; the page draws a marker there and the findings say why)."""
    if isinstance(geometry, Box):
        return {"kind": "box", "size": list(geometry.size)}
    if isinstance(geometry, Cylinder):
        return {"kind": "cylinder", "radius": geometry.radius, "length": geometry.length}
    if isinstance(geometry, Sphere):
        return {"kind": "sphere", "radius": geometry.radius}
    if isinstance(geometry, Capsule):
        return {"kind": "capsule", "radius": geometry.radius, "length": geometry.length}
    assert isinstance(geometry, Mesh)
    if geometry.path is None:
        return {"kind": "missing", "uri": geometry.uri}
    return {"kind": "mesh", "mesh": meshes.add(geometry.path, geometry.scale, geometry.uri), "uri": geometry.uri}


def inertia_box(inertial: Inertial | None) -> Json | None:
    """Mass, centre of mass and the equivalent box: the uniform box of the same mass whose
    principal moments are the link's, turned to the principal axes. ``box`` is None when the
    moments cannot belong to a body (the triangle inequality fails): that is a finding already."""
    if inertial is None or inertial.mass is None:
        return None
    out: Json = {"mass": inertial.mass, **_pose(inertial.origin), "box": None, "quat": [1.0, 0.0, 0.0, 0.0]}
    if inertial.inertia is None or not inertial.mass > 0:
        return out
    try:
        moments, axes = symmetric_eigen(tensor_rows(inertial.inertia))
    except (ValueError, ArithmeticError):
        return out
    i1, i2, i3 = moments
    m = inertial.mass
    # A box a x b x c has I1 = m/12 (b^2 + c^2) ...; solved for the sides.
    squares = (6.0 / m * (i2 + i3 - i1), 6.0 / m * (i1 + i3 - i2), 6.0 / m * (i1 + i2 - i3))
    if not all(math.isfinite(s) and s >= 0.0 for s in squares):
        return out
    out["box"] = [math.sqrt(s) for s in squares]
    out["quat"] = list(rotation_quat(axes))  # w, x, y, z: principal axes in the inertial frame
    return out


def joint_range(joint: Joint) -> tuple[float, float] | None:
    """The slider's range: the joint's limits, or a free range where it has none. None for a joint
    a single slider cannot drive (fixed, floating, planar, spherical)."""
    if joint.type.dof != 1:
        return None
    kind = "angular" if joint.type.is_angular else "linear"
    lower, upper = -FREE_RANGE[kind], FREE_RANGE[kind]
    limit = joint.limit
    if joint.type is not JointType.CONTINUOUS and limit is not None:
        if limit.lower is not None and math.isfinite(limit.lower):
            lower = limit.lower
        if limit.upper is not None and math.isfinite(limit.upper):
            upper = limit.upper
    if lower > upper:
        lower, upper = upper, lower
    return lower, upper


def home(joint: Joint) -> float:
    """The home pose: every joint at zero, or at the limit nearest zero when zero is outside."""
    span = joint_range(joint)
    if span is None:
        return 0.0
    return min(max(0.0, span[0]), span[1])


def finding_link(finding: Finding, robot: Robot, renamed: dict[str, str] | None = None) -> str | None:
    """The link a finding is about: the link it names, a joint's child link, a merged link's new
    body; None for findings about the whole robot (or elements without a link)."""
    match = _ELEMENT.match(finding.element)
    if match is None:
        # Frontend findings often name the element in the message only ("... in link 'base'").
        match = _IN_MESSAGE.search(finding.message)
    if match is None:
        return None
    kind, name = match.group(1), match.group(2)
    links = robot.link_map()
    name = (renamed or {}).get(name, name)
    if kind == "link":
        if name in links:
            return name
        # A link merged away: the message names where it went ("merged into 'base'").
        into = re.search(r"merged into '([^']*)'", finding.message)
        if into and into.group(1) in links:
            return into.group(1)
        return None
    if kind == "joint":
        for joint in robot.joints:
            if joint.name == name:
                return joint.child
    if kind == "sensor":
        for sensor in robot.sensors:
            if sensor.name == name:
                return sensor.parent
    if kind == "fixed_frame":
        for frame in robot.fixed_frames:
            if frame.name == name:
                return frame.parent
    return None


def _joint(joint: Joint) -> Json:
    span = joint_range(joint)
    out: Json = {
        "name": joint.name,
        "type": joint.type.value,
        "parent": joint.parent,
        "child": joint.child,
        **_pose(joint.origin),
        "axis": list(joint.effective_axis),
        "range": list(span) if span is not None else None,
        "home": home(joint),
        "mimic": None,
    }
    if joint.mimic is not None:
        out["mimic"] = {
            "joint": joint.mimic.joint,
            "multiplier": joint.mimic.multiplier if joint.mimic.multiplier is not None else 1.0,
            "offset": joint.mimic.offset if joint.mimic.offset is not None else 0.0,
        }
    return out


def renames(findings: list[Finding]) -> dict[str, str]:
    """Old name -> new name, from the passes' ``renamed`` findings (sanitized or ruled names)."""
    out: dict[str, str] = {}
    for f in findings:
        match = re.match(r"^'(.*)' -> '(.*)'$", f.message) if f.code == "renamed" else None
        if match:
            out[match.group(1)] = match.group(2)
    return out


def build_scene(robot: Robot, findings: list[Finding], meshes: MeshTable) -> Json:
    """The page's data for ``robot``: links with their shapes and inertia, joints in tree order,
    and the findings, each with the link it is about."""
    named = {m.name: m for m in robot.materials}
    links = []
    for link in robot.links:
        links.append(
            {
                "name": link.name,
                "visuals": [
                    {**shape(v.geometry, meshes), **_pose(v.origin), "rgba": _color(v.material, named)}
                    for v in link.visuals
                ],
                "collisions": [
                    {**shape(c.geometry, meshes), **_pose(c.origin), "rgba": list(COLLIDER_RGBA)}
                    for c in link.collisions
                ],
                "inertial": inertia_box(link.inertial),
            }
        )
    renamed = renames(findings)
    items = []
    for f in findings:
        items.append(
            {
                "severity": f.severity.value,
                "code": f.code,
                "element": f.element,
                "message": f.message,
                "where": str(f.loc) if f.loc is not None else "",
                "link": finding_link(f, robot, renamed),
            }
        )
    return {
        "robot": robot.name,
        "roots": [link.name for link in robot.root_links()],
        "links": links,
        "joints": [_joint(j) for j in robot.topological_joints()],
        "findings": items,
    }
