"""The IR verifier: invariants every stage must leave intact.

``verify(robot)`` returns findings (errors, and warnings for suspicious but legal input);
``check(robot)`` raises :class:`VerificationError` carrying every error. The pipeline runs it
after the frontend, and the tests run it after every pass.
"""

from __future__ import annotations

import dataclasses
import enum
import math
import re
from collections import Counter
from collections.abc import Mapping

from robodesc.ir.diagnostics import Findings, Severity, SourceLoc, VerificationError
from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Inertial, Mesh, Pose, Sphere
from robodesc.ir.model import Joint, JointType, Mimic, Robot
from robodesc.ir.principal import below_engine_floor, inertia_problem

STAGE = "verify"

# Findings about physical plausibility rather than structure. The pipeline lets the user choose
# (--invalid-inertia error|warn|repair) what these do; structural errors are always fatal.
PHYSICAL_CODES = frozenset({"bad-mass", "bad-inertia"})


def check(robot: Robot) -> Findings:
    """Verify and raise on any error; return the warnings."""
    findings = verify(robot)
    if findings.errors:
        raise VerificationError(findings.errors)
    return findings


def verify(robot: Robot) -> Findings:
    out = Findings()
    _names(robot, out)
    _tree(robot, out)
    _references(robot, out)
    _numbers(robot, out)
    _robot_strings(robot, out)
    for link in robot.links:
        label = f"link {link.name!r}"
        if link.inertial is not None:
            _inertial(link.inertial, label, link.src, out)
        for i, visual in enumerate(link.visuals):
            _geometry(visual.geometry, f"{label} visual {i}", visual.src or link.src, out)
        for i, collision in enumerate(link.collisions):
            _geometry(collision.geometry, f"{label} collision {i}", collision.src or link.src, out)
    for joint in robot.joints:
        _joint(joint, out)
    return out


def _err(out: Findings, code: str, msg: str, element: str, loc: SourceLoc | None) -> None:
    out.add(Severity.ERROR, code, msg, element=element, loc=loc, stage=STAGE)


def _warn(out: Findings, code: str, msg: str, element: str, loc: SourceLoc | None) -> None:
    out.add(Severity.WARNING, code, msg, element=element, loc=loc, stage=STAGE)


def _names(robot: Robot, out: Findings) -> None:
    namespaces: dict[str, list[tuple[str, SourceLoc | None]]] = {
        "link": [(x.name, x.src) for x in robot.links],
        "joint": [(x.name, x.src) for x in robot.joints],
        "material": [(x.name, x.src) for x in robot.materials],
        "loop_joint": [(x.name, x.src) for x in robot.loop_joints],
        "fixed_frame": [(x.name, x.src) for x in robot.fixed_frames],
        "sensor": [(x.name, x.src) for x in robot.sensors],
        "transmission": [(x.name, x.src) for x in robot.transmissions],
    }
    for kind, entries in namespaces.items():
        counts = Counter(name for name, _ in entries)
        reported: set[str] = set()
        for name, src in entries:
            if not name and kind != "material":
                _err(out, "empty-name", f"{kind} has an empty name", kind, src)
            elif counts[name] > 1 and name not in reported:
                reported.add(name)
                _err(out, "duplicate-name", f"{counts[name]} {kind}s share this name", f"{kind} {name!r}", src)


def _tree(robot: Robot, out: Findings) -> None:
    links = robot.link_map()
    if not robot.links:
        _err(out, "no-links", "robot has no links", f"robot {robot.name!r}", robot.src)
        return
    parents: dict[str, Joint] = {}
    for joint in robot.joints:
        if joint.child in parents:
            first = parents[joint.child]
            _err(
                out,
                "two-parents",
                f"link {joint.child!r} already has parent joint {first.name!r} ({first.src}); "
                "a URDF link has exactly one parent (use a loop joint to close a loop)",
                f"joint {joint.name!r}",
                joint.src,
            )
        else:
            parents[joint.child] = joint
    reported = _cycles(links, parents, out)
    roots = [link for link in robot.links if link.name not in parents]
    if len(roots) == 0 and not reported:
        _err(out, "no-root", "no root link: every link is some joint's child", f"robot {robot.name!r}", robot.src)
    elif len(roots) > 1:
        names = ", ".join(repr(r.name) for r in roots[:6]) + (" ..." if len(roots) > 6 else "")
        _err(
            out,
            "many-roots",
            f"{len(roots)} root links ({names}); exactly one link may lack a parent joint",
            f"robot {robot.name!r}",
            roots[1].src,
        )


