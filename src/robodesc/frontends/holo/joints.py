"""Lowering one :class:`JointSpec` to a builder joint: its type, axis, limits (degrees or radians for
angular joints, by notation; metres for prismatic ones), dynamics, mimic, safety controller and
``@actuator`` s.

HoloScript has two units for joint angles, and which one a file means follows its notation:
- ``@joint { limits: { min, max } }``, ``@joint(limits: [..])``, ``joint_type`` properties and joint
  blocks: **degrees**. HoloScript's URDF compiler multiplies ``@joint`` limits by pi/180, and every
  example in these notations writes degrees (+-180, +-135, [0, 150]).
- ``@joint_revolute`` & co. with ``joint_limits``, ``behavior "RevoluteJoint" { lowerLimit,
  upperLimit }`` and the joints of a ``robot`` block: **radians**. The robotics plugin, the only
  HoloScript code that reads ``@joint_revolute``, writes ``joint_limits`` to URDF as they are and
  converts them from radians to degrees for USD ("HoloScript angular inputs are radians"); HoloScript's
  own documentation of ``behavior "RevoluteJoint"`` writes +-3.14159 with ``maxVelocity: 2.094``; and
  every example in these notations writes radians (+-3.14159, -2.3562, +-6.28318, +-1.57).
Limits that look like the other unit are read as the notation says, with a warning that gives the
values to write."""

from __future__ import annotations

import math
from dataclasses import dataclass

from robodesc.frontends.compose.builder import JOINT_TYPES, RobotBuilder, axis_vector, joint_type
from robodesc.frontends.holo.context import JointSpec, Lowering, Obj
from robodesc.frontends.holo.parser import Value
from robodesc.frontends.holo.values import describe, fail, num, string, suggest, vec3
from robodesc.ir.diagnostics import SourceLoc
from robodesc.ir.geometry import Vec3
from robodesc.ir.model import JointType, SafetyController

LIMIT_KEYS = ("min", "max", "lower", "upper", "effort", "velocity")


@dataclass(slots=True)
class _Limits:
    lower: float | None
    upper: float | None
    effort: float | None
    velocity: float | None
    loc: SourceLoc


def lower_joint(ctx: Lowering, builder: RobotBuilder, obj: Obj, spec: JointSpec, parent: str, name: str) -> JointType:
    """Add the joint that moves ``obj`` to the builder; its type as written (fixed, continuous ...)."""
    label = obj.label
    jtype = _joint_type(ctx, spec, label)
    p = spec.params
    angular = jtype in (JointType.REVOLUTE, JointType.CONTINUOUS)
    # Revolute limits, offsets and soft limits: degrees or radians by notation (see the module's
    # docstring); prismatic ones metres.
    k = math.pi / 180.0 if angular and not spec.radians else 1.0
    axis = _axis(ctx, spec, jtype, label)
    lim = (
        _behavior_limits(p, k, spec.loc, label) if spec.notation.startswith("behavior") else _limits(p, k, spec, label)
    )
    jtype = _check_limits(ctx, jtype, lim, k, spec, label)
    # joint_viscous_friction (the robotics plugin's PhysX viscous friction coefficient) is URDF's
    # damping: torque per unit joint velocity.
    dkey = next((key for key in ("damping", "viscous_friction") if key in p), None)
    damping = num(p[dkey], dkey, label) if dkey is not None else None
    friction = num(p["friction"], "friction", label) if "friction" in p else None
    armature = num(p["armature"], "armature", label) if "armature" in p else None
    mimic, multiplier, offset = _mimic(ctx, p, k, label)
    safety = _safety(p, k, label)
    builder.joint(
        name,
        jtype,
        parent,
        obj.name,
        axis=axis,
        lower=lim.lower,
        upper=lim.upper,
        effort=lim.effort,
        velocity=lim.velocity,
        damping=damping,
        friction=friction,
        mimic=mimic,
        multiplier=multiplier,
        offset=offset,
        safety=safety,
        armature=armature,
        src=spec.loc,
        limit_src=lim.loc,
        display_name=None,
    )
    _actuators(builder, obj, jtype, name)
    return jtype


def _joint_type(ctx: Lowering, spec: JointSpec, label: str) -> JointType:
    key = spec.type.strip().lower()
    if key not in JOINT_TYPES and not suggest(key, JOINT_TYPES):
        # spring, d6, distance ...: physics constraints with no URDF joint. HoloScript's own
        # compiler writes them as fixed without a word; robodesc does the same, and says so.
        ctx.note(
            "unsupported-joint-type",
            f"joint type {spec.type!r} has no URDF/SDF/USD equivalent: written as a fixed joint; its "
            "other parameters are dropped",
            label,
            spec.type_loc,
            warn=True,
        )
        key = "fixed"
    return joint_type(key, label, spec.type_loc)


