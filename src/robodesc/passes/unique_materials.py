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


def unique_materials(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    defs: dict[str, Material] = {}
    by_content: dict[Key, str] = {}
    kept: list[Material] = []
    for mat in robot.materials:
        if mat.is_reference():
            kept.append(mat)
            defs.setdefault(mat.name, mat)
            continue
        if mat.name in defs:
            if content_key(defs[mat.name]) == content_key(mat):
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
        kept.append(mat)
        defs[mat.name] = mat
        by_content.setdefault(content_key(mat), mat.name)
    created: list[Material] = []
    named = 0
    unnamed_visuals = 0
    for link in robot.links:
        for visual in link.visuals:
            inline = visual.material
            if inline is None:
                continue
            mat = inline
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
            key = content_key(mat)
            unnamed_visuals += 0 if mat.name else 1
            if mat.name:
                name = mat.name
                if name in defs and content_key(defs[name]) != key:
                    name = f"{mat.name}_{content_hash(mat)}"
                    ctx.warn(
                        "material-renamed",
                        f"material {mat.name!r} is defined with another colour: this one is named {name!r}",
                        element=f"link {link.name!r}",
                        loc=mat.src,
                    )
            elif key in by_content:
                name = by_content[key]
            else:
                base = f"material_{link.name}_{content_hash(mat)}"
                name, i = base, 0
                while name in defs:
                    i += 1
                    name = f"{base}_{i}"
            if name not in defs:
                definition = _definition(mat, name)
                defs[name] = definition
                created.append(definition)
                by_content.setdefault(key, name)
                if not mat.name:
                    named += 1
                    ctx.info(
                        "material-named",
                        f"unnamed material {_describe(mat)} named {name!r}",
                        element=f"link {link.name!r}",
                        loc=mat.src,
                    )
            visual.material = Material(name=name, display_name=mat.name or None, src=mat.src)
    robot.materials = kept + created
    if unnamed_visuals:
        ctx.warn(
            "unnamed-materials",
            f"{unnamed_visuals} unnamed inline material(s) -> {named} uniquely named robot-level definition(s)",
            element=f"robot {robot.name!r}",
        )
    return robot


def _describe(mat: Material) -> str:
    parts = []
    if mat.color is not None:
        parts.append("rgba " + " ".join(f"{c:g}" for c in mat.color))
    if mat.texture:
        parts.append(f"texture {mat.texture!r}")
    return "(" + ", ".join(parts) + ")"
