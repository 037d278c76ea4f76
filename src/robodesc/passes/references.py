"""Renaming a link, joint or material together with every reference to it.

Shared by ``sanitize_names``, ``rename`` and ``unique_materials``: a rename is only correct when
all of these follow, so they live in one place.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from lxml import etree

from robodesc.ir.geometry import Extension
from robodesc.ir.model import Robot


def retarget_extension(ext: Extension, kind: str, mapping: Mapping[str, str], names_of_kind: set[str]) -> None:
    if ext.anchor is not None and ext.anchor[0] == kind and ext.anchor[1] in mapping:
        ext.anchor = (kind, mapping[ext.anchor[1]])
    # A gazebo ``reference`` names a link or a joint; a name that is both is taken as the link
    # (Gazebo's own look-up order).
    if ext.reference is not None and ext.reference in mapping and ext.reference in names_of_kind:
        new = mapping[ext.reference]
        ext.reference = new
        root = etree.fromstring(ext.xml, etree.XMLParser(resolve_entities=False, no_network=True))
        root.set("reference", new)
        ext.xml = etree.tostring(root, encoding="unicode")


def rename_links(robot: Robot, mapping: Mapping[str, str], *, keep_original: bool = True) -> None:
    """Rename links by ``{old: new}``. With ``keep_original`` (sanitization) ``display_name`` keeps the
    first original name; an explicit rename is the name the user wants shown, so it keeps none."""
    if not mapping:
        return
    old_names = {link.name for link in robot.links}
    for link in robot.links:
        if link.name in mapping:
            if keep_original:
                link.display_name = link.display_name or link.name
            link.name = mapping[link.name]
    for joint in robot.joints:
        joint.parent = mapping.get(joint.parent, joint.parent)
        joint.child = mapping.get(joint.child, joint.child)
    for loop in robot.loop_joints:
        loop.link1.link = mapping.get(loop.link1.link, loop.link1.link)
        loop.link2.link = mapping.get(loop.link2.link, loop.link2.link)
    for frame in robot.fixed_frames:
        frame.parent = mapping.get(frame.parent, frame.parent)
    for sensor in robot.sensors:
        sensor.parent = mapping.get(sensor.parent, sensor.parent)
    for ext in robot.extensions:
        retarget_extension(ext, "link", mapping, old_names)


def rename_joints(robot: Robot, mapping: Mapping[str, str], *, keep_original: bool = True) -> None:
    """Rename joints by ``{old: new}`` and every mimic, transmission, ros2_control and sensor reference
    (``keep_original`` as in :func:`rename_links`)."""
    if not mapping:
        return
    link_names = {link.name for link in robot.links}
    old_names = {joint.name for joint in robot.joints} - link_names
    for joint in robot.joints:
        if joint.name in mapping:
            if keep_original:
                joint.display_name = joint.display_name or joint.name
            joint.name = mapping[joint.name]
        if joint.mimic is not None:
            joint.mimic.joint = mapping.get(joint.mimic.joint, joint.mimic.joint)
    for tr in robot.transmissions:
        for tj in tr.joints:
            tj.name = mapping.get(tj.name, tj.name)
    for rc in robot.ros2_controls:
        for cj in rc.joints:
            cj.name = mapping.get(cj.name, cj.name)
    for sensor in robot.sensors:
        if sensor.parent_joint is not None:
            sensor.parent_joint = mapping.get(sensor.parent_joint, sensor.parent_joint)
    for ext in robot.extensions:
        retarget_extension(ext, "joint", mapping, old_names)


def rename_materials(robot: Robot, mapping: Mapping[str, str]) -> None:
    """Rename robot-level materials and the visual references to them."""
    if not mapping:
        return
    for mat in robot.materials:
        if mat.name in mapping:
            mat.display_name = mat.display_name or mat.name
            mat.name = mapping[mat.name]
    for link in robot.links:
        for visual in link.visuals:
            m = visual.material
            if m is not None and m.is_reference() and m.name in mapping:
                m.display_name = m.display_name or m.name
                m.name = mapping[m.name]
    for ext in robot.extensions:
        retarget_extension(ext, "material", mapping, set())


def rename_simple(robot: Robot, kind: str, mapping: Mapping[str, str]) -> None:
    """Loop joints, fixed frames, sensors: nothing refers to them but extension anchors."""
    if not mapping:
        return
    table: dict[str, list[Any]] = {
        "loop_joint": list(robot.loop_joints),
        "fixed_frame": list(robot.fixed_frames),
        "sensor": list(robot.sensors),
    }
    for node in table[kind]:
        if node.name in mapping:
            node.display_name = node.display_name or node.name
            node.name = mapping[node.name]
    for ext in robot.extensions:
        retarget_extension(ext, kind, mapping, set())
