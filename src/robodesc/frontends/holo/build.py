"""From the walked scene to the robot: whose joint is which, which objects are robot bodies and
which are props, the base, the parent of every body, then links, joints and sensors through the
builder."""

from __future__ import annotations

from robodesc.frontends.compose.builder import RobotBuilder
from robodesc.frontends.holo.context import HoloProp, HoloResult, JointSpec, Lowering, Obj
from robodesc.frontends.holo.joint_specs import JOINT_TRAITS, joint_blocks, joint_spec
from robodesc.frontends.holo.joints import lower_joint
from robodesc.frontends.holo.links import lower_link, lower_prop
from robodesc.frontends.holo.parser import Block
from robodesc.frontends.holo.scene import JOINT_KINDS, empty_link
from robodesc.frontends.holo.sensors import lower_sensors
from robodesc.frontends.holo.values import fail, suggest, unique
from robodesc.ir.diagnostics import BrokenReferenceError
from robodesc.ir.model import JointType

KNOWN_PROPS = frozenset(
    {
        "geometry",
        "position",
        "rotation",
        "scale",
        "color",
        "material",
        "mass",
        "inertia",
        "physics",
        "parent",
        "joint_type",
        "axis",
        "limits",
        "joint_name",
        "radius",
        "height",
        "length",
        "size",
        "joint_parent",
        "joint_axis",
        "joint_limits",
        "joint_effort",
        "joint_origin",
        "joint_friction",
        "joint_damping",
        "joint_viscous_friction",
        "max_effort",
        "max_velocity",
        "armature",
        "static",
        "fixed",
        "mesh",
        "rigidbody",
        "behavior",
    }
)
KNOWN_TRAITS = frozenset(
    {"physics", "rigid", "collidable", "trigger", "grabbable", "joint", "sensor", "actuator", "static", *JOINT_TRAITS}
)


def build(ctx: Lowering, name: str, comp: Block) -> HoloResult:
    """The robot named ``name`` from the objects and joints ``ctx`` holds; its props beside it."""
    joints = _joint_specs(ctx)
    if not joints:
        raise fail(
            f"the composition holds no robot: none of its {len(ctx.objects)} objects declares a joint "
            '(@joint, @joint_revolute, behavior "RevoluteJoint", joint_type, parent, or a joint block)',
            f"composition {name!r}",
            comp.loc,
        )
    referenced = {s.parent for s in joints.values() if s.parent is not None}
    _resolve_parents(ctx, joints)
    bodies, root, props = _bodies(ctx, joints, referenced)
    if not bodies:
        raise fail("the composition has no robot objects (only props)", f"composition {name!r}", comp.loc)
    if root is None:
        root = _inferred_base(ctx, bodies, joints, referenced)
    if root.name in joints:
        raise fail("the base cannot have a joint", root.label, joints[root.name].loc)
    statics = {b.name for b in bodies if is_static(b)} - {root.name}
    for static_name in sorted(statics):
        obj = ctx.objects[static_name]
        ctx.note(
            "static-link",
            "static object inside the robot: read as a link (only the base is fixed)",
            obj.label,
            obj.block.loc,
            warn=True,
        )
    builder = RobotBuilder(
        name,
        source_file=ctx.file,
        options=ctx.options,
        findings=ctx.findings,
        src=comp.loc,
        fixed_base=_fixed_base(root),
    )
    parent_of, movable = _connect(ctx, builder, bodies, root, joints)
    for obj in bodies:
        floats = obj is root and not _fixed_base(root)
        lower_link(ctx, builder, obj, moves=_moves(obj.name, parent_of, movable), floats=floats)
    for obj in bodies:
        lower_sensors(ctx, builder, obj)
    return HoloResult(builder.build(), props, ctx.findings, ctx.gravity)


