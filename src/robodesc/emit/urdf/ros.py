"""URDF for ROS: what urdfdom (robot_state_publisher, MoveIt, ``check_urdf``, Pinocchio) loads.

urdfdom reads URDF 1.0 and nothing else. The IR can hold three things it refuses:

- a ``<capsule>`` (pybullet's and Isaac's extension): "Unknown geometry type 'capsule'";
- a ``spherical`` joint (pybullet's and the compositions' ball joint): "Joint type not recognized";
- a revolute/prismatic ``<limit>`` without ``effort`` or ``velocity``: "joint limit: no effort".

The third is handled by the URDF emitter itself for every URDF it writes
(``UrdfOptions.default_effort``/``default_velocity``, see ``writer.py``). The first two are lowered
here, on a copy of the robot, for the URDF written for ROS (``--ros2``, the Isaac folder's URDF,
``-t urdf`` from a composition or from an MJCF or SDF model):

- a capsule becomes a cylinder of the same radius and length plus a sphere at each end (the same
  solid); ``UrdfOptions.capsules = "keep"`` keeps ``<capsule>`` instead (pybullet, Isaac and MuJoCo
  read it, urdfdom does not);
- a spherical joint ``J`` becomes three revolute joints ``J_x``, ``J_y``, ``J_z`` (axes x, y, z of
  the joint frame, in that order) through two near-massless links ``J_x_link`` and ``J_y_link``
  (``BALL_LINK_MASS``: MuJoCo and Gazebo refuse a moving link without mass). The joints are
  ``continuous`` unless the ball joint had lower/upper limits, which each of the three then gets.

Each change is a warning. :func:`ros_equivalent` is deterministic, so validation applies it to the
IR to compare the URDF that was written with the robot it stands for.
"""

from __future__ import annotations

import copy
import re
from collections.abc import Sequence
from dataclasses import replace
from typing import TypeVar

from robodesc.ir.diagnostics import Findings
from robodesc.ir.geometry import Capsule, Cylinder, Inertia, Inertial, Pose, Sphere
from robodesc.ir.model import Collision, Joint, JointType, Link, Robot, Visual
from robodesc.ir.rigid import rpy_rotation

STAGE = "emit:urdf"
# The mass (kg) and principal moments (kg·m²) of the two links a spherical joint is split through.
BALL_LINK_MASS = 1e-6
BALL_LINK_INERTIA = 1e-9
_AXES = (("x", (1.0, 0.0, 0.0)), ("y", (0.0, 1.0, 0.0)), ("z", (0.0, 0.0, 1.0)))
COMPOSITION_SUFFIXES = (".yaml", ".yml", ".holo", ".py")


URDF_SUFFIXES = (".urdf", ".xacro")
# How far into an ``.xml`` file its root element is looked for (comments and a licence header first).
_SNIFF_BYTES = 64 * 1024


def from_composition(robot: Robot) -> bool:
    """Whether the URDF is a new file, written for ROS, rather than a round trip of a URDF/xacro input:
    the robot was composed (YAML, ``.holo``, Python) or read from another format (MJCF, SDF). A
    menagerie model's URDF has no pybullet extensions to keep; its readers are ROS's (urdfdom,
    Pinocchio), which refuse ``<capsule>`` and spherical joints."""
    src = robot.source_file
    if src is None or src.lower().endswith(COMPOSITION_SUFFIXES):
        return True
    if src.lower().endswith(URDF_SUFFIXES):
        return False
    if not src.lower().endswith(".xml"):
        return True  # .sdf, .mjcf, model.config
    return not _urdf_root(src)


def _urdf_root(path: str) -> bool:
    """Whether an ``.xml`` file's root element is ``<robot>`` (URDF) rather than ``<mujoco>`` or
    ``<sdf>``; a file that cannot be read now counts as URDF (the round trip keeps what it had)."""
    try:
        with open(path, "rb") as handle:
            head = handle.read(_SNIFF_BYTES).decode("utf-8", "replace")
    except OSError:
        return True
    # The first element that is not a declaration, comment or processing instruction.
    body = re.sub(r"<\?.*?\?>|<!--.*?-->|<!DOCTYPE[^>]*>", "", head, flags=re.DOTALL)
    first = re.search(r"<\s*([A-Za-z_][\w.:-]*)", body)
    return first is None or first.group(1) == "robot"


def non_urdf_features(robot: Robot) -> tuple[list[str], list[str]]:
    """(links with a capsule, spherical joints): what urdfdom refuses."""
    capsules = [
        link.name
        for link in robot.links
        if any(isinstance(v.geometry, Capsule) for v in link.visuals)
        or any(isinstance(c.geometry, Capsule) for c in link.collisions)
    ]
    spherical = [j.name for j in robot.joints if j.type is JointType.SPHERICAL]
    return capsules, spherical


def _names(items: list[str]) -> str:
    shown = ", ".join(repr(n) for n in items[:5])
    return shown + (f" and {len(items) - 5} more" if len(items) > 5 else "")


def warn_round_trip(robot: Robot, findings: Findings) -> None:
    """``-t urdf`` of a URDF input keeps pybullet's extensions: say that ROS will not load it."""
    capsules, spherical = non_urdf_features(robot)
    what = []
    if capsules:
        what.append(f"<capsule> shapes (links {_names(capsules)})")
    if spherical:
        what.append(f"spherical joints ({_names(spherical)})")
    if what:
        findings.warn(
            "urdf-not-ros",
            f"kept the source's {' and '.join(what)}: pybullet, MuJoCo and Isaac Sim read them, ROS's urdfdom "
            "refuses them (--ros2 writes a URDF that ROS loads)",
            element=f"robot {robot.name!r}",
            stage=STAGE,
        )


