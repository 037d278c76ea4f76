"""Reading joints in every spelling HoloScript uses into :class:`JointSpec` records: ``@joint``,
``@joint_revolute`` & co. with ``joint_*`` properties, ``behavior "RevoluteJoint"``,
``joint_type``/``parent`` properties, and ``joint "Name" { parent, child }`` blocks."""

from __future__ import annotations

from robodesc.frontends.holo.context import JointSpec, Lowering, Obj
from robodesc.frontends.holo.parser import Block, Trait, Value
from robodesc.frontends.holo.scene import empty_link
from robodesc.frontends.holo.values import fail, string, suggest, text, unique
from robodesc.ir.diagnostics import BrokenReferenceError

# Trait spellings of a joint: @joint_revolute ... (HoloScript's own URDF compiler reads only @joint).
JOINT_TRAITS = {
    "joint_revolute": "revolute",
    "joint_hinge": "revolute",
    "joint_continuous": "continuous",
    "joint_prismatic": "prismatic",
    "joint_slider": "prismatic",
    "joint_fixed": "fixed",
    "joint_ball": "spherical",
    "joint_spherical": "spherical",
}
BEHAVIOR_JOINTS: dict[str, str] = {
    "RevoluteJoint": "revolute",
    "HingeJoint": "revolute",
    "ContinuousJoint": "continuous",
    "PrismaticJoint": "prismatic",
    "SliderJoint": "prismatic",
    "FixedJoint": "fixed",
    "BallJoint": "spherical",
    "SphericalJoint": "spherical",
}


# ---- joint blocks ------------------------------------------------------------------------------
def joint_blocks(ctx: Lowering) -> dict[str, JointSpec]:
    """``joint "Name" [@joint_revolute] { type, axis, limits, parent, child }`` declarations, by child.

    A declaration naming an object as ``child`` is that object's joint. Without a child, the
    joint moves a new, empty link ``<Name>_link``; a parent that is no object becomes an empty
    link of that name. Each of these is reported."""
    specs: dict[str, JointSpec] = {}
    previous_child: str | None = None
    for block, enclosing in ctx.joint_decls:
        jname = block.name or f"joint_{len(specs) + 1}"
        child, spec = _joint_block(ctx, block, jname, enclosing, previous_child)
        if child in specs:
            raise fail(f"object {child!r} has two joints", f"joint {jname!r}", block.loc)
        specs[child] = spec
        previous_child = child
    return specs


def _joint_block(
    ctx: Lowering, block: Block, jname: str, enclosing: str | None, previous_child: str | None
) -> tuple[str, JointSpec]:
    label = f"joint {jname!r}"
    p = {k[6:] if k.startswith("joint_") else k: v for k, v in block.props.items()}
    for t in block.traits:
        p.update(t.params)
    jtype_text = next((JOINT_TRAITS[t.name] for t in block.traits if t.name in JOINT_TRAITS), None)
    type_value = p.get("type") or p.get("jointType")
    if type_value is not None:
        jtype_text = string(type_value, "type", label)
    if jtype_text is None:
        raise fail("a joint needs a type (type: revolute, or @joint_revolute)", label, block.loc)
    parent_value = p.get("parent") or p.get("connectedBody")
    parent = text(parent_value, "parent", label)
    if parent is None:
        parent = previous_child or enclosing
        if parent is not None:
            ctx.note(
                "inferred-parent",
                f"the joint names no parent: it hangs from {parent!r}, "
                + ("the link the previous joint moves" if parent == previous_child else "its enclosing object"),
                label,
                block.loc,
            )
    if parent is not None and parent not in ctx.objects:
        empty_link(ctx, parent, None, block, f"{label} names parent {parent!r}, which is no object")
    child = text(p.get("child"), "child", label)
    if child is None:
        child = unique(f"{jname}_link", set(ctx.objects))
        empty_link(ctx, child, parent, block, f"{label} names no child object")
    elif child not in ctx.objects:
        raise BrokenReferenceError(
            f"joint child {child!r} is not an object of this composition{suggest(child, ctx.objects)}",
            element=label,
            loc=p["child"].loc,
        )
    spec = JointSpec(
        type=jtype_text,
        type_loc=block.loc if type_value is None else type_value.loc,
        parent=parent,
        parent_loc=None if parent_value is None else parent_value.loc,
        params=p,
        loc=block.loc,
        notation="robot joint" if id(block) in ctx.robot_joints else "joint block",
        name=jname,
        radians=id(block) in ctx.robot_joints,
    )
    return child, spec


