"""The scene walk: what the parser noted, the environment (gravity, up axis), templates, and every
object of the composition flattened into ``ctx.objects`` at its world pose (groups compose their pose
into their children's); joint blocks are collected into ``ctx.joint_decls`` for later."""

from __future__ import annotations

import math
import os
from collections.abc import Iterable

import numpy as np

from robodesc.frontends.holo.context import Lowering, Obj
from robodesc.frontends.holo.parser import Block, Value
from robodesc.frontends.holo.templates import apply_template, trait_or_prop_mass
from robodesc.frontends.holo.values import describe, fail, num, pose_of, suggest, unique, vec3
from robodesc.ir.diagnostics import BrokenReferenceError
from robodesc.ir.transforms import Mat

# Primitive shapes HoloScript declares as blocks (`sphere "Ball" { }`), from its PRIMITIVE_SHAPES.
SHAPE_KINDS = ("cube", "box", "sphere", "cylinder", "cone", "torus", "plane", "capsule", "ring")
OBJECT_KINDS = ("object", "orb", "entity", "instanced_object", "spatial_agent", "link", "end_effector", *SHAPE_KINDS)
# Blocks that only hold objects: their pose (if any) composes into their children's.
GROUP_KINDS = ("spatial_group", "group", "scene", "composition", "robot", "spawn_group", "zone")
JOINT_KINDS = ("joint",)


def read_scene(ctx: Lowering) -> tuple[str, Block]:
    """Walk the document into ``ctx``; the robot's name and the block that holds it."""
    comps = [b for b in ctx.doc.body.children if b.kind == "composition"]
    comp = comps[0] if len(comps) == 1 else ctx.doc.body
    name = (comp.name if len(comps) == 1 else None) or os.path.splitext(os.path.basename(ctx.file))[0]
    _parser_notes(ctx)
    environment(ctx, comp)
    collect_templates(ctx, comp)
    walk(ctx, comp.children if comp is not ctx.doc.body else ctx.doc.body.children, ctx.up, None, ())
    if not ctx.objects and not ctx.joint_decls:
        raise fail(
            "the composition holds no robot: it declares no objects and no joints",
            f"composition {name!r}",
            comp.loc,
        )
    return name, comp


def _parser_notes(ctx: Lowering) -> None:
    """What the parser stepped over or read another way, as findings."""
    doc = ctx.doc
    for key, loc in doc.duplicate_keys:
        ctx.note("duplicate-key", f"key {key!r} is given twice; the last one counts", loc=loc, warn=True)
    for skipped in doc.skipped:
        ctx.note(
            "ignored-block",
            f"'{skipped.kind}' {'block' if skipped.why == 'code' else 'statement'} ignored: "
            "it is not part of a robot description",
            loc=skipped.loc,
        )
    if doc.stray:
        text, loc = doc.stray[0]
        ctx.note(
            "ignored-syntax",
            f"{len(doc.stray)} stray token(s) between declarations stepped over, as HoloScript's parser "
            f"does (the first: {text[:20]!r})",
            loc=loc,
            warn=True,
        )
    for key, loc in doc.equals_props:
        ctx.note("equals-property", f"'{key} = ...' read as '{key}: ...' (HoloScript's reading)", loc=loc)


# ---- environment -------------------------------------------------------------------------------
def environment(ctx: Lowering, comp: Block) -> None:
    """The environment's gravity, and from it which way is up (``ctx.up``, ``ctx.y_up``)."""
    envs = [b for b in comp.children if b.kind == "environment"]
    _read_gravity(ctx, envs)
    gravity = ctx.gravity
    if gravity is None:
        ctx.note(
            "assumed-up-axis",
            "no environment gravity: positions are read with +z up (the robot convention)",
            loc=comp.loc,
        )
        return
    norm = math.sqrt(sum(c * c for c in gravity))
    if norm == 0:
        return
    unit = tuple(c / norm for c in gravity)
    if np.allclose(unit, (0, 0, -1), atol=1e-6):
        return
    if np.allclose(unit, (0, -1, 0), atol=1e-6):
        # A Y-up scene: rotate it +90° about X so that +y becomes +z, as the IR wants.
        ctx.y_up = True
        ctx.up = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=float)
        ctx.note(
            "converted-up-axis",
            "gravity points along -y: the composition is Y-up; it is rotated +90° about x into robodesc's Z-up frame",
            loc=envs[0].loc,
        )
        return
    raise fail(
        f"gravity {list(gravity)} is not along -z or -y; robodesc cannot tell which way is up",
        "environment",
        envs[0].props["gravity"].loc,
    )


def _read_gravity(ctx: Lowering, envs: list[Block]) -> None:
    ignored: list[str] = []
    for env in envs:
        for key, value in env.props.items():
            if key == "gravity" and isinstance(value.data, (list, dict)):
                ctx.gravity = vec3(value, "environment.gravity", "environment")
            elif key == "gravity":
                ctx.note(
                    "ignored-gravity",
                    f"gravity {describe(value)} is no vector: it does not tell which way is up",
                    "environment",
                    value.loc,
                    warn=True,
                )
            else:
                ignored.append(key)
        for child in env.children:
            ignored.append(child.kind)
    if ignored:
        ctx.note(
            "ignored-environment",
            f"environment settings {', '.join(sorted(set(ignored)))} are simulator settings, not part of the robot",
            loc=envs[0].loc,
        )


