"""An object's mass and inertia tensor: ``mass``, ``@physics { mass, inertia }``, ``physics: { }`` or
the object's own ``inertia`` (the same mass may be stated more than once; different ones are an
error; the tensor once)."""

from __future__ import annotations

import math

from robodesc.frontends.holo.context import Obj
from robodesc.frontends.holo.parser import Value
from robodesc.frontends.holo.values import describe, fail, num, suggest
from robodesc.ir.contact import Contact
from robodesc.ir.diagnostics import SourceLoc
from robodesc.ir.geometry import Inertia

INERTIA_KEYS = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")


def mass(obj: Obj) -> tuple[float | None, Inertia | None]:
    """The object's mass (kg) and inertia tensor, each None when not given."""
    label = obj.label
    found, inertia_value = _stated(obj)
    value = None
    if found:
        first = found[0]
        for other in found[1:]:
            if not math.isclose(other[1], first[1], rel_tol=1e-9, abs_tol=1e-12):
                raise fail(
                    f"{other[0]} {other[1]:g} contradicts {first[0]} {first[1]:g} (at {first[2]})", label, other[2]
                )
        value = first[1]
        if value < 0:
            raise fail(f"mass must be positive, got {value:g}", label, first[2])
    inertia = None
    if inertia_value is not None:
        inertia = _inertia(inertia_value, label)
        if value is None:
            raise fail("an inertia tensor needs a mass", label, inertia_value.loc)
    return value, inertia


def _stated(obj: Obj) -> tuple[list[tuple[str, float, SourceLoc]], Value | None]:
    """Every mass the object states (where, how much, at which location), and its inertia value."""
    label = obj.label
    found: list[tuple[str, float, SourceLoc]] = []
    inertia_value: Value | None = None
    if "mass" in obj.props:
        found.append(("mass", num(obj.props["mass"], "mass", label), obj.props["mass"].loc))
    t = obj.trait("physics")
    if t is not None:
        if "mass" in t.params:
            found.append(("@physics.mass", num(t.params["mass"], "@physics.mass", label), t.params["mass"].loc))
        if "inertia" in t.params:
            inertia_value = t.params["inertia"]
    if "physics" in obj.props:
        ph = obj.props["physics"]
        if not isinstance(ph.data, dict):
            raise fail(f"physics: expected {{ mass, inertia }}, got {describe(ph)}", label, ph.loc)
        if "mass" in ph.data:
            found.append(("physics.mass", num(ph.data["mass"], "physics.mass", label), ph.data["mass"].loc))
        if "inertia" in ph.data:
            if inertia_value is not None:
                raise fail("inertia given twice (@physics and physics:)", label, ph.data["inertia"].loc)
            inertia_value = ph.data["inertia"]
    if "inertia" in obj.props:
        # `inertia: [ixx, iyy, izz, ixy, ixz, iyz]` beside `mass`, as HoloScript's robotics plugin
        # reads it (its Isaac Lab examples write the tensor so).
        if inertia_value is not None:
            raise fail("inertia given twice (inertia: and physics)", label, obj.props["inertia"].loc)
        inertia_value = obj.props["inertia"]
    return found, inertia_value


def _inertia(value: Value, label: str) -> Inertia:
    if isinstance(value.data, list):
        # [ixx, iyy, izz] or [ixx, iyy, izz, ixy, ixz, iyz]: the robotics plugin's order.
        items = value.data
        if len(items) not in (3, 6):
            raise fail(
                f"inertia: expected [ixx, iyy, izz] or [ixx, iyy, izz, ixy, ixz, iyz], got {len(items)} numbers",
                label,
                value.loc,
            )
        n = [num(item, f"inertia[{i}]", label) for i, item in enumerate(items)] + [0.0] * (6 - len(items))
        return Inertia(n[0], n[1], n[2], n[3], n[4], n[5], src=value.loc)
    if not isinstance(value.data, dict):
        raise fail("inertia: expected { ixx, iyy, izz, ixy, ixz, iyz }", label, value.loc)
    d = value.data
    for key in d:
        if key not in INERTIA_KEYS:
            raise fail(f"inertia: unknown key {key!r}{suggest(key, INERTIA_KEYS)}", label, value.key_locs[key])
    for key in ("ixx", "iyy", "izz"):
        if key not in d:
            raise fail(f"inertia needs {key}", label, value.loc)
    v = {k: num(d[k], f"inertia.{k}", label) if k in d else 0.0 for k in INERTIA_KEYS}
    return Inertia(v["ixx"], v["iyy"], v["izz"], v["ixy"], v["ixz"], v["iyz"], src=value.loc)


# HoloScript's physics keys for the surface, and the IR's names for them (docs/contact.md).
_CONTACT_KEYS = {"friction": "mu", "restitution": "restitution"}


def contact(obj: Obj) -> Contact | None:
    """``@physics { friction, restitution }`` or ``physics: { friction, restitution }``."""
    values: dict[str, float] = {}
    loc: SourceLoc | None = None
    t = obj.trait("physics")
    sources = [(t.params, "@physics")] if t is not None else []
    if "physics" in obj.props and isinstance(obj.props["physics"].data, dict):
        sources.append((obj.props["physics"].data, "physics"))
    for params, where in sources:
        for key, name in _CONTACT_KEYS.items():
            if key in params:
                value = num(params[key], f"{where}.{key}", obj.label)
                if value < 0:
                    raise fail(f"{where}.{key}: must be >= 0, got {value:g}", obj.label, params[key].loc)
                values[name] = value
                loc = loc or params[key].loc
    return Contact(**values, src=loc) if values else None  # type: ignore[arg-type]
