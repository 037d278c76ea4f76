"""An object's look: its ``material`` name and its ``color`` (or the material's colour)."""

from __future__ import annotations

from robodesc.frontends.compose.colors import ColorError, parse_color
from robodesc.frontends.holo.context import Lowering, Obj
from robodesc.frontends.holo.parser import Expr
from robodesc.frontends.holo.values import describe, fail, num, string
from robodesc.ir.geometry import RGBA


def material(ctx: Lowering, obj: Obj) -> str | None:
    value = obj.props.get("material")
    if value is None:
        return None
    if isinstance(value.data, str):
        return value.data
    if isinstance(value.data, dict):
        # material: { preset: "chrome", color: ..., metalness: ... }: the name, and the colour
        # when the object gives none; the rendering parameters are not part of URDF.
        for key in ("name", "preset", "type"):
            if key in value.data and isinstance(value.data[key].data, str):
                return str(value.data[key].data)
        return None
    ctx.note("ignored-property", f"material {describe(value)} ignored", obj.label, value.loc, warn=True)
    return None


def color(ctx: Lowering, obj: Obj) -> RGBA | None:
    value = obj.props.get("color")
    mat = obj.props.get("material")
    if value is None and mat is not None and isinstance(mat.data, dict):
        value = mat.data.get("color") or mat.data.get("baseColor")
    if value is None:
        return None
    if isinstance(value.data, Expr):
        ctx.note("ignored-property", f"color {describe(value)} ignored", obj.label, value.loc, warn=True)
        return None
    try:
        if isinstance(value.data, list):
            return parse_color([num(v, "color", obj.label) for v in value.data])
        return parse_color(string(value, "color", obj.label))
    except ColorError as exc:
        raise fail(str(exc), obj.label, value.loc) from None
