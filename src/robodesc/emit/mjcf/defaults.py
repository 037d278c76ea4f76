"""``<default>`` classes: visual and collision geoms, and the joint and actuator properties most
elements share (each element then writes only where it differs)."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections import Counter

from robodesc.emit.mjcf.context import MjcfContext

# Properties pulled into the defaults, with MuJoCo's own default value (what an element that does
# not write the attribute would otherwise get).
_JOINT: dict[str, str | None] = {"damping": "0", "frictionloss": "0", "armature": "0"}
_ACTUATOR: dict[str, str | None] = {"kp": None, "kv": None, "forcerange": None}
FOOT_FRICTION = "0.8 0.02 0.01"  # slide, torsion (m), roll (m): menagerie's legged robots' feet


def defaults(ctx: MjcfContext, worldbody: ET.Element, actuator: ET.Element | None) -> ET.Element:
    # The main (unnamed) default: it applies inside robot.xml and, through <include>, to nothing of
    # the scene but its own elements of these kinds (the scene has no joints or actuators).
    root = ET.Element("default")
    top = root
    joint_defaults = _pull(list(worldbody.iter("joint")), _JOINT)
    if joint_defaults:
        ET.SubElement(top, "joint", joint_defaults)
    kinds = [k for k in ("position", "velocity", "motor") if actuator is not None and actuator.find(k) is not None]
    # A default class holds one actuator default, which <position>, <velocity> and <motor> all write
    # (each sets the gain and bias): with two kinds present (a source's own motors and servos) the
    # second would overwrite the first, so nothing is pulled.
    if actuator is not None and len(kinds) == 1:
        pulled = _pull(list(actuator.iter(kinds[0])), _ACTUATOR)
        if pulled:
            ET.SubElement(top, kinds[0], pulled)
    visual = ET.SubElement(top, "default", {"class": "visual"})
    ET.SubElement(visual, "geom", group="2", contype="0", conaffinity="0")
    collision = ET.SubElement(top, "default", {"class": "collision"})
    # Self-collision off: the robot's colliders touch the world (contype 1 there) but not each other.
    if ctx.options.self_collision:
        ET.SubElement(collision, "geom", group="3")
    else:
        ET.SubElement(collision, "geom", group="3", contype="0", conaffinity="1")
    if ctx.options.feet:  # an unused class is harmless
        # mujoco_menagerie's feet (Go1, A1, ANYmal C): torsional and rolling friction (condim 6), the
        # foot's own friction and solver parameters against the floor's (priority 1), and its
        # friction where the source gives none (a geom's own friction still wins).
        foot = ET.SubElement(collision, "default", {"class": "foot"})
        ET.SubElement(foot, "geom", condim="6", priority="1", friction=FOOT_FRICTION)
    return root


def _pull(elements: list[ET.Element], props: dict[str, str | None]) -> dict[str, str]:
    """For each property, the most common value goes to the default when at least two elements
    share it; elements that carry it drop the attribute, elements without it write MuJoCo's default."""
    out: dict[str, str] = {}
    for prop, mujoco_default in props.items():
        values = [el.get(prop, mujoco_default) for el in elements]
        counts = Counter(v for v in values if v is not None)
        if not counts:
            continue
        value, count = counts.most_common(1)[0]
        if count < 2 or value == mujoco_default:
            continue
        if mujoco_default is None and any(v is None for v in values):
            continue  # an element that must not get this property could not say "none"
        out[prop] = value
        for el in elements:
            current = el.get(prop, mujoco_default)
            if current == value:
                el.attrib.pop(prop, None)
            elif current is not None:
                el.set(prop, current)
    return out