def _joint_specs(ctx: Lowering) -> dict[str, JointSpec]:
    """Each object's joint (its own, or a joint block naming it as child), by object; and what of
    each object the lowering does not read, as findings."""
    joints: dict[str, JointSpec] = {}
    declared = joint_blocks(ctx)
    for obj in ctx.objects.values():
        spec = joint_spec(ctx, obj) if obj.block.kind not in JOINT_KINDS else None
        if obj.name in declared:
            if spec is not None:
                raise fail(
                    f"joint given twice ({spec.notation} and a joint block at {declared[obj.name].loc})",
                    obj.label,
                    spec.loc,
                )
            spec = declared[obj.name]
        if spec is not None:
            joints[obj.name] = spec
        _note_unread(ctx, obj)
    return joints


def _note_unread(ctx: Lowering, obj: Obj) -> None:
    for key in obj.props:
        if key not in KNOWN_PROPS:
            ctx.note("ignored-property", f"property {key!r} ignored", obj.label, obj.block.prop_locs.get(key))
    for trait in obj.traits:
        if trait.name not in KNOWN_TRAITS:
            ctx.note("ignored-trait", f"trait @{trait.name} ignored", obj.label, trait.loc)
        elif trait.name == "trigger":
            ctx.note("ignored-trait", "@trigger volumes are not part of a robot description", obj.label, trait.loc)


def _resolve_parents(ctx: Lowering, joints: dict[str, JointSpec]) -> None:
    """A parent no object of the file is, nor close to one, is declared elsewhere (an import, a part
    of the scene HoloScript resolves at run time): an empty link stands for it. A near miss is an error."""
    for spec_owner, spec in list(joints.items()):
        real = [n for n in ctx.objects if n not in ctx.synthetic]
        if spec.parent is not None and spec.parent not in ctx.objects and not suggest(spec.parent, real):
            owner = ctx.objects[spec_owner]
            empty_link(
                ctx,
                spec.parent,
                None,
                owner.block,
                f"{spec.notation} of object {spec_owner!r} names parent {spec.parent!r}, which is no object of this file",
                place=False,
            )
        elif spec.parent is not None and spec.parent not in ctx.objects:
            raise BrokenReferenceError(
                f"{spec.notation} parent {spec.parent!r} is not an object of this composition"
                f"{suggest(spec.parent, ctx.objects)}",
                element=f"object {spec_owner!r}",
                loc=spec.parent_loc,
            )


def _bodies(
    ctx: Lowering, joints: dict[str, JointSpec], referenced: set[str]
) -> tuple[list[Obj], Obj | None, list[HoloProp]]:
    """The robot's bodies in order, the base when a static object is it, and the props."""
    props: list[HoloProp] = []
    bodies: list[Obj] = []
    root: Obj | None = None
    for obj in ctx.objects.values():
        if obj.trait("grabbable") is not None and obj.name in joints:
            ctx.note(
                "grabbable-link",
                "@grabbable object declares a joint: it is a robot link (the joint wins over the prop reading)",
                obj.label,
                obj.block.loc,
            )
        elif obj.trait("grabbable") is not None:
            if obj.name in referenced:
                raise fail("a @grabbable prop cannot carry robot joints", obj.label, obj.block.loc)
            props.append(lower_prop(ctx, obj, "grabbable"))
            ctx.note(
                "prop",
                "@grabbable object is a free prop, not a robot link (load_holo returns it for world files)",
                obj.label,
                obj.block.loc,
            )
            continue
        if is_static(obj) and root is not None and obj.name not in referenced and obj.name not in joints:
            props.append(lower_prop(ctx, obj, "static"))
            ctx.note(
                "prop",
                f"static object is not connected to the robot (its base is {root.name!r}); treated as a fixture",
                obj.label,
                obj.block.loc,
            )
            continue
        if root is None and is_static(obj) and obj.name not in joints:
            root = obj
        bodies.append(obj)
    return bodies, root, props


def _inferred_base(ctx: Lowering, bodies: list[Obj], joints: dict[str, JointSpec], referenced: set[str]) -> Obj:
    """Without a static object, the root of the joint tree the author wrote: the first object a joint
    hangs from that hangs from nothing itself (a scene's first object may be its sky); else the first
    object without a joint. It floats."""
    hubs = [b for b in bodies if b.name not in joints and b.name in referenced]
    candidates = hubs or [b for b in bodies if b.name not in joints]
    root = candidates[0] if candidates else bodies[0]
    how = (
        "the first object a joint names as its parent and that has no joint itself"
        if hubs
        else ("the first object without a joint")
    )
    ctx.note(
        "inferred-base",
        f'no static object (@physics {{ type: "static" }}, @static): {how} is the base, and it floats',
        root.label,
        root.block.loc,
        warn=True,
    )
    return root