# ---- an object's own joint ---------------------------------------------------------------------
def joint_spec(ctx: Lowering, obj: Obj) -> JointSpec | None:
    """The joint the object declares itself, in whichever notation; two notations are an error."""
    label = obj.label
    specs = [_joint_trait_spec(t, label) for t in obj.traits_named("joint")]
    specs += [_typed_trait_spec(obj, t) for t in obj.traits if t.name in JOINT_TRAITS]
    specs += _behavior_specs(ctx, obj)
    prop_spec = _property_spec(obj, bool(specs))
    if prop_spec is not None:
        specs.append(prop_spec)
    if len(specs) > 1:
        raise fail(
            f"joint given twice ({specs[0].notation} at {specs[0].loc} and {specs[1].notation}); keep one",
            label,
            specs[1].loc,
        )
    return specs[0] if specs else None


def _joint_trait_spec(t: Trait, label: str) -> JointSpec:
    """``@joint { jointType, connectedBody, axis, limits }`` (or ``@joint(type, ...)``)."""
    p = t.params
    key = next((k for k in ("jointType", "type", "_arg0") if k in p), None)
    if key is None:
        raise fail("@joint needs jointType (revolute, continuous, prismatic, fixed, ball ...)", label, t.loc)
    parent = p.get("connectedBody") or p.get("parent")
    return JointSpec(
        type=string(p[key], f"@joint.{key}", label),
        type_loc=p[key].loc,
        parent=text(parent, "@joint.connectedBody", label),
        parent_loc=None if parent is None else parent.loc,
        params=p,
        loc=t.loc,
        notation="@joint",
        name=text(p.get("name"), "@joint.name", label),
    )


def _typed_trait_spec(obj: Obj, t: Trait) -> JointSpec:
    """``@joint_revolute`` with ``joint_*`` properties (HoloScript's Isaac Lab examples)."""
    label = obj.label
    p = {**{k[6:] if k.startswith("joint_") else k: v for k, v in obj.props.items()}, **t.params}
    parent = p.get("parent") or p.get("connectedBody")
    return JointSpec(
        type=JOINT_TRAITS[t.name],
        type_loc=t.loc,
        parent=text(parent, "joint_parent", label),
        parent_loc=None if parent is None else parent.loc,
        params=p,
        loc=t.loc,
        notation=f"@{t.name}",
        name=text(obj.props.get("joint_name"), "joint_name", label),
        radians=True,
    )


def _behavior_specs(ctx: Lowering, obj: Obj) -> list[JointSpec]:
    """``behavior "RevoluteJoint" { axis, lowerLimit, ... }`` blocks; other behaviors are ignored."""
    label = obj.label
    specs: list[JointSpec] = []
    joint_behaviors = [b for b in obj.behaviors if b.name in BEHAVIOR_JOINTS]
    override = obj.props.get("behavior")
    for b in obj.behaviors:
        if b.name not in BEHAVIOR_JOINTS:
            ctx.note("ignored-behavior", f"behavior {b.name!r} ignored", label, b.loc)
            continue
        params = b.props
        if override is not None and isinstance(override.data, dict) and len(joint_behaviors) == 1:
            # `behavior: { axis: [0, 1, 0] }` on an object using a template whose behavior block
            # is the joint: the object's values win, key by key, as template values do.
            params = {**b.props, **override.data}
            ctx.note(
                "template-override",
                f"behavior: {{ {', '.join(override.data)} }} overrides behavior {b.name!r} of its template",
                label,
                override.loc,
            )
        parent = params.get("connectedBody") or params.get("parent") or obj.props.get("parent")
        specs.append(
            JointSpec(
                type=BEHAVIOR_JOINTS[b.name],
                type_loc=b.name_loc,
                parent=text(parent, "parent", label),
                parent_loc=None if parent is None else parent.loc,
                params=params,
                loc=b.loc,
                notation=f'behavior "{b.name}"',
                radians=True,
            )
        )
    return specs


def _property_spec(obj: Obj, others: bool) -> JointSpec | None:
    """``joint_type`` (with ``parent``, ``axis``, ``limits``) properties; else a bare ``parent`` (or
    ``joint_parent``) property, when no other notation gives a joint, is a fixed joint."""
    label = obj.label
    props = obj.props
    if "joint_type" in props:
        parent: Value | None = props.get("parent") or props.get("joint_parent")
        return JointSpec(
            type=string(props["joint_type"], "joint_type", label),
            type_loc=props["joint_type"].loc,
            parent=text(parent, "parent", label),
            parent_loc=None if parent is None else parent.loc,
            params={k: v for k, v in props.items() if k in ("axis", "limits")},
            loc=obj.block.prop_locs.get("joint_type", obj.block.loc),
            notation="joint_type",
            name=text(props.get("joint_name"), "joint_name", label),
        )
    if ("parent" in props or "joint_parent" in props) and not others:
        pkey = "parent" if "parent" in props else "joint_parent"
        value = props[pkey]
        return JointSpec(
            type="fixed",
            type_loc=value.loc,
            parent=string(value, pkey, label),
            parent_loc=value.loc,
            params={},
            loc=obj.block.prop_locs.get(pkey, obj.block.loc),
            notation=pkey,
        )
    return None
