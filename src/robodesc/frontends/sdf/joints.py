"""SDF joints into IR joints.

The IR's joint frame is its child link's frame (URDF's convention), so a joint's origin is the SDF
joint frame in its parent's IR frame, and the child's contents are re-expressed in it (:mod:`.build`).
Axes are turned into that frame from the one they are ``expressed_in`` (SDF 1.4: the model frame;
1.5 and 1.6: the model frame under ``use_parent_model_frame``). A revolute joint whose limits are
SDF's "none" (±1e16, or no ``<limit>``) is continuous. ``-1`` effort or velocity is "no limit".
A mimic (SDF 1.11) ``q = m (q_leader - reference) + offset`` keeps the IR's ``m q_leader + offset'``.
Ball joints are spherical; a universal (and revolute2) joint is two revolutes through a massless
link; screw and gearbox joints have no IR form: fixed, with a warning.
"""

from __future__ import annotations

import numpy as np
from lxml import etree

from robodesc.frontends.sdf.frames import WORLD, Frames, Node
from robodesc.frontends.sdf.source import STAGE
from robodesc.frontends.sdf.values import loc, number, vec3
from robodesc.ir.diagnostics import Findings, ParseError
from robodesc.ir.model import Dynamics, Joint, JointType, Limit, Mimic
from robodesc.ir.transforms import Mat

# SDF's "unlimited" joint limit (libsdformat's default lower and upper).
UNLIMITED = 1e16
_TYPES = {
    "revolute": JointType.REVOLUTE,
    "continuous": JointType.CONTINUOUS,
    "prismatic": JointType.PRISMATIC,
    "fixed": JointType.FIXED,
    "ball": JointType.SPHERICAL,
}
_TWO_AXES = ("universal", "revolute2")
_NO_FORM = ("screw", "gearbox")


def joint_ends(frames: Frames, node: Node) -> tuple[str, str]:
    """The links (scoped names, or ``world``) a joint's ``<parent>`` and ``<child>`` attach to."""
    out = []
    for key in ("parent", "child"):
        text = node.element.findtext(key)
        if text is None:
            raise ParseError(f"a <joint> needs a <{key}>", loc=loc(node.file, node.element))
        named = frames.resolve(text, node.scope, node.element, f"joint {key}")
        out.append(named if named == WORLD else frames.link_of(named))
    return out[0], out[1]


def read_joint(
    frames: Frames, node: Node, parent: str, child: str, parent_frame: Mat, findings: Findings
) -> list[Joint]:
    """The IR joint(s) for one SDF joint; ``parent_frame`` is the parent's IR frame in the model."""
    el, file = node.element, node.file
    kind = (el.get("type") or "").strip()
    here = loc(file, el)
    label = f"joint {node.name!r}"
    joint_pose = frames.in_model(node.name)
    origin_m = np.linalg.inv(parent_frame) @ joint_pose
    from robodesc.frontends.sdf.links import _clean
    from robodesc.ir.transforms import matrix_pose

    origin = _clean(matrix_pose(origin_m))
    base = Joint(name=node.name, type=JointType.FIXED, parent=parent, child=child, origin=origin, src=here)
    if node.name != (el.get("name") or ""):
        base.display_name = el.get("name")
    if kind in _NO_FORM or kind not in (*_TYPES, *_TWO_AXES):
        findings.warn(
            "sdf-joint-unsupported",
            f"a {kind or 'typeless'} joint has no form in robodesc's targets; it is written as fixed, so every target "
            "loses its motion",
            element=label,
            loc=here,
            stage=STAGE,
        )
        return [base]
    if kind in _TWO_AXES:
        return _two_axes(frames, node, base, joint_pose, findings)
    base.type = _TYPES[kind]
    if base.type is JointType.FIXED:
        return [base]
    axis_el = el.find("axis")
    if base.type is JointType.SPHERICAL:
        findings.info(
            "sdf-ball-joint",
            "a ball joint: spherical in MJCF, USD and SDF; URDF has none, so its target writes three revolutes "
            "through massless links",
            element=label,
            loc=here,
            stage=STAGE,
        )
        if axis_el is not None:
            base.dynamics = _dynamics(file, axis_el)
        return [base]
    _axis_into(frames, node, base, axis_el, joint_pose, findings)
    return [base]