def _connect(
    ctx: Lowering, builder: RobotBuilder, bodies: list[Obj], root: Obj, joints: dict[str, JointSpec]
) -> tuple[dict[str, str], set[str]]:
    """Every body but the base joined to its parent; (parent of each body, bodies whose joint moves)."""
    body_names = [b.name for b in bodies]
    used_joint_names: set[str] = set()
    parent_of: dict[str, str] = {}
    movable: set[str] = set()
    for i, obj in enumerate(bodies):
        if obj is root:
            continue
        spec = joints.get(obj.name)
        parent = _parent(ctx, obj, spec, body_names, i, root)
        if spec is None:
            actuator = obj.trait("actuator")
            if actuator is not None:
                raise fail("@actuator on an object without a joint", obj.label, actuator.loc)
            jname = unique(f"{parent}_to_{obj.name}", used_joint_names)
            builder.joint(jname, JointType.FIXED, parent, obj.name, src=obj.block.loc)
        else:
            jname = unique(spec.name or f"{obj.name}_joint", used_joint_names)
            if lower_joint(ctx, builder, obj, spec, parent, jname) is not JointType.FIXED:
                movable.add(obj.name)
        parent_of[obj.name] = parent
        used_joint_names.add(jname)
    return parent_of, movable


def _parent(ctx: Lowering, obj: Obj, spec: JointSpec | None, body_names: list[str], i: int, root: Obj) -> str:
    """The body ``obj`` hangs from: its joint's parent, else one inferred (with a finding)."""
    parent = spec.parent if spec is not None else None
    if parent is None:
        parent = _inferred_parent(ctx, obj, body_names[:i], root)
        what = f"its {spec.notation} names no parent" if spec is not None else "it has no joint"
        how = (
            "the object it is declared in"
            if obj.enclosing == parent
            else "the base (it stands for a body declared elsewhere)"
            if obj.name in ctx.synthetic
            else "the most recent robot object declared before it"
        )
        ctx.note(
            "inferred-parent",
            f"{what}: attached to {parent!r}, {how}" + ("" if spec is not None else ", by a fixed joint"),
            obj.label,
            obj.block.loc,
        )
    elif parent not in body_names:
        raise BrokenReferenceError(
            f"{spec.notation if spec else 'joint'} parent {parent!r} is a prop, not part of the robot",
            element=obj.label,
            loc=spec.parent_loc if spec else obj.block.loc,
        )
    return parent


def is_static(obj: Obj) -> bool:
    """``@physics { type: "static" }``, or the ``@static`` trait / ``static: true`` / ``fixed: true``."""
    if obj.trait("static") is not None:
        return True
    if any(obj.props.get(k) is not None and obj.props[k].data is True for k in ("static", "fixed")):
        return True
    t = obj.trait("physics")
    if t is None or "type" not in t.params:
        return False
    return t.params["type"].data == "static"


def _fixed_base(root: Obj) -> bool | None:
    if is_static(root):
        return True
    t = root.trait("physics")
    if t is None or "type" not in t.params:
        return None
    return t.params["type"].data in ("static", "kinematic")


def _inferred_parent(ctx: Lowering, obj: Obj, before: list[str], root: Obj) -> str:
    if obj.enclosing is not None and obj.enclosing in before:
        return obj.enclosing
    if obj.name in ctx.synthetic:
        # A stand-in for a body declared elsewhere: the base holds it (a chain through the
        # objects declared before it could close a loop through its own children).
        return root.name
    return before[-1] if before else root.name


def _moves(name: str, parent_of: dict[str, str], movable: set[str]) -> bool:
    """Whether a movable joint lies between the base and ``name``."""
    seen: set[str] = set()
    while name in parent_of and name not in seen:
        if name in movable:
            return True
        seen.add(name)
        name = parent_of[name]
    return False