def _cycles(links: Mapping[str, object], parents: dict[str, Joint], out: Findings) -> set[str]:
    """Report every parent-joint cycle once; return the links on cycles.

    Each link is walked up at most once over the whole robot (a walk stops at a link an earlier walk
    finished), so this is linear in the number of links: a 50,000-link chain must not cost
    50,000 walks of 50,000 steps."""
    reported: set[str] = set()
    done: set[str] = set()
    order: dict[str, int] | None = None
    for start in links:
        if start in done:
            continue
        on_path: dict[str, int] = {}
        path: list[str] = []
        cur = start
        while cur in parents and cur not in done and cur not in on_path:
            on_path[cur] = len(path)
            path.append(cur)
            cur = parents[cur].parent
        if cur in on_path:
            cycle = path[on_path[cur] :]
            reported.update(cycle)
            if order is None:
                order = {name: i for i, name in enumerate(links)}
            # Name the cycle parent-to-child, starting from the link declared first.
            down = list(reversed(cycle))
            start_at = min(range(len(down)), key=lambda i: order.get(down[i], len(order)))
            down = down[start_at:] + down[:start_at]
            joint = parents[down[0]]
            chain = " -> ".join([*down, down[0]])
            _err(out, "cycle", f"joints form a cycle: {chain}", f"joint {joint.name!r}", joint.src)
        done.update(path)
    return reported


def _references(robot: Robot, out: Findings) -> None:
    """Every name an element refers to names something of this robot."""
    links = {x.name for x in robot.links}
    joints = robot.joint_map()
    for joint in robot.joints:
        label = f"joint {joint.name!r}"
        _need_link(links, joint.parent, label, "parent link", joint.src, out)
        _need_link(links, joint.child, label, "child link", joint.src, out)
        if joint.parent == joint.child:
            _err(out, "self-joint", "parent and child are the same link", label, joint.src)
        if joint.mimic is not None:
            _mimic_leader(joint, joint.mimic, joints, out)
    _mimic_chains(robot, out)
    _attachment_references(robot, links, joints, out)
    _controlled_joints(robot, joints, out)
    _material_references(robot, out)


def _need_link(links: set[str], name: str, element: str, what: str, src: SourceLoc | None, out: Findings) -> None:
    if name not in links:
        _err(out, "dangling-link", f"{what} {name!r} is not a link of this robot", element, src)


def _mimic_leader(joint: Joint, mimic: Mimic, joints: Mapping[str, Joint], out: Findings) -> None:
    """The joint ``mimic`` follows exists, has one degree of freedom and is another joint; the
    follower has one too (else the ``<mimic>`` has no effect)."""
    label = f"joint {joint.name!r}"
    src = mimic.src or joint.src
    leader = joints.get(mimic.joint)
    if leader is None:
        _err(out, "dangling-mimic", f"mimics joint {mimic.joint!r}, which does not exist", label, src)
    elif leader.type.dof != 1:
        _err(
            out,
            "bad-mimic",
            f"mimics {leader.name!r}, a {leader.type.value} joint; only one-DOF joints can lead",
            label,
            src,
        )
    elif joint.type.dof != 1:
        _warn(
            out,
            "ignored-mimic",
            f"a {joint.type.value} joint cannot follow {leader.name!r}; its <mimic> has no effect "
            "and is left out of URDF output",
            label,
            src,
        )
    elif leader.name == joint.name:
        _err(out, "bad-mimic", "a joint cannot mimic itself", label, src)


def _attachment_references(robot: Robot, links: set[str], joints: Mapping[str, Joint], out: Findings) -> None:
    """Loop joints, fixed frames and sensors hang on links of this robot; a fixed frame does not
    take a link's name; a sensor's parent joint exists."""
    for loop in robot.loop_joints:
        label = f"loop_joint {loop.name!r}"
        _need_link(links, loop.link1.link, label, "link1", loop.link1.src or loop.src, out)
        _need_link(links, loop.link2.link, label, "link2", loop.link2.src or loop.src, out)
    for frame in robot.fixed_frames:
        _need_link(links, frame.parent, f"fixed_frame {frame.name!r}", "parent link", frame.src, out)
        if frame.name in links:
            _err(
                out,
                "frame-shadows-link",
                "a fixed frame may not share a link's name",
                f"fixed_frame {frame.name!r}",
                frame.src,
            )
    for sensor in robot.sensors:
        _need_link(links, sensor.parent, f"sensor {sensor.name!r}", "parent link", sensor.src, out)
        if sensor.parent_joint is not None and sensor.parent_joint not in joints:
            _err(
                out,
                "dangling-joint",
                f"parent joint {sensor.parent_joint!r} is not a joint of this robot",
                f"sensor {sensor.name!r}",
                sensor.src,
            )