def _unique(name: str, taken: set[str]) -> str:
    out, n = name, 1
    while out in taken:
        out = f"{name}_{n}"
        n += 1
    taken.add(out)
    return out


def _offset(pose: Pose | None, dz: float) -> Pose:
    base = pose or Pose()
    # dz along the pose's own z axis: the rotation's third column (pure Python: no numpy at emit time).
    shift = [row[2] * dz for row in rpy_rotation(base.rpy)]
    xyz = tuple(float(a + b) for a, b in zip(base.xyz, shift, strict=True))
    return Pose(xyz=xyz, rpy=base.rpy)  # type: ignore[arg-type]


ShapeT = TypeVar("ShapeT", Visual, Collision)


def _split_capsules(link: Link) -> int:
    visuals, n_visual = _split(link.visuals)
    collisions, n_collision = _split(link.collisions)
    link.visuals, link.collisions = visuals, collisions
    return n_visual + n_collision


def _split(shapes: Sequence[ShapeT]) -> tuple[list[ShapeT], int]:
    """Each capsule of ``shapes`` as a cylinder and a sphere at each end; the count of capsules."""
    out: list[ShapeT] = []
    count = 0
    for shape in shapes:
        c = shape.geometry
        if not isinstance(c, Capsule):
            out.append(shape)
            continue
        count += 1
        out.append(replace(shape, geometry=Cylinder(radius=c.radius, length=c.length, src=c.src)))
        for dz in (c.length / 2, -c.length / 2):
            out.append(replace(shape, geometry=Sphere(radius=c.radius, src=c.src), origin=_offset(shape.origin, dz)))
    return out, count


def _ball_link(name: str) -> Link:
    m = BALL_LINK_INERTIA
    return Link(name=name, inertial=Inertial(mass=BALL_LINK_MASS, inertia=Inertia(ixx=m, iyy=m, izz=m)))


def _split_ball(joint: Joint, taken_links: set[str], taken_joints: set[str]) -> tuple[list[Link], list[Joint]]:
    lim = joint.limit
    bounded = lim is not None and lim.lower is not None and lim.upper is not None
    kind = JointType.REVOLUTE if bounded else JointType.CONTINUOUS
    links = [_unique(f"{joint.name}_x_link", taken_links), _unique(f"{joint.name}_y_link", taken_links)]
    chain = [joint.parent, *links, joint.child]
    joints = []
    for i, (suffix, axis) in enumerate(_AXES):
        joints.append(
            Joint(
                name=_unique(f"{joint.name}_{suffix}", taken_joints),
                type=kind,
                parent=chain[i],
                child=chain[i + 1],
                origin=joint.origin if i == 0 else None,
                axis=axis,
                limit=copy.copy(lim) if bounded else None,
                dynamics=copy.copy(joint.dynamics),
                armature=joint.armature,
                src=joint.src,
            )
        )
    return [_ball_link(n) for n in links], joints


def ros_equivalent(robot: Robot, capsules: str = "split", findings: Findings | None = None) -> Robot:
    """A copy of ``robot`` that urdfdom loads (see the module docstring); ``robot`` is not touched."""
    out = copy.deepcopy(robot)
    sink = findings if findings is not None else Findings()
    if capsules == "split":
        split = {link.name: n for link in out.links if (n := _split_capsules(link))}
        if split:
            sink.warn(
                "urdf-capsule-split",
                f"{sum(split.values())} capsule(s) on links {_names(list(split))} written as a cylinder and two "
                "spheres (URDF 1.0 has no capsule; urdfdom refuses <capsule>)",
                element=f"robot {robot.name!r}",
                stage=STAGE,
            )
    else:
        kept, _ = non_urdf_features(out)
        if kept:
            sink.warn(
                "urdf-not-ros",
                f"<capsule> kept on links {_names(kept)} (capsules='keep'): pybullet, MuJoCo and Isaac Sim read it, "
                "urdfdom (ROS) refuses the file",
                element=f"robot {robot.name!r}",
                stage=STAGE,
            )
    balls = [j for j in out.joints if j.type is JointType.SPHERICAL]
    if balls:
        taken_links = {link.name for link in out.links}
        taken_joints = {j.name for j in out.joints}
        joints: list[Joint] = []
        for j in out.joints:
            if j.type is not JointType.SPHERICAL:
                joints.append(j)
                continue
            new_links, new_joints = _split_ball(j, taken_links, taken_joints)
            out.links.extend(new_links)
            joints.extend(new_joints)
        out.joints = joints
        sink.warn(
            "urdf-spherical-split",
            f"{len(balls)} spherical joint(s) ({_names([j.name for j in balls])}) written as three revolute joints "
            f"each (NAME_x, NAME_y, NAME_z about the joint frame's axes) through two links of {BALL_LINK_MASS:g} kg "
            "(URDF has no ball joint; urdfdom refuses type='spherical')",
            element=f"robot {robot.name!r}",
            stage=STAGE,
        )
    return out


__all__ = [
    "BALL_LINK_INERTIA",
    "BALL_LINK_MASS",
    "from_composition",
    "non_urdf_features",
    "ros_equivalent",
    "warn_round_trip",
]
