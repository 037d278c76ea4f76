"""One robot-level material per distinct colour/texture, each under a name of its own.

Layout after this pass: every material with a colour or texture is *defined* in
``robot.materials``; visuals hold *references* (a :class:`Material` with only a name).

Naming:
- an unnamed inline material (go2's ``<material name="">``) reuses the first material with the same
  colour and texture, else becomes ``material_<link>_<hash>`` where ``<link>`` is the owning link and
  ``<hash>`` the first 6 hex digits of ``sha1("rgba=<r> <g> <b> <a>;texture=<uri>")`` (floats in
  Python ``repr``);
- a named material keeps its name; a second, *different* material under a name already taken
  becomes ``<name>_<hash>``; identical definitions are shared;
- named materials are never merged with each other, even when their colours agree (a name is
  information).
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field

from robodesc.ir.geometry import Material
from robodesc.ir.model import Robot
from robodesc.passes.context import PassContext

NAME = "unique_materials"

Key = tuple[tuple[float, ...] | None, str | None]


def content_key(mat: Material) -> Key:
    return (tuple(mat.color) if mat.color is not None else None, mat.texture)


def content_hash(mat: Material) -> str:
    rgba = " ".join(repr(float(c)) for c in mat.color) if mat.color is not None else ""
    text = f"rgba={rgba};texture={mat.texture or ''}"
    return hashlib.sha1(text.encode("utf-8")).hexdigest()[:6]


def _definition(mat: Material, name: str) -> Material:
    return Material(
        name=name,
        color=mat.color,
        texture=mat.texture,
        texture_path=mat.texture_path,
        display_name=mat.display_name or (mat.name if mat.name and mat.name != name else None),
        src=mat.src,
        extensions=list(mat.extensions),
    )


@dataclass(slots=True)
class _Table:
    """The robot-level definitions while the pass runs."""

    defs: dict[str, Material] = field(default_factory=dict)  # name -> definition (or reference)
    by_content: dict[Key, str] = field(default_factory=dict)  # colour/texture -> first name with it
    kept: list[Material] = field(default_factory=list)  # robot.materials after the pass, then ...
    created: list[Material] = field(default_factory=list)  # ... these, made from inline materials
    named: int = 0  # definitions made for unnamed inline materials


def unique_materials(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    table = _robot_level(robot.materials, ctx)
    unnamed_visuals = 0
    for link in robot.links:
        for visual in link.visuals:
            mat = visual.material
            if mat is None:
                continue
            if mat.is_reference():
                if not mat.name:
                    visual.material = None
                    ctx.info(
                        "material-dropped",
                        "empty material reference removed",
                        element=f"link {link.name!r}",
                        loc=mat.src,
                    )
                continue
            unnamed_visuals += 0 if mat.name else 1
            visual.material = _define_inline(mat, link.name, table, ctx)
    robot.materials = table.kept + table.created
    if unnamed_visuals:
        ctx.warn(
            "unnamed-materials",
            f"{unnamed_visuals} unnamed inline material(s) -> {table.named} uniquely named robot-level definition(s)",
            element=f"robot {robot.name!r}",
        )
    return robot


def _robot_level(materials: list[Material], ctx: PassContext) -> _Table:
    """The table of the robot-level materials: an identical definition given twice is kept once, a
    different one under a name already taken is renamed ``<name>_<hash>``."""
    table = _Table()
    for mat in materials:
        if mat.is_reference():
            table.kept.append(mat)
            table.defs.setdefault(mat.name, mat)
            continue
        if mat.name in table.defs:
            if content_key(table.defs[mat.name]) == content_key(mat):
                ctx.info(
                    "material-duplicate",
                    "identical definition given twice; one kept",
                    element=f"material {mat.name!r}",
                    loc=mat.src,
                )
                continue
            new = f"{mat.name}_{content_hash(mat)}"
            ctx.warn(
                "material-renamed",
                f"a different material already has this name: renamed {new!r}",
                element=f"material {mat.name!r}",
                loc=mat.src,
            )
            mat = _definition(mat, new)
        table.kept.append(mat)
        table.defs[mat.name] = mat
        table.by_content.setdefault(content_key(mat), mat.name)
    return table


def _define_inline(mat: Material, link: str, table: _Table, ctx: PassContext) -> Material:
    """The reference that replaces the inline material ``mat`` of a visual of ``link``; its
    definition is added to ``table`` unless one of that name is there."""
    key = content_key(mat)
    name = _inline_name(mat, key, link, table, ctx)
    if name not in table.defs:
        definition = _definition(mat, name)
        table.defs[name] = definition
        table.created.append(definition)
        table.by_content.setdefault(key, name)
        if not mat.name:
            table.named += 1
            ctx.info(
                "material-named",
                f"unnamed material {_describe(mat)} named {name!r}",
                element=f"link {link!r}",
                loc=mat.src,
            )
    return Material(name=name, display_name=mat.name or None, src=mat.src)


def _inline_name(mat: Material, key: Key, link: str, table: _Table, ctx: PassContext) -> str:
    """A named material keeps its name unless another colour has it (then ``<name>_<hash>``); an
    unnamed one takes the first name with its colour and texture, else ``material_<link>_<hash>``."""
    if mat.name:
        name = mat.name
        if name in table.defs and content_key(table.defs[name]) != key:
            name = f"{mat.name}_{content_hash(mat)}"
            ctx.warn(
                "material-renamed",
                f"material {mat.name!r} is defined with another colour: this one is named {name!r}",
                element=f"link {link!r}",
                loc=mat.src,
            )
        return name
    if key in table.by_content:
        return table.by_content[key]
    base = f"material_{link}_{content_hash(mat)}"
    name, i = base, 0
    while name in table.defs:
        i += 1
        name = f"{base}_{i}"
    return name


def _describe(mat: Material) -> str:
    parts = []
    if mat.color is not None:
        parts.append("rgba " + " ".join(f"{c:g}" for c in mat.color))
    if mat.texture:
        parts.append(f"texture {mat.texture!r}")
    return "(" + ", ".join(parts) + ")"