def _controlled_joints(robot: Robot, joints: Mapping[str, Joint], out: Findings) -> None:
    """The joints transmissions and ``<ros2_control>`` blocks name exist."""
    for tr in robot.transmissions:
        for tj in tr.joints:
            if tj.name not in joints:
                _err(
                    out,
                    "dangling-joint",
                    f"refers to joint {tj.name!r}, which does not exist",
                    f"transmission {tr.name!r}",
                    tj.src or tr.src,
                )
    for rc in robot.ros2_controls:
        for cj in rc.joints:
            if cj.name not in joints:
                _err(
                    out,
                    "dangling-joint",
                    f"refers to joint {cj.name!r}, which does not exist",
                    f"ros2_control {rc.name!r}",
                    cj.src or rc.src,
                )


def _material_references(robot: Robot, out: Findings) -> None:
    """A visual's material reference names a robot-level material (a warning: it has no colour)."""
    material_names = {m.name for m in robot.materials}
    for link in robot.links:
        for visual in link.visuals:
            m = visual.material
            if m is not None and m.is_reference() and m.name and m.name not in material_names:
                _warn(
                    out,
                    "undefined-material",
                    f"material {m.name!r} is not defined; it has no colour",
                    f"link {link.name!r}",
                    m.src or visual.src,
                )


def _mimic_chains(robot: Robot, out: Findings) -> None:
    """Report every cycle of mimic references once, at the joint declared first on it.

    Like :func:`_cycles`, every joint is followed at most once in total, so long hostile mimic
    chains cost linear time."""
    joints = robot.joint_map()
    order = {joint.name: i for i, joint in enumerate(robot.joints)}
    done: set[str] = set()
    for joint in robot.joints:
        if joint.name in done:
            continue
        on_path: dict[str, int] = {}
        path: list[Joint] = []
        cur: Joint | None = joint
        while cur is not None and cur.name not in done and cur.name not in on_path:
            on_path[cur.name] = len(path)
            path.append(cur)
            cur = joints.get(cur.mimic.joint) if cur.mimic is not None else None
        if cur is not None and cur.name in on_path:
            cycle = path[on_path[cur.name] :]
            if len(cycle) > 1:  # a joint mimicking itself is reported by _references
                first = min(range(len(cycle)), key=lambda i: order[cycle[i].name])
                names = [j.name for j in cycle[first:] + cycle[:first]]
                head = cycle[first]
                _err(
                    out,
                    "mimic-cycle",
                    "mimic joints form a cycle: " + " -> ".join([*names, names[0]]),
                    f"joint {head.name!r}",
                    head.src,
                )
        done.update(on_path)


def _inertial(inertial: Inertial, label: str, src: SourceLoc | None, out: Findings) -> None:
    loc = inertial.src or src
    mass = inertial.mass
    zero_tensor = inertial.inertia is None or not any(inertial.inertia.as_tuple())
    if mass is not None and math.isfinite(mass):
        if mass < 0:
            _err(out, "bad-mass", f"mass must be > 0 (is {mass:g})", label, loc)
            return
        if mass == 0:
            if zero_tensor:
                # The "massless frame link" idiom: legal URDF, but simulators need mass on moving bodies.
                _warn(out, "massless-link", "mass and inertia are zero (a massless frame link)", label, loc)
            else:
                _err(out, "bad-mass", "mass is 0 but the inertia tensor is not", label, loc)
            return
    if inertial.inertia is not None:
        problem = inertia_problem(inertial.inertia)
        if problem is not None:
            _err(out, "bad-inertia", problem, label, inertial.inertia.src or loc)
        elif (tiny := below_engine_floor(inertial.inertia)) is not None:
            _warn(out, "tiny-inertia", tiny, label, inertial.inertia.src or loc)


