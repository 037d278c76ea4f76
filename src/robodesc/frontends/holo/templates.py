"""Templates: defaults an object overrides key by key (``object "A" using "T" { }``)."""

from __future__ import annotations

from robodesc.frontends.holo.context import Lowering
from robodesc.frontends.holo.parser import Block, Trait, Value


def apply_template(
    ctx: Lowering, template: Block, block: Block, label: str, behaviors: list[Block]
) -> tuple[dict[str, Value], list[Trait], list[Block]]:
    """The object's properties, traits and behavior blocks over its template's."""
    note_overrides(ctx, template, block, label)
    props = merge_props(template.props, block.props)
    traits = merge_traits(template.traits, block.traits)
    if trait_or_prop_mass(template) is not None and trait_or_prop_mass(block) is not None:
        props, traits = drop_template_mass(props, traits, block)
    mine = {b.name for b in behaviors}
    behaviors = [b for b in template.children if b.kind == "behavior" and b.name not in mine] + behaviors
    return props, traits, behaviors


def note_overrides(ctx: Lowering, template: Block, block: Block, label: str) -> None:
    """Template values are defaults: say which the object overrides (an info finding)."""
    over: list[str] = [k for k in block.props if k in template.props]
    tmass = trait_or_prop_mass(template)
    omass = trait_or_prop_mass(block)
    if tmass is not None and omass is not None and "mass" not in over:
        over.append("mass")
    names = {t.name for t in template.traits}
    over += [f"@{t.name}" for t in block.traits if t.name in names and t.params and t.name != "sensor"]
    if over:
        ctx.note(
            "template-override",
            f"overrides template {template.name!r} defaults: {', '.join(sorted(set(over)))}",
            label,
            block.name_loc,
        )


def trait_or_prop_mass(block: Block) -> Value | None:
    for t in block.traits:
        if t.name == "physics" and "mass" in t.params:
            return t.params["mass"]
    if "mass" in block.props:
        return block.props["mass"]
    ph = block.props.get("physics")
    if ph is not None and isinstance(ph.data, dict) and "mass" in ph.data:
        return ph.data["mass"]
    return None


def drop_template_mass(
    props: dict[str, Value], traits: list[Trait], block: Block
) -> tuple[dict[str, Value], list[Trait]]:
    """The object gives its own mass: every mass that only the template gave goes (defaults, not rivals)."""
    props = dict(props)
    if "mass" not in block.props:
        props.pop("mass", None)
    ph = props.get("physics")
    own_ph = block.props.get("physics")
    own_has = own_ph is not None and isinstance(own_ph.data, dict) and "mass" in own_ph.data
    if ph is not None and isinstance(ph.data, dict) and "mass" in ph.data and not own_has:
        data = {k: v for k, v in ph.data.items() if k != "mass"}
        props["physics"] = Value(data, ph.loc, {k: v for k, v in ph.key_locs.items() if k != "mass"})
    own_trait_mass = any(t.name == "physics" and "mass" in t.params for t in block.traits)
    out: list[Trait] = []
    for t in traits:
        if t.name == "physics" and "mass" in t.params and not own_trait_mass:
            t = Trait(t.name, {k: v for k, v in t.params.items() if k != "mass"}, t.loc, t.key_locs, t.in_header)
        out.append(t)
    return props, out


def merge_props(base: dict[str, Value], over: dict[str, Value]) -> dict[str, Value]:
    out = dict(base)
    for key, value in over.items():
        out[key] = merge_value(out[key], value) if key in out else value
    return out


def merge_value(base: Value, over: Value) -> Value:
    if isinstance(base.data, dict) and isinstance(over.data, dict):
        merged = dict(base.data)
        locs = dict(base.key_locs)
        for key, value in over.data.items():
            merged[key] = merge_value(merged[key], value) if key in merged else value
            locs[key] = over.key_locs.get(key, over.loc)
        return Value(merged, over.loc, locs)
    return over


def merge_traits(base: list[Trait], over: list[Trait]) -> list[Trait]:
    """Template traits overridden key by key by the object's; sensors accumulate."""
    out: list[Trait] = []
    over_names = {t.name for t in over if t.name != "sensor"}
    for t in base:
        if t.name in over_names:
            mine = next(o for o in over if o.name == t.name)
            params = merge_props(t.params, mine.params)
            out.append(Trait(t.name, params, mine.loc, {**t.key_locs, **mine.key_locs}, mine.in_header))
        else:
            out.append(t)
    done = {t.name for t in base}
    out += [t for t in over if t.name == "sensor" or t.name not in done]
    return out