def collect_templates(ctx: Lowering, block: Block) -> None:
    for child in block.children:
        if child.kind == "template":
            if not child.name:
                raise fail("a template needs a name", "template", child.loc)
            if child.name in ctx.templates:
                first = ctx.templates[child.name]
                raise fail(
                    f"duplicate template name {child.name!r} (first at {first.name_loc})",
                    f"template {child.name!r}",
                    child.name_loc,
                )
            ctx.templates[child.name] = child
        elif child.kind in GROUP_KINDS:
            collect_templates(ctx, child)


# ---- the walk ----------------------------------------------------------------------------------
def walk(ctx: Lowering, blocks: Iterable[Block], frame: Mat, enclosing: str | None, scope: tuple[str, ...]) -> None:
    for block in blocks:
        if block.kind in OBJECT_KINDS and block.kind not in ("composition",):
            if block.kind in SHAPE_KINDS and "geometry" not in block.props:
                block.props["geometry"] = Value(block.kind, block.loc)
            obj = read_object(ctx, block, frame, enclosing, scope)
            inner = [c for c in block.children if c.kind != "behavior"]
            walk(ctx, inner, obj.world, obj.name, (*scope, obj.name))
        elif block.kind in GROUP_KINDS:
            _group(ctx, block, frame, enclosing, scope)
        elif block.kind in JOINT_KINDS:
            ctx.joint_decls.append((block, enclosing))
        elif block.kind == "behavior":
            ctx.note("ignored-block", "behavior outside an object ignored", f"behavior {block.name!r}", block.loc)
        elif block.kind not in ("template", "environment"):
            what = f"'{block.kind}' block" + (f" {block.name!r}" if block.name else "")
            ctx.note("ignored-block", f"{what} ignored: it is not part of a robot description", loc=block.loc)


def _group(ctx: Lowering, block: Block, frame: Mat, enclosing: str | None, scope: tuple[str, ...]) -> None:
    label = f"{block.kind} {block.name!r}" if block.name else block.kind
    for key in block.props:
        if key not in ("origin", "position", "rotation"):
            ctx.note("ignored-property", f"property {key!r} ignored", label, block.prop_locs[key])
    local = pose_of(ctx, block.props, label, position_keys=("origin", "position"))
    inner = (*scope, block.name) if block.name else scope
    if block.kind == "robot":
        _robot_block(ctx, block)
    walk(ctx, block.children, frame @ local, enclosing, inner)


def _robot_block(ctx: Lowering, block: Block) -> None:
    """``robot NAME { base_link { mass } joints { hip { type, axis, limits } } }`` (the robotics
    plugin's Isaac Lab bridge): an unnamed block is a link named by its keyword, and each block
    inside ``joints`` a joint named by its keyword."""
    for child in block.children:
        if child.name is not None or child.kind in (*OBJECT_KINDS, *GROUP_KINDS, *JOINT_KINDS, "template"):
            continue
        if child.kind == "joints":
            for j in child.children:
                j.name, j.kind = j.kind, "joint"
                j.name_loc = j.loc
                ctx.robot_joints.add(id(j))
            child.kind = "group"
            ctx.note("robot-joints", "each block in 'joints' read as a joint named by its keyword", loc=child.loc)
        else:
            child.name, child.kind = child.kind, "link"
            child.name_loc = child.loc
            ctx.note("robot-link", f"block '{child.name}' read as a link of that name", loc=child.loc)


# ---- one object --------------------------------------------------------------------------------
def read_object(ctx: Lowering, block: Block, frame: Mat, enclosing: str | None, scope: tuple[str, ...]) -> Obj:
    name = _object_name(ctx, block, scope)
    label = f"object {name!r}"
    props = dict(block.props)
    traits = list(block.traits)
    behaviors = [c for c in block.children if c.kind == "behavior"]
    template = _template(ctx, block, label)
    if template is not None:
        props, traits, behaviors = apply_template(ctx, template, block, label, behaviors)
    _normalize_shape(ctx, props, label)
    _normalize_mass(ctx, block, props, label)
    if "position" not in props and "joint_origin" in props:
        props["position"] = props["joint_origin"]
        ctx.note(
            "joint-origin-as-position",
            "joint_origin read as the object's position",
            label,
            props["joint_origin"].loc,
        )
    local = pose_of(ctx, props, label, position_keys=("position",))
    obj = Obj(name, block, props, traits, behaviors, frame @ local, enclosing, len(ctx.objects))
    ctx.objects[name] = obj
    return obj