def _geometry(geom: Geometry, label: str, src: SourceLoc | None, out: Findings) -> None:
    loc = geom.src or src
    bad: str | None = None
    if isinstance(geom, Box):
        if any(not (s > 0) for s in geom.size):
            bad = f"box size must be positive (is {' '.join(f'{s:g}' for s in geom.size)})"
    elif isinstance(geom, Sphere):
        if not geom.radius > 0:
            bad = f"sphere radius must be positive (is {geom.radius:g})"
    elif isinstance(geom, Cylinder | Capsule):
        if not geom.radius > 0 or geom.length < 0 or (isinstance(geom, Cylinder) and not geom.length > 0):
            bad = f"{type(geom).__name__.lower()} radius and length must be positive (are {geom.radius:g}, {geom.length:g})"
    elif isinstance(geom, Mesh) and geom.scale is not None and any(s == 0 for s in geom.scale):
        bad = f"mesh scale has a zero factor ({' '.join(f'{s:g}' for s in geom.scale)})"
    if bad:
        _err(out, "bad-geometry", bad, label, loc)


def _joint(joint: Joint, out: Findings) -> None:
    label = f"joint {joint.name!r}"
    movable = joint.type in (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC, JointType.PLANAR)
    if movable and joint.axis is not None and all(a == 0 for a in joint.axis):
        _err(out, "zero-axis", "axis is the zero vector", label, joint.src)
    limit = joint.limit
    if limit is not None and limit.lower is not None and limit.upper is not None:
        if limit.lower > limit.upper:
            _err(
                out,
                "bad-limits",
                f"lower limit {limit.lower:g} is above upper limit {limit.upper:g}",
                label,
                limit.src or joint.src,
            )
        elif (
            joint.type in (JointType.REVOLUTE, JointType.PRISMATIC)
            and not (limit.lower <= 0 <= limit.upper)
            and joint.mimic is None
        ):
            _warn(
                out,
                "zero-outside-limits",
                f"zero position lies outside the limits [{limit.lower:g}, {limit.upper:g}]",
                label,
                limit.src or joint.src,
            )
    dynamics = joint.dynamics
    if dynamics is not None:
        for field_name in ("damping", "friction", "spring_stiffness"):
            value = getattr(dynamics, field_name)
            if value is not None and value < 0:
                # Legal to carry, but it feeds energy in: a simulator's state grows without bound.
                _warn(
                    out,
                    "negative-dynamics",
                    f"{field_name.replace('_', ' ')} is negative ({value:g}): simulators gain energy from it and "
                    "become unstable",
                    label,
                    dynamics.src or joint.src,
                )
    if limit is not None:
        for field_name in ("effort", "velocity"):
            value = getattr(limit, field_name)
            if value is not None and value < 0:
                _err(
                    out, "bad-limits", f"{field_name} limit must be >= 0 (is {value:g})", label, limit.src or joint.src
                )


# What every number in the IR must satisfy. Beyond these no target carries the value faithfully:
# USD stores masses, inertias, limits and local joint frames as float32 (at most 3.4e38, and
# limits become degrees there), and the passes square and multiply lengths and masses (inertia
# from geometry, lumping, principal axes) in doubles, whose products must not overflow to inf or
# underflow to 0. The bounds sit far outside any real robot (the largest number in the corpora is
# a 1e16 "unbounded" joint limit).
LIMIT = 1e30  # any float
MAX_LENGTH = 1e6  # m: positions, shape sizes, mesh scale factors
MIN_SIZE = 1e-9  # m: the smallest non-zero shape size or mesh scale factor
MAX_MASS = 1e12  # kg
MAX_INT = 2**31 - 1  # counts (camera pixels, ray samples): USD and SDF store int32
AXIS_NORM = (1e-9, 1e9)  # a joint axis is normalised; its length must survive squaring


