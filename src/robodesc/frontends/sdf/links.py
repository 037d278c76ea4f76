"""SDF links into IR links: the inertial (SDF's defaults where it says nothing: 1 kg and a unit
tensor, as libsdformat and Drake apply them), visuals with their material, collisions with their
``<surface>`` as the contact IR. Every pose is re-expressed in the IR link's frame (the frame of
the joint leading to the link, see :mod:`.build`)."""

from __future__ import annotations

from typing import Any

import numpy as np
from lxml import etree

from robodesc.frontends.gazebo_contact import surface_contact
from robodesc.frontends.options import LoadOptions
from robodesc.frontends.sdf.frames import Frames, Node
from robodesc.frontends.sdf.shapes import read_shape
from robodesc.frontends.sdf.source import STAGE
from robodesc.frontends.sdf.values import loc, number, numbers, tag
from robodesc.ir.diagnostics import Findings, ParseError
from robodesc.ir.geometry import Inertia, Inertial, Material, Pose
from robodesc.ir.model import Collision, Link, Visual
from robodesc.ir.transforms import Mat, matrix_pose

_INERTIA = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")


def read_link(frames: Frames, node: Node, ir_frame: Mat, options: LoadOptions, findings: Findings) -> Link:
    """``ir_frame``: the pose, in the model's frame, of the frame the IR link is expressed in."""
    el, scope = node.element, node.scope
    link = Link(name=node.name, src=loc(node.file, el))
    if node.name != (el.get("name") or ""):
        link.display_name = el.get("name")
    to_ir = np.linalg.inv(ir_frame)
    link_pose = frames.in_model(node.name)

    def local(pose: etree._Element | None) -> Pose:
        return _clean(matrix_pose(to_ir @ frames.relative_to(pose, scope, node.file, node.name)))

    link.inertial = _inertial(node, el.find("inertial"), to_ir @ link_pose, findings)
    for visual in el.iterfind("visual"):
        name = visual.get("name")
        label = f"link {node.name!r} visual {name!r}"
        shape = read_shape(scope, visual.find("geometry"), label, frames.source.roots, options, findings)
        if shape is None:
            continue
        link.visuals.append(
            Visual(
                shape,
                origin=local(visual.find("pose")),
                name=name,
                material=_material(node, visual, name or "visual"),
                src=loc(node.file, visual),
            )
        )
    for collision in el.iterfind("collision"):
        name = collision.get("name")
        label = f"link {node.name!r} collision {name!r}"
        shape = read_shape(scope, collision.find("geometry"), label, frames.source.roots, options, findings)
        if shape is None:
            continue
        surface = collision.find("surface")
        contact = None
        if surface is not None:
            contact = surface_contact(surface, label, loc(node.file, surface), findings)
        link.collisions.append(
            Collision(
                shape, origin=local(collision.find("pose")), name=name, src=loc(node.file, collision), contact=contact
            )
        )
    self_collide = el.findtext("self_collide")
    if self_collide is not None and self_collide.strip().lower() in ("1", "true", "0", "false"):
        link.self_collide = self_collide.strip().lower() in ("1", "true")
    return link


def _inertial(node: Node, el: etree._Element | None, link_in_ir: Mat, findings: Findings) -> Inertial:
    file = node.file
    if el is None:
        findings.info(
            "sdf-default-inertial",
            "has no <inertial>: SDF's default, 1 kg with a unit inertia tensor, as Gazebo and Drake read it",
            element=f"link {node.name!r}",
            loc=loc(file, node.element),
            stage=STAGE,
        )
        return Inertial(1.0, _clean(matrix_pose(link_in_ir)), Inertia(1.0, 1.0, 1.0))
    pose = el.find("pose")
    if pose is not None and pose.get("relative_to"):
        raise ParseError(
            "an <inertial>'s pose is relative to its link; relative_to is not allowed", loc=loc(file, pose)
        )
    from robodesc.frontends.sdf.values import pose_value
    from robodesc.ir.transforms import pose_matrix

    frame = link_in_ir @ pose_matrix(pose_value(file, pose))
    mass_el = el.find("mass")
    mass = number(file, mass_el) if mass_el is not None else 1.0
    if mass < 0:
        raise ParseError(f"<mass> must not be negative, got {mass:g}", loc=loc(file, mass_el))  # type: ignore[arg-type]
    values = {"ixx": 1.0, "iyy": 1.0, "izz": 1.0, "ixy": 0.0, "ixz": 0.0, "iyz": 0.0}
    tensor = el.find("inertia")
    for key in _INERTIA:
        found = tensor.find(key) if tensor is not None else None
        if found is not None:
            values[key] = number(file, found)
    return Inertial(
        mass,
        _clean(matrix_pose(frame)),
        Inertia(**values, src=loc(file, tensor) if tensor is not None else None),
        src=loc(file, el),
    )


def _material(node: Node, visual: etree._Element, name: str) -> Material | None:
    el = visual.find("material")
    if el is None:
        return None
    file = node.file
    colour: Any = None
    for key in ("diffuse", "ambient"):
        found = el.find(key)
        if found is not None:
            values = numbers(file, found)
            if len(values) not in (3, 4):
                raise ParseError(f"<{key}> needs 3 or 4 numbers (r g b [a])", loc=loc(file, found))
            colour = (*values[:3], values[3] if len(values) == 4 else 1.0)
            break
    script = el.find("script/name")
    if colour is None and script is None:
        return None
    material = Material(name=f"{node.name}::{name}", color=colour, src=loc(file, el))
    if script is not None:
        material.extensions.append(_keep(el, file))
    return material


def _keep(el: etree._Element, file: str) -> Any:
    from robodesc.ir.geometry import Extension

    return Extension(tag=tag(el), xml=etree.tostring(el, encoding="unicode"), src=loc(file, el))


def _clean(pose: Pose) -> Pose:
    """Rounding noise from composing frames (1e-17) kept out of the IR: a pose that is the identity to
    1e-12 is the identity."""
    xyz = tuple(0.0 if abs(v) < 1e-12 else v for v in pose.xyz)
    rpy = tuple(0.0 if abs(v) < 1e-12 else v for v in pose.rpy)
    return Pose(xyz, rpy)  # type: ignore[arg-type]