def _axis(ctx: Lowering, spec: JointSpec, jtype: JointType, label: str) -> Vec3 | None:
    p = spec.params
    if "axis" not in p:
        if jtype.dof > 0 and jtype is not JointType.SPHERICAL and jtype is not JointType.FLOATING:
            ctx.note("default-axis", "no axis given: URDF's default +x applies", label, spec.loc, warn=True)
        return None
    value = p["axis"]
    axis: Vec3 | None
    if isinstance(value.data, str):
        try:
            axis = axis_vector(value.data)
        except ValueError as exc:
            raise fail(str(exc), label, value.loc) from None
    else:
        axis = vec3(value, f"{spec.notation}.axis", label)
    if not any(axis or ()):
        raise fail("axis is the zero vector", label, value.loc)
    return axis


def _limits(p: dict[str, Value], k: float, spec: JointSpec, label: str) -> _Limits:
    """``limits: [min, max]`` or ``limits: { min, max, effort, velocity }``, and the effort and
    velocity keys beside them (``maxTorque``, ``max_velocity`` ...)."""
    lim = _Limits(None, None, None, None, spec.loc)
    if "limits" in p and isinstance(p["limits"].data, list):
        value = p["limits"]
        lim.loc = value.loc
        pair = value.data if isinstance(value.data, list) else []
        if len(pair) != 2:
            raise fail(f"limits: expected [min, max], got {describe(value)}", label, value.loc)
        lim.lower = num(pair[0], "limits[0]", label) * k
        lim.upper = num(pair[1], "limits[1]", label) * k
    elif "limits" in p:
        value = p["limits"]
        lim.loc = value.loc
        if not isinstance(value.data, dict):
            raise fail(f"limits: expected {{ min, max, effort, velocity }}, got {describe(value)}", label, value.loc)
        d = value.data
        for key in d:
            if key not in LIMIT_KEYS:
                raise fail(
                    f"limits: unknown key {key!r}{suggest(key, ('min', 'max', 'effort', 'velocity'))}",
                    label,
                    value.key_locs[key],
                )
        lo = d.get("min") or d.get("lower")
        hi = d.get("max") or d.get("upper")
        lim.lower = None if lo is None else num(lo, "limits.min", label) * k
        lim.upper = None if hi is None else num(hi, "limits.max", label) * k
        lim.effort = num(d["effort"], "limits.effort", label) if "effort" in d else None
        lim.velocity = num(d["velocity"], "limits.velocity", label) if "velocity" in d else None
    for key in ("effort", "max_effort", "maxTorque", "maxForce", "torque"):
        if key in p and lim.effort is None:
            lim.effort = num(p[key], key, label)
    for key in ("velocity", "max_velocity", "maxVelocity"):
        if key in p and lim.velocity is None:
            lim.velocity = num(p[key], key, label)
    return lim


def _behavior_limits(p: dict[str, Value], k: float, loc: SourceLoc, label: str) -> _Limits:
    """A ``behavior "RevoluteJoint"`` block's ``lowerLimit``, ``upperLimit``, ``maxVelocity``, ``maxTorque``."""
    lim = _Limits(None, None, None, None, loc)
    if "lowerLimit" in p:
        lim.lower = num(p["lowerLimit"], "lowerLimit", label) * k
    if "upperLimit" in p:
        lim.upper = num(p["upperLimit"], "upperLimit", label) * k
    if "maxVelocity" in p:
        lim.velocity = num(p["maxVelocity"], "maxVelocity", label)
    for key in ("maxTorque", "maxForce", "maxEffort"):
        if key in p:
            lim.effort = num(p[key], key, label)
    return lim


def _check_limits(ctx: Lowering, jtype: JointType, lim: _Limits, k: float, spec: JointSpec, label: str) -> JointType:
    """Refuse limits that cannot be, say which look wrong; a revolute joint without both limits turns
    continuous (its limits dropped from ``lim``)."""
    lower, upper = lim.lower, lim.upper
    if lower is not None and upper is not None and lower > upper:
        raise fail("the lower limit is above the upper limit", label, lim.loc)
    angular = jtype in (JointType.REVOLUTE, JointType.CONTINUOUS)
    if angular and lower is not None and upper is not None:
        _check_unit(ctx, spec, lower / k, upper / k, lim.loc, label)
    if jtype is JointType.REVOLUTE and (lower is None or upper is None):
        ctx.note(
            "unlimited-revolute",
            "revolute joint without min/max limits: written as a continuous joint (it may turn freely)",
            label,
            spec.loc,
            warn=True,
        )
        lim.lower = lim.upper = None
        return JointType.CONTINUOUS
    if jtype is JointType.PRISMATIC and (lower is None or upper is None):
        raise fail("a prismatic joint needs limits { min, max } (metres)", label, lim.loc)
    return jtype