# (owner type, field) -> (smallest non-zero magnitude, largest magnitude, unit). Fields not listed
# get (0, LIMIT). Looked up once per dataclass type, not per value.
_BOUNDS: dict[tuple[type, str], tuple[float, float, str]] = {
    (Pose, "xyz"): (0.0, MAX_LENGTH, " m"),
    (Box, "size"): (MIN_SIZE, MAX_LENGTH, " m"),
    (Sphere, "radius"): (MIN_SIZE, MAX_LENGTH, " m"),
    (Cylinder, "radius"): (MIN_SIZE, MAX_LENGTH, " m"),
    (Cylinder, "length"): (MIN_SIZE, MAX_LENGTH, " m"),
    (Capsule, "radius"): (MIN_SIZE, MAX_LENGTH, " m"),
    (Capsule, "length"): (MIN_SIZE, MAX_LENGTH, " m"),
    (Mesh, "scale"): (MIN_SIZE, MAX_LENGTH, ""),
    (Inertial, "mass"): (0.0, MAX_MASS, " kg"),
}
_DEFAULT_BOUNDS = (0.0, LIMIT, "")

# A value out of bounds: (field path, location, value, bounds); a string with a character no
# target can carry has bounds None.
_Bad = tuple[str, SourceLoc | None, float | str, tuple[float, float, str] | None]

# Characters XML 1.0 cannot carry (every target is XML or USD text/crate read back through XML
# tooling): C0 controls but tab, newline and carriage return; surrogates; U+FFFE, U+FFFF.
_NOT_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")


def _numbers(robot: Robot, out: Findings) -> None:
    """Every number finite and within the bounds above, named by element, field and file:line.

    One pass over the whole IR, linear in its size: it runs on every robot, before and after the
    passes, whichever frontend (URDF, xacro, a composition) built it."""
    groups: list[tuple[str, list[object]]] = [
        ("link", list(robot.links)),
        ("joint", list(robot.joints)),
        ("material", list(robot.materials)),
        ("loop_joint", list(robot.loop_joints)),
        ("fixed_frame", list(robot.fixed_frames)),
        ("sensor", list(robot.sensors)),
        ("transmission", list(robot.transmissions)),
    ]
    for kind, nodes in groups:
        for node in nodes:
            bad: list[_Bad] = []
            _scan(node, getattr(node, "src", None), "", _DEFAULT_BOUNDS, bad)
            for path, loc, value, bounds in bad:
                element = f"{kind} {getattr(node, 'name', '')!r}"
                field_path = path.lstrip(".") or "name"
                if isinstance(value, str) or bounds is None:
                    _err(out, "bad-character", _character_message(field_path, str(value)), element, loc)
                elif isinstance(value, float) and not math.isfinite(value):
                    _err(out, "non-finite", f"{field_path} is {value}", element, loc)
                else:
                    _err(out, "out-of-range", _range_message(field_path, value, bounds), element, loc)
        for node in nodes:
            axis = getattr(node, "axis", None)
            if axis is not None and any(axis) and all(math.isfinite(a) for a in axis):
                norm = math.hypot(*axis)
                if not AXIS_NORM[0] <= norm <= AXIS_NORM[1]:
                    _err(
                        out,
                        "out-of-range",
                        f"axis length is {norm:g}; it must lie between {AXIS_NORM[0]:g} and {AXIS_NORM[1]:g} "
                        "(the axis is normalised, and its squares must stay finite and non-zero)",
                        f"{kind} {getattr(node, 'name', '')!r}",
                        getattr(node, "src", None),
                    )


def value_problems(obj: object) -> list[str]:
    """The number-range and character problems of one IR value (a shape, a pose, an inertial), as
    the verifier words them; for frontends that compute with a value before the verifier runs (a
    composition derives inertia from shape sizes)."""
    bad: list[_Bad] = []
    _scan(obj, None, "", _DEFAULT_BOUNDS, bad)
    out: list[str] = []
    for path, _loc, value, bounds in bad:
        field_path = path.lstrip(".") or "value"
        if isinstance(value, str) or bounds is None:
            out.append(_character_message(field_path, str(value)))
        elif isinstance(value, float) and not math.isfinite(value):
            out.append(f"{field_path} is {value}")
        else:
            out.append(_range_message(field_path, value, bounds))
    return out


def _character_message(path: str, value: str) -> str:
    found = _NOT_XML.search(value)
    code = f"U+{ord(found.group(0)):04X}" if found else "a control character"
    return f"{path} contains {code}, a character XML cannot carry; remove it"


def _robot_strings(robot: Robot, out: Findings) -> None:
    if _NOT_XML.search(robot.name):
        _err(out, "bad-character", _character_message("name", robot.name), f"robot {robot.name!r}", robot.src)