def _axis_into(
    frames: Frames, node: Node, joint: Joint, axis_el: etree._Element | None, joint_pose: Mat, findings: Findings
) -> None:
    file = node.file
    joint.axis = _axis(frames, node, axis_el, joint_pose)
    if axis_el is None:
        if joint.type is JointType.REVOLUTE:
            joint.type = JointType.CONTINUOUS
        return
    limit_el = axis_el.find("limit")
    limit = Limit(src=loc(file, limit_el)) if limit_el is not None else None
    if limit_el is not None and limit is not None:
        for key in ("lower", "upper", "effort", "velocity"):
            found = limit_el.find(key)
            if found is None:
                continue
            value = number(file, found)
            if key in ("effort", "velocity") and value < 0:
                continue  # SDF's -1: no limit
            if key in ("lower", "upper") and abs(value) >= UNLIMITED:
                continue
            setattr(limit, key, value)
    if joint.type is JointType.REVOLUTE and (limit is None or limit.lower is None or limit.upper is None):
        if limit is not None and (limit.lower is not None or limit.upper is not None):
            findings.warn(
                "sdf-one-sided-limit",
                "only one of lower and upper is limited; the IR's revolute needs both, so it is read as continuous "
                "and every target loses the one limit",
                element=f"joint {node.name!r}",
                loc=loc(file, limit_el),  # type: ignore[arg-type]  # a limit was given
                stage=STAGE,
            )
            limit.lower = limit.upper = None
        joint.type = JointType.CONTINUOUS
    if limit is not None and any(v is not None for v in (limit.lower, limit.upper, limit.effort, limit.velocity)):
        joint.limit = limit
    joint.dynamics = _dynamics(file, axis_el)
    mimic = axis_el.find("mimic")
    if mimic is not None:
        joint.mimic = _mimic(frames, node, mimic)


def _axis(
    frames: Frames, node: Node, axis_el: etree._Element | None, joint_pose: Mat, key: str = "xyz"
) -> tuple[float, float, float]:
    file = node.file
    xyz_el = axis_el.find(key) if axis_el is not None else None
    if xyz_el is None:
        return (0.0, 0.0, 1.0)
    vector = np.array(vec3(file, xyz_el))
    norm = float(np.linalg.norm(vector))
    if norm == 0:
        raise ParseError(f"<{key}> of an axis must not be zero", loc=loc(file, xyz_el))
    vector = vector / norm
    expressed = xyz_el.get("expressed_in")
    version = node.scope.version
    use_model = axis_el.findtext("use_parent_model_frame")  # type: ignore[union-attr]  # xyz_el is in it
    in_model = version == "1.4" or (
        version in ("1.5", "1.6") and use_model is not None and use_model.strip().lower() in ("1", "true")
    )
    if expressed:
        frame = frames.in_model(frames.resolve(expressed, node.scope, xyz_el, "axis expressed_in"))
        vector = frame[:3, :3] @ vector
    elif in_model:
        vector = vector  # already in the model frame
    else:
        vector = joint_pose[:3, :3] @ vector
    local = joint_pose[:3, :3].T @ vector
    clean = tuple(0.0 if abs(v) < 1e-12 else float(v) for v in local)
    return (clean[0], clean[1], clean[2])


def _dynamics(file: str, axis_el: etree._Element) -> Dynamics | None:
    el = axis_el.find("dynamics")
    if el is None:
        return None
    dynamics = Dynamics(src=loc(file, el))
    for key in ("damping", "friction", "spring_reference", "spring_stiffness"):
        found = el.find(key)
        if found is not None:
            setattr(dynamics, key, number(file, found))
    return dynamics


def _mimic(frames: Frames, node: Node, el: etree._Element) -> Mimic:
    file = node.file
    leader = el.get("joint")
    if not leader:
        raise ParseError("<mimic> needs joint=", loc=loc(file, el))
    name = frames.resolve(leader, node.scope, el, "mimic joint")
    values = {}
    for key, default in (("multiplier", 1.0), ("offset", 0.0), ("reference", 0.0)):
        found = el.find(key)
        values[key] = number(file, found) if found is not None else default
    offset = values["offset"] - values["multiplier"] * values["reference"]
    return Mimic(name, values["multiplier"], offset, src=loc(file, el))


def _two_axes(frames: Frames, node: Node, base: Joint, joint_pose: Mat, findings: Findings) -> list[Joint]:
    """A universal joint as two revolutes, through a massless link at the joint's frame."""
    el, file = node.element, node.file
    findings.warn(
        "sdf-universal-joint",
        f"a {el.get('type')} joint has no IR form: it becomes two revolute joints ({node.name}_1, {node.name}_2) "
        f"through a massless link {node.name}_cross; every target keeps its motion, but that link gets each "
        "engine's mass for a massless body (MuJoCo 0.001 kg; PhysX 1 kg without colliders)",
        element=f"joint {node.name!r}",
        loc=loc(file, el),
        stage=STAGE,
    )
    middle = f"{node.name}_cross"
    first = Joint(f"{node.name}_1", JointType.REVOLUTE, base.parent, middle, origin=base.origin, src=base.src)
    second = Joint(f"{node.name}_2", JointType.REVOLUTE, middle, base.child, src=base.src)
    _axis_into(frames, node, first, el.find("axis"), joint_pose, findings)
    axis2 = el.find("axis2")
    _axis_into(frames, node, second, axis2, joint_pose, findings)
    if axis2 is None:
        second.axis = (0.0, 1.0, 0.0) if first.axis != (0.0, 1.0, 0.0) else (1.0, 0.0, 0.0)
    return [first, second]
