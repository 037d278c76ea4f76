"""Reading the syntax tree's values: numbers (through the compositions' one finite check), strings,
vectors, poses; and the small helpers the messages share."""

from __future__ import annotations

import difflib
import math
from collections.abc import Iterable

from robodesc.frontends.compose.numbers import finite
from robodesc.frontends.holo.context import Lowering
from robodesc.frontends.holo.parser import Expr, Value
from robodesc.ir.diagnostics import ParseError, SourceLoc
from robodesc.ir.geometry import Pose, Vec3
from robodesc.ir.transforms import Mat, pose_matrix


def fail(message: str, element: str, loc: SourceLoc | None) -> ParseError:
    return ParseError(message, element=element, loc=loc)


def num(value: Value, path: str, element: str) -> float:
    if isinstance(value.data, bool) or not isinstance(value.data, float):
        raise fail(f"{path}: expected a number, got {describe(value)}", element, value.loc)
    return finite(value.data, element, value.loc, path=path)


def string(value: Value, path: str, element: str) -> str:
    if not isinstance(value.data, str):
        raise fail(f"{path}: expected a string, got {describe(value)}", element, value.loc)
    return value.data


def text(value: Value | None, path: str, label: str) -> str | None:
    if value is None:
        return None
    return string(value, path, label)


def vec3(value: Value, path: str, element: str) -> Vec3:
    if isinstance(value.data, dict):
        d = value.data
        unknown = [k for k in d if k not in ("x", "y", "z")]
        if unknown:
            raise fail(f"{path}: unknown component {unknown[0]!r} (x, y, z)", element, value.key_locs[unknown[0]])
        x, y, z = (num(d[k], f"{path}.{k}", element) if k in d else 0.0 for k in ("x", "y", "z"))
        return (x, y, z)
    if not isinstance(value.data, list) or len(value.data) != 3:
        raise fail(f"{path}: expected [x, y, z], got {describe(value)}", element, value.loc)
    a, b, c = (num(v, f"{path}[{i}]", element) for i, v in enumerate(value.data))
    return (a, b, c)


def pose_of(ctx: Lowering, props: dict[str, Value], label: str, position_keys: tuple[str, ...]) -> Mat:
    """The pose ``position``/``rotation`` (roll-pitch-yaw in degrees) state, as a matrix."""
    xyz: Vec3 = (0.0, 0.0, 0.0)
    for key in position_keys:
        if (key in props and isinstance(props[key].data, (str, Expr, bool))) or (
            key in props and props[key].data is None
        ):
            ctx.note(
                "ignored-property",
                f"{key} {describe(props[key])} is no [x, y, z]: the origin is used",
                label,
                props[key].loc,
                warn=True,
            )
        elif key in props:
            xyz = vec3(props[key], key, label)
    rpy: Vec3 = (0.0, 0.0, 0.0)
    if "rotation" in props and not isinstance(props["rotation"].data, (list, dict)):
        ctx.note(
            "ignored-property",
            f"rotation {describe(props['rotation'])} is no [roll, pitch, yaw]: no rotation is applied",
            label,
            props["rotation"].loc,
            warn=True,
        )
    elif "rotation" in props:
        deg = vec3(props["rotation"], "rotation", label)
        if sum(1 for d in deg if d != 0) > 1:
            ctx.note(
                "rotation-convention",
                f"rotation {list(deg)} read as roll-pitch-yaw in degrees about fixed x, y, z axes (URDF's "
                "convention); a three.js Euler 'XYZ' reading would differ",
                label,
                props["rotation"].loc,
            )
        rpy = (math.radians(deg[0]), math.radians(deg[1]), math.radians(deg[2]))
    return pose_matrix(Pose(xyz=xyz, rpy=rpy))


def unique(name: str, used: set[str]) -> str:
    out, i = name, 2
    while out in used:
        out = f"{name}_{i}"
        i += 1
    return out


def describe(value: Value) -> str:
    d = value.data
    if isinstance(d, bool):
        return f"a boolean ({str(d).lower()})"
    if isinstance(d, float):
        return f"a number ({d:g})"
    if isinstance(d, str):
        return f"a string ({d!r})"
    if isinstance(d, list):
        return f"a list of {len(d)}"
    if isinstance(d, dict):
        return "an object"
    if isinstance(d, Expr):
        return f"an expression ({d.text!r})"
    return "null"


def suggest(name: str, known: Iterable[str]) -> str:
    close = difflib.get_close_matches(name, list(known), n=1)
    return f"; did you mean {close[0]!r}?" if close else ""