def _check_unit(ctx: Lowering, spec: JointSpec, lower: float, upper: float, loc: SourceLoc, label: str) -> None:
    """Warn when angular limits, as written, look like the other unit than the notation's."""
    if not spec.radians and looks_like_radians(lower, upper):
        ctx.note(
            "radian-looking-limits",
            f"limits [{lower:g}, {upper:g}] are read in degrees (HoloScript's unit for angles in "
            f"{spec.notation}) but look like radians; if radians were meant, write "
            f"[{math.degrees(lower):.4g}, {math.degrees(upper):.4g}]",
            label,
            loc,
            warn=True,
        )
    elif spec.radians and looks_like_degrees(lower, upper):
        ctx.note(
            "degree-looking-limits",
            f"limits [{lower:g}, {upper:g}] are read in radians (HoloScript's unit for angles in "
            f"{spec.notation}, as its robotics plugin reads them) but look like degrees; if degrees "
            f"were meant, write [{math.radians(lower):.4g}, {math.radians(upper):.4g}]",
            label,
            loc,
            warn=True,
        )


def looks_like_radians(lower: float, upper: float) -> bool:
    """Both limits within 2π and at least one a multiple of π/2 (±1.57, ±3.14, 6.28)."""
    if max(abs(lower), abs(upper)) > 2 * math.pi + 1e-3 or (lower == 0 and upper == 0):
        return False
    return any(v != 0 and abs(v / (math.pi / 2) - round(v / (math.pi / 2))) < 2e-3 for v in (lower, upper))


def looks_like_degrees(lower: float, upper: float) -> bool:
    """A limit beyond one turn (2 pi): rare in radians, common in degrees (+-90, +-170)."""
    return max(abs(lower), abs(upper)) > 2 * math.pi + 1e-3


def _mimic(ctx: Lowering, p: dict[str, Value], k: float, label: str) -> tuple[str | None, float | None, float | None]:
    """``mimic: "Leader"`` or ``mimic: { joint, multiplier, offset }``: (leader joint, multiplier, offset)."""
    if "mimic" not in p:
        return None, None, None
    m = p["mimic"]
    multiplier = offset = None
    if isinstance(m.data, str):
        mimic = m.data
    elif isinstance(m.data, dict) and "joint" in m.data:
        mimic = string(m.data["joint"], "mimic.joint", label)
        if "multiplier" in m.data:
            multiplier = num(m.data["multiplier"], "mimic.multiplier", label)
        if "offset" in m.data:
            offset = num(m.data["offset"], "mimic.offset", label) * k
    else:
        raise fail("mimic: expected { joint, multiplier, offset }", label, m.loc)
    # The author names the leader by its object; joints are named after their objects.
    if mimic in ctx.objects:
        mimic = f"{mimic}_joint"
    return mimic, multiplier, offset


def _safety(p: dict[str, Value], k: float, label: str) -> SafetyController | None:
    if "safetyController" not in p:
        return None
    sc = p["safetyController"]
    if not isinstance(sc.data, dict):
        raise fail("safetyController: expected an object", label, sc.loc)
    d = sc.data

    def get(*names: str) -> Value | None:
        for nm in names:
            if nm in d:
                return d[nm]
        return None

    kv = get("kVelocity", "k_velocity")
    if kv is None:
        raise fail("safetyController needs kVelocity", label, sc.loc)
    kp, sl, su = (
        get("kPosition", "k_position"),
        get("softLowerLimit", "soft_lower_limit"),
        get("softUpperLimit", "soft_upper_limit"),
    )
    return SafetyController(
        k_velocity=num(kv, "safetyController.kVelocity", label),
        k_position=None if kp is None else num(kp, "safetyController.kPosition", label),
        soft_lower_limit=None if sl is None else num(sl, "safetyController.softLowerLimit", label) * k,
        soft_upper_limit=None if su is None else num(su, "safetyController.softUpperLimit", label) * k,
        src=sc.loc,
    )


def _actuators(builder: RobotBuilder, obj: Obj, jtype: JointType, name: str) -> None:
    label = obj.label
    for act in obj.traits_named("actuator"):
        if jtype is JointType.FIXED:
            raise fail("@actuator on an object whose joint is fixed", label, act.loc)
        a = act.params
        builder.actuator(
            name,
            type=string(a["transmissionType"], "@actuator.transmissionType", label)
            if "transmissionType" in a
            else "transmission_interface/SimpleTransmission",
            interface=string(a["hardwareInterface"], "@actuator.hardwareInterface", label)
            if "hardwareInterface" in a
            else None,
            reduction=num(a["mechanicalReduction"], "@actuator.mechanicalReduction", label)
            if "mechanicalReduction" in a
            else None,
            name=string(a["name"], "@actuator.name", label) if "name" in a else None,
            src=act.loc,
        )