def _object_name(ctx: Lowering, block: Block, scope: tuple[str, ...]) -> str:
    """The block's name, or its kind when unnamed; a name used before gets a unique link name."""
    name = block.name or block.kind
    if not block.name:
        ctx.note("unnamed-object", f"unnamed {block.kind} block named {name!r}", block.kind, block.loc)
    if name in ctx.objects or name in ctx.renamed:
        # HoloScript allows the same name twice; links need unique names.
        new = unique(f"{scope[-1]}_{name}" if scope else name, set(ctx.objects) | set(ctx.renamed))
        first = ctx.objects[ctx.renamed.get(name, name)].block
        ctx.note(
            "renamed-duplicate",
            f"object name {name!r} is used again (first at {first.name_loc}): this one's link is named {new!r}"
            f"; references to {name!r} mean the first",
            f"object {name!r}",
            block.name_loc,
            warn=True,
        )
        ctx.renamed.setdefault(name, name)
        name = new
    return name


def _template(ctx: Lowering, block: Block, label: str) -> Block | None:
    """The template the block uses, if this file defines it (a near-miss of a defined name is an error)."""
    if block.using is None:
        return None
    template = ctx.templates.get(block.using)
    if template is None and not suggest(block.using, ctx.templates):
        ctx.note(
            "unknown-template",
            f"template {block.using!r} is not defined in this file (HoloScript may import it): "
            "its defaults are not applied",
            label,
            block.using_loc,
            warn=True,
        )
    elif template is None:
        raise BrokenReferenceError(
            f"template {block.using!r} is not defined{suggest(block.using, ctx.templates)}",
            element=label,
            loc=block.using_loc,
        )
    return template


def _normalize_shape(ctx: Lowering, props: dict[str, Value], label: str) -> None:
    """Other spellings of the shape: ``mesh: { type: "cube", width, height, depth }`` or
    ``mesh: "file.glb"`` for ``geometry`` (an info finding)."""
    mesh = props.get("mesh")
    if "geometry" in props or mesh is None:
        return
    if isinstance(mesh.data, str):
        props["geometry"] = mesh
        ctx.note("mesh-as-geometry", "mesh read as the geometry", label, mesh.loc)
    elif isinstance(mesh.data, dict) and isinstance(mesh.data.get("type", Value(None, mesh.loc)).data, str):
        d = mesh.data
        props["geometry"] = d["type"]
        if "scale" not in props:
            _mesh_scale(props, d, mesh, label)
        ctx.note(
            "mesh-as-geometry",
            "mesh { type, width, height, depth } read as the geometry and its scale",
            label,
            mesh.loc,
        )


def _mesh_scale(props: dict[str, Value], d: dict[str, Value], mesh: Value, label: str) -> None:
    dims = {k: d[k] for k in ("width", "height", "depth", "radius", "size") if k in d}
    if "radius" in dims:
        r = num(dims["radius"], "mesh.radius", label)
        h = num(dims["height"], "mesh.height", label) if "height" in dims else 2 * r
        props["scale"] = Value([Value(2 * r, mesh.loc), Value(h, mesh.loc), Value(2 * r, mesh.loc)], mesh.loc)
    elif "size" in dims:
        props["scale"] = dims["size"]
    elif dims:
        w, h, dp = (num(dims[k], f"mesh.{k}", label) if k in dims else 1.0 for k in ("width", "height", "depth"))
        props["scale"] = Value([Value(w, mesh.loc), Value(h, mesh.loc), Value(dp, mesh.loc)], mesh.loc)


def _normalize_mass(ctx: Lowering, block: Block, props: dict[str, Value], label: str) -> None:
    """``rigidbody: { mass }`` (or a ``rigidbody { }`` block) for ``mass`` (an info finding)."""
    if trait_or_prop_mass(block) is not None or "mass" in props:
        return
    rb = props.get("rigidbody")
    rb_props = rb.data if rb is not None and isinstance(rb.data, dict) else None
    if rb_props is None:
        child = next((c for c in block.children if c.kind == "rigidbody"), None)
        rb_props = child.props if child is not None else None
    if rb_props is not None and "mass" in rb_props:
        props["mass"] = rb_props["mass"]
        ctx.note("rigidbody-mass", "rigidbody mass read as the object's mass", label, rb_props["mass"].loc)


def empty_link(ctx: Lowering, name: str, parent: str | None, block: Block, why: str, *, place: bool = True) -> None:
    """An empty link ``name`` standing for a body the file names but does not declare."""
    world = ctx.objects[parent].world if parent in ctx.objects else ctx.up
    if place and ("position" in block.props or "origin" in block.props):
        world = world @ pose_of(ctx, block.props, f"joint {block.name!r}", ("origin", "position"))
    ctx.objects[name] = Obj(name, block, {}, [], [], world, parent, len(ctx.objects))
    ctx.synthetic.add(name)
    ctx.note(
        "empty-link",
        f"{why}: a link {name!r} without shape or mass stands for it",
        f"joint {block.name!r}" if block.kind in JOINT_KINDS else f"object {block.name!r}",
        block.loc,
        warn=True,
    )
