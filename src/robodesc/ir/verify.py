"""The IR verifier: invariants every stage must leave intact.

``verify(robot)`` returns findings (errors, and warnings for suspicious but legal input);
``check(robot)`` raises :class:`VerificationError` carrying every error. The pipeline runs it
after the frontend, and the tests run it after every pass.
"""

from __future__ import annotations

import dataclasses
import enum
import math
from collections import Counter

from robodesc.ir.diagnostics import Findings, Severity, SourceLoc, VerificationError
from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Inertial, Mesh, Sphere
from robodesc.ir.model import Joint, JointType, Robot
from robodesc.ir.principal import inertia_problem

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
    # Cycles: walk up from every link; a walk that revisits a link is a cycle.
    reported: set[str] = set()
    for start in links:
        seen: list[str] = []
        cur = start
        while cur in parents and cur not in seen:
            seen.append(cur)
            cur = parents[cur].parent
        if cur in seen and not reported.intersection(seen):
            cycle = seen[seen.index(cur) :]
            reported.update(cycle)
            # Name the cycle parent-to-child, starting from the link declared first.
            order = list(links)
            down = list(reversed(cycle))
            start_at = min(range(len(down)), key=lambda i: order.index(down[i]))
            down = down[start_at:] + down[:start_at]
            joint = parents[down[0]]
            chain = " -> ".join([*down, down[0]])
            _err(out, "cycle", f"joints form a cycle: {chain}", f"joint {joint.name!r}", joint.src)
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


def _references(robot: Robot, out: Findings) -> None:
    links = {x.name for x in robot.links}
    joints = robot.joint_map()

    def need_link(name: str, element: str, what: str, src: SourceLoc | None) -> None:
        if name not in links:
            _err(out, "dangling-link", f"{what} {name!r} is not a link of this robot", element, src)

    for joint in robot.joints:
        label = f"joint {joint.name!r}"
        need_link(joint.parent, label, "parent link", joint.src)
        need_link(joint.child, label, "child link", joint.src)
        if joint.parent == joint.child:
            _err(out, "self-joint", "parent and child are the same link", label, joint.src)
        if joint.mimic is not None:
            leader = joints.get(joint.mimic.joint)
            if leader is None:
                _err(
                    out,
                    "dangling-mimic",
                    f"mimics joint {joint.mimic.joint!r}, which does not exist",
                    label,
                    joint.mimic.src or joint.src,
                )
            elif leader.type.dof != 1:
                _err(
                    out,
                    "bad-mimic",
                    f"mimics {leader.name!r}, a {leader.type.value} joint; only one-DOF joints can lead",
                    label,
                    joint.mimic.src or joint.src,
                )
            elif joint.type.dof != 1:
                _warn(
                    out,
                    "ignored-mimic",
                    f"a {joint.type.value} joint cannot follow {leader.name!r}; its <mimic> has no effect "
                    "and is left out of URDF output",
                    label,
                    joint.mimic.src or joint.src,
                )
            elif leader.name == joint.name:
                _err(out, "bad-mimic", "a joint cannot mimic itself", label, joint.mimic.src or joint.src)
    _mimic_chains(robot, out)
    for loop in robot.loop_joints:
        label = f"loop_joint {loop.name!r}"
        need_link(loop.link1.link, label, "link1", loop.link1.src or loop.src)
        need_link(loop.link2.link, label, "link2", loop.link2.src or loop.src)
    for frame in robot.fixed_frames:
        need_link(frame.parent, f"fixed_frame {frame.name!r}", "parent link", frame.src)
        if frame.name in links:
            _err(
                out,
                "frame-shadows-link",
                "a fixed frame may not share a link's name",
                f"fixed_frame {frame.name!r}",
                frame.src,
            )
    for sensor in robot.sensors:
        need_link(sensor.parent, f"sensor {sensor.name!r}", "parent link", sensor.src)
        if sensor.parent_joint is not None and sensor.parent_joint not in joints:
            _err(
                out,
                "dangling-joint",
                f"parent joint {sensor.parent_joint!r} is not a joint of this robot",
                f"sensor {sensor.name!r}",
                sensor.src,
            )
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
    joints = robot.joint_map()
    for joint in robot.joints:
        seen = [joint.name]
        cur = joint
        while cur.mimic is not None and cur.mimic.joint in joints:
            nxt = joints[cur.mimic.joint]
            if nxt.name in seen:
                if nxt.name == joint.name and len(seen) > 1:
                    _err(
                        out,
                        "mimic-cycle",
                        "mimic joints form a cycle: " + " -> ".join([*seen, nxt.name]),
                        f"joint {joint.name!r}",
                        joint.src,
                    )
                break
            seen.append(nxt.name)
            cur = nxt


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
    if limit is not None:
        for field_name in ("effort", "velocity"):
            value = getattr(limit, field_name)
            if value is not None and value < 0:
                _err(
                    out, "bad-limits", f"{field_name} limit must be >= 0 (is {value:g})", label, limit.src or joint.src
                )


def _numbers(robot: Robot, out: Findings) -> None:
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
            bad: list[tuple[str, SourceLoc | None, float]] = []
            _nonfinite(node, getattr(node, "src", None), "", bad)
            for path, loc, value in bad:
                _err(out, "non-finite", f"{path.lstrip('.')} is {value}", f"{kind} {getattr(node, 'name', '')!r}", loc)


_FIELDS: dict[type, tuple[str, ...]] = {}


def _fields(cls: type) -> tuple[str, ...]:
    names = _FIELDS.get(cls)
    if names is None:
        names = tuple(f.name for f in dataclasses.fields(cls) if f.name not in ("src", "extensions", "extra_attrs"))
        _FIELDS[cls] = names
    return names


def _nonfinite(obj: object, loc: SourceLoc | None, path: str, bad: list[tuple[str, SourceLoc | None, float]]) -> None:
    """Collect every non-finite float under ``obj`` with its path. Hot on large robots: no generators,
    and only containers that can hold floats are entered."""
    if isinstance(obj, float):
        if not math.isfinite(obj):
            bad.append((path, loc, obj))
    elif isinstance(obj, tuple | list):
        for i, item in enumerate(obj):
            if isinstance(item, float):
                if not math.isfinite(item):
                    bad.append((f"{path}[{i}]", loc, item))
            elif not isinstance(item, str | int):
                _nonfinite(item, loc, f"{path}[{i}]", bad)
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        here = getattr(obj, "src", None) or loc
        for name in _fields(type(obj)):
            value = getattr(obj, name)
            if value is None or isinstance(value, str | bool | int | enum.Enum):
                continue
            _nonfinite(value, here, f"{path}.{name}", bad)