def _range_message(path: str, value: float, bounds: tuple[float, float, str]) -> str:
    low, high, unit = bounds
    if isinstance(value, int):
        return f"{path} is {value}, beyond {MAX_INT} (targets store it as a 32-bit integer)"
    if abs(value) > high:
        why = "no robot is that large" if unit == " m" else "no target represents it faithfully"
        return f"{path} is {value:g}{unit}, beyond ±{high:g}{unit} ({why})"
    return (
        f"{path} is {value:g}{unit}; a non-zero size must be at least {low:g}{unit} "
        "(smaller ones vanish when squared or converted to float32)"
    )


_FIELDS: dict[type, tuple[tuple[str, tuple[float, float, str]], ...]] = {}


def _fields(cls: type) -> tuple[tuple[str, tuple[float, float, str]], ...]:
    names = _FIELDS.get(cls)
    if names is None:
        names = tuple(
            (f.name, _BOUNDS.get((cls, f.name), _DEFAULT_BOUNDS))
            for f in dataclasses.fields(cls)
            if f.name not in ("src", "extensions")
        )
        _FIELDS[cls] = names
    return names


def _scan_fields(
    obj: object,
    fields: tuple[tuple[str, tuple[float, float, str]], ...],
    loc: SourceLoc | None,
    path: str,
    bad: list[_Bad],
) -> None:
    """:func:`_scan` of one dataclass's fields, each against its own bounds."""
    here = getattr(obj, "src", None) or loc
    for name, field_bounds in fields:
        value = getattr(obj, name)
        if type(value) is float:
            if not (-field_bounds[1] <= value <= field_bounds[1]) or (
                field_bounds[0] and 0.0 < abs(value) < field_bounds[0]
            ):
                bad.append((f"{path}.{name}", here, value, field_bounds))
        elif type(value) is str:
            if _NOT_XML.search(value):
                bad.append((f"{path}.{name}", here, value, None))
        elif value is not None and type(value) is not bool:
            _scan(value, here, f"{path}.{name}", field_bounds, bad)


def _scan(obj: object, loc: SourceLoc | None, path: str, bounds: tuple[float, float, str], bad: list[_Bad]) -> None:
    """Collect every number under ``obj`` outside ``bounds`` (NaN and infinities included), and every
    string with a character XML cannot carry, with its path. Hot on large robots (it visits every
    value of the IR, twice per compile): the fields of a dataclass are checked in place by exact
    type, one chained comparison per float, and a path string is built only for containers entered
    and for offending values."""
    known = _FIELDS.get(type(obj))
    if known is not None:  # an IR dataclass seen before: most nodes, checked first
        _scan_fields(obj, known, loc, path, bad)
    elif type(obj) is float:
        if not (-bounds[1] <= obj <= bounds[1]) or (bounds[0] and 0.0 < abs(obj) < bounds[0]):
            bad.append((path, loc, obj, bounds))
    elif type(obj) is str:
        if _NOT_XML.search(obj):
            bad.append((path, loc, obj, None))
    elif type(obj) is tuple or type(obj) is list:
        low, high = bounds[0], bounds[1]
        for i, item in enumerate(obj):
            if type(item) is float:
                if not (-high <= item <= high) or (low and 0.0 < abs(item) < low):
                    bad.append((f"{path}[{i}]", loc, item, bounds))
            elif type(item) is int:
                if not -MAX_INT <= item <= MAX_INT:
                    bad.append((f"{path}[{i}]", loc, item, bounds))
            elif type(item) is not bool:
                _scan(item, loc, f"{path}[{i}]", bounds, bad)
    elif type(obj) is int:
        if not -MAX_INT <= obj <= MAX_INT:
            bad.append((path, loc, obj, bounds))
    elif type(obj) is dict:
        for key, value in obj.items():
            _scan(key, loc, f"{path}[{key!r}]", bounds, bad)
            _scan(value, loc, f"{path}[{key!r}]", bounds, bad)
    elif type(obj) is bool or obj is None or isinstance(obj, enum.Enum):
        return
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        _scan_fields(obj, _fields(type(obj)), loc, path, bad)
    elif isinstance(obj, int):  # an int subclass that is no bool or enum
        _scan(int(obj), loc, path, bounds, bad)
    elif isinstance(obj, float):
        _scan(float(obj), loc, path, bounds, bad)
    elif isinstance(obj, str):
        _scan(str(obj), loc, path, bounds, bad)
