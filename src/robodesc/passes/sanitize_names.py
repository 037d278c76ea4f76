"""Make every name a valid USD/Isaac identifier, unique in its namespace.

Scheme (deterministic, documented in docs/passes.md):

1. A name matching ``[A-Za-z][A-Za-z0-9_]*`` is valid and never changes.
2. Otherwise: Unicode NFKD, combining marks dropped, so ``ä`` → ``a``; every character still outside
   ``[A-Za-z0-9_]`` becomes ``_`` (``关节`` → ``__``, ``joint-1`` → ``joint_1``).
3. A result that is empty or starts with a digit or ``_`` gets the prefix ``a``
   (``100_shoulder_mesh`` → ``a100_shoulder_mesh``, ``_base`` → ``a_base``; Isaac's own prefix).
4. If the result is taken in its namespace (by a valid name, or an earlier sanitized one), the first
   free of ``<name>_1``, ``<name>_2`` ... is used, in input order.

Namespaces: links (fixed frames share it: a frame may not shadow a link), joints, materials, fixed
frames, sensors, loop joints. The robot name is sanitized too. ``display_name`` keeps the original.

>>> sanitize("Schulter-Gelenk"), sanitize("Gelenk_ä"), sanitize("100_shoulder_mesh")
('Schulter_Gelenk', 'Gelenk_a', 'a100_shoulder_mesh')
"""

from __future__ import annotations

import re
import unicodedata
from collections.abc import Iterable

from robodesc.ir.diagnostics import SourceLoc
from robodesc.ir.model import Robot
from robodesc.passes.context import PassContext
from robodesc.passes.references import rename_joints, rename_links, rename_materials, rename_simple

NAME = "sanitize_names"
VALID = re.compile(r"[A-Za-z][A-Za-z0-9_]*")
_BAD_CHAR = re.compile(r"[^A-Za-z0-9_]")
PREFIX = "a"


def is_valid(name: str) -> bool:
    return VALID.fullmatch(name) is not None


def sanitize(name: str) -> str:
    """The valid identifier for ``name`` (without the uniqueness suffix)."""
    if is_valid(name):
        return name
    decomposed = unicodedata.normalize("NFKD", name)
    ascii_only = "".join(c for c in decomposed if not unicodedata.combining(c))
    out = _BAD_CHAR.sub("_", ascii_only)
    if not out or not out[0].isalpha():
        out = PREFIX + out
    return out


def unique_names(names: Iterable[str], reserved: Iterable[str] = ()) -> dict[str, str]:
    """``{old: new}`` for the names that must change; valid names (and ``reserved``) keep theirs."""
    names = list(names)
    taken = set(reserved) | {n for n in names if is_valid(n)}
    out: dict[str, str] = {}
    for name in names:
        if is_valid(name) or name in out:
            continue
        base = sanitize(name)
        candidate, i = base, 0
        while candidate in taken:
            i += 1
            candidate = f"{base}_{i}"
        taken.add(candidate)
        out[name] = candidate
    return out


def sanitize_names(robot: Robot, ctx: PassContext) -> Robot:
    """Rename every invalid name and every reference to it; one finding per renamed element."""
    ctx.stage = NAME
    if not is_valid(robot.name):
        new = sanitize(robot.name)
        ctx.info("renamed", f"robot name {robot.name!r} -> {new!r}", element=f"robot {robot.name!r}", loc=robot.src)
        robot.display_name = robot.display_name or robot.name
        robot.name = new

    # Links and fixed frames share one namespace (a frame may not shadow a link).
    links = unique_names(
        (link.name for link in robot.links), reserved=(f.name for f in robot.fixed_frames if is_valid(f.name))
    )
    _report(ctx, "link", links, {link.name: link.src for link in robot.links})
    rename_links(robot, links)

    joints = unique_names(joint.name for joint in robot.joints)
    _report(ctx, "joint", joints, {j.name: j.src for j in robot.joints})
    rename_joints(robot, joints)

    # Material names in robot.materials plus named inline materials; empty names are the business
    # of unique_materials.
    material_names = [m.name for m in robot.materials]
    for link in robot.links:
        material_names += [v.material.name for v in link.visuals if v.material is not None and v.material.name]
    materials = unique_names(dict.fromkeys(n for n in material_names if n))
    _report(ctx, "material", materials, {m.name: m.src for m in robot.materials})
    rename_materials(robot, materials)
    for link in robot.links:
        for visual in link.visuals:
            m = visual.material
            if m is not None and not m.is_reference() and m.name in materials:
                m.display_name = m.display_name or m.name
                m.name = materials[m.name]

    frames = unique_names((f.name for f in robot.fixed_frames), reserved=(link.name for link in robot.links))
    _report(ctx, "fixed_frame", frames, {f.name: f.src for f in robot.fixed_frames})
    rename_simple(robot, "fixed_frame", frames)
    sensors = unique_names(s.name for s in robot.sensors)
    _report(ctx, "sensor", sensors, {s.name: s.src for s in robot.sensors})
    rename_simple(robot, "sensor", sensors)
    loops = unique_names(lj.name for lj in robot.loop_joints)
    _report(ctx, "loop_joint", loops, {lj.name: lj.src for lj in robot.loop_joints})
    rename_simple(robot, "loop_joint", loops)
    return robot


def _report(ctx: PassContext, kind: str, mapping: dict[str, str], locs: dict[str, SourceLoc | None]) -> None:
    for old, new in mapping.items():
        ctx.info(
            "renamed", f"{old!r} -> {new!r} (not a valid USD identifier)", element=f"{kind} {old!r}", loc=locs.get(old)
        )
