"""Build a robot from parts in a few readable lines; the YAML and ``.holo`` readers lower to this too.

>>> from robodesc.frontends.compose.builder import RobotBuilder
>>> from robodesc.frontends.compose.shapes import box, cylinder
>>> from robodesc.frontends.compose.units import deg
>>> b = RobotBuilder("arm")
>>> b.link("base", box(0.2, 0.2, 0.1), mass=5.0, color="#333")
>>> b.link("upper", cylinder(0.03, 0.4), mass=1.0, pose=(0, 0, 0.25), frame="world")
>>> b.joint("shoulder", "revolute", "base", "upper", axis="z", limits=deg(-90, 90), effort=10, velocity=2)
>>> robot = b.build()
>>> robot.joint("shoulder").origin.xyz
(0.0, 0.0, 0.25)

Poses are given either in the parent frame (the default: a link's pose is its parent joint's origin)
or in the composition (world) frame (``frame="world"``); the builder derives every joint origin from
them. Inertia tensors are kept when given and left ``None`` otherwise: the geometric-inertia pass
fills them from the parts' shapes and the mass.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from robodesc.frontends.compose.colors import ColorError, color_hex, parse_color
from robodesc.frontends.compose.meshes import resolve_mesh
from robodesc.frontends.compose.shapes import mesh_volume, volume
from robodesc.frontends.compose.units import ANGLE_UNITS, LENGTH_UNITS, Range
from robodesc.frontends.options import LoadOptions
from robodesc.frontends.packages import PackageResolver
from robodesc.ir.contact import Contact
from robodesc.ir.diagnostics import BrokenReferenceError, Findings, ParseError, SourceLoc
from robodesc.ir.geometry import RGBA, Geometry, Inertia, Inertial, Material, Mesh, Pose, Vec3
from robodesc.ir.model import (
    CameraSpec,
    Collision,
    Dynamics,
    FixedFrame,
    Joint,
    JointType,
    Limit,
    Link,
    LoopFrame,
    LoopJoint,
    Mimic,
    RaySpec,
    Robot,
    SafetyController,
    Sensor,
    SensorType,
    Transmission,
    TransmissionActuator,
    TransmissionJoint,
    Visual,
)
from robodesc.ir.principal import inertia_problem
from robodesc.ir.transforms import Mat, matrix_pose, pose_matrix
from robodesc.ir.verify import check, value_problems

STAGE = "compose"

Frame = Literal["parent", "world"]
PoseLike = Pose | Sequence[float]
AxisLike = str | Sequence[float]
ColorLike = str | Sequence[float]

JOINT_TYPES: dict[str, JointType] = {
    "revolute": JointType.REVOLUTE,
    "hinge": JointType.REVOLUTE,
    "continuous": JointType.CONTINUOUS,
    "prismatic": JointType.PRISMATIC,
    "slider": JointType.PRISMATIC,
    "fixed": JointType.FIXED,
    "floating": JointType.FLOATING,
    "free": JointType.FLOATING,
    "planar": JointType.PLANAR,
    "spherical": JointType.SPHERICAL,
    "ball": JointType.SPHERICAL,
}

SENSOR_TYPES: dict[str, SensorType] = {
    "camera": SensorType.CAMERA,
    "depth": SensorType.DEPTH,
    "depth_camera": SensorType.DEPTH,
    "lidar": SensorType.RAY,
    "ray": SensorType.RAY,
    "imu": SensorType.IMU,
    "force_torque": SensorType.FORCE_TORQUE,
    "contact": SensorType.CONTACT,
    "gps": SensorType.GPS,
}

AXES: dict[str, Vec3] = {
    "x": (1.0, 0.0, 0.0),
    "y": (0.0, 1.0, 0.0),
    "z": (0.0, 0.0, 1.0),
    "-x": (-1.0, 0.0, 0.0),
    "-y": (0.0, -1.0, 0.0),
    "-z": (0.0, 0.0, -1.0),
}


def pose(xyz: Sequence[float] = (0.0, 0.0, 0.0), rpy: Sequence[float] = (0.0, 0.0, 0.0), unit: str = "rad") -> Pose:
    """A pose from a translation (m) and fixed-axis roll-pitch-yaw in ``unit`` ("rad" or "deg")."""
    k = ANGLE_UNITS[unit]
    return Pose(xyz=_vec3(xyz), rpy=(rpy[0] * k, rpy[1] * k, rpy[2] * k))


def axis_vector(axis: AxisLike) -> Vec3:
    """``"z"``, ``"-y"`` or three numbers."""
    if isinstance(axis, str):
        try:
            return AXES[axis.strip().lower()]
        except KeyError:
            raise ValueError(f"unknown axis {axis!r} (x, y, z, -x, -y, -z or three numbers)") from None
    return _vec3(axis)


@dataclass(slots=True)
class Part:
    """One shape of a link: drawn (``visual``), collided with (``collision``), or both.

    ``origin`` is the shape's pose in the link frame. ``mass`` or ``density`` (kg/m³) here, or a
    ``mass`` on the link, gives the link its mass.
    """

    geometry: Geometry
    origin: PoseLike | None = None
    color: ColorLike | None = None
    material: str | None = None
    visual: bool = True
    collision: bool = True
    mass: float | None = None
    density: float | None = None
    name: str | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class _LinkSpec:
    name: str
    parts: list[Part]
    mass: float | None
    density: float | None
    inertia: Inertia | None
    com: Pose | None
    pose: Pose | None
    frame: Frame
    color: ColorLike | None
    material: str | None
    element: str
    src: SourceLoc | None
    display_name: str | None
    contact: Contact | None = None


@dataclass(slots=True)
class _JointSpec:
    joint: Joint
    origin: Pose | None
    frame: Frame


@dataclass(slots=True)
class _Placed:
    """Something placed on a link: a loop-joint side, a frame or a sensor, in the parent or world frame."""

    link: str
    pose: Pose | None
    frame: Frame


@dataclass(slots=True)
class _Actuator:
    joint: str
    name: str | None
    type: str | None
    interface: str | None
    reduction: float | None
    src: SourceLoc | None


@dataclass
class RobotBuilder:
    """Collects links, joints, frames, sensors and actuators, then :meth:`build` makes the IR.

    ``source_file`` anchors relative mesh paths (its folder) and is recorded on the robot;
    ``options`` gives the package map and the missing-mesh policy; ``findings`` collects what the
    builder inferred or changed.
    """

    name: str
    source_file: str | None = None
    options: LoadOptions = field(default_factory=LoadOptions)
    findings: Findings = field(default_factory=Findings)
    src: SourceLoc | None = None
    fixed_base: bool | None = None
    display_name: str | None = None
    _links: dict[str, _LinkSpec] = field(default_factory=dict, init=False)
    _joints: dict[str, _JointSpec] = field(default_factory=dict, init=False)
    _loops: dict[str, tuple[LoopJoint, _Placed, _Placed]] = field(default_factory=dict, init=False)
    _frames: dict[str, tuple[FixedFrame, _Placed]] = field(default_factory=dict, init=False)
    _sensors: dict[str, tuple[Sensor, _Placed]] = field(default_factory=dict, init=False)
    _actuators: list[_Actuator] = field(default_factory=list, init=False)

    # ---- declaring --------------------------------------------------------------------------
    def link(
        self,
        name: str,
        *parts: Part | Geometry,
        mass: float | None = None,
        density: float | None = None,
        inertia: Inertia | Sequence[float] | None = None,
        com: PoseLike | None = None,
        pose: PoseLike | None = None,
        frame: Frame = "parent",
        color: ColorLike | None = None,
        material: str | None = None,
        element: str | None = None,
        src: SourceLoc | None = None,
        display_name: str | None = None,
        contact: Contact | None = None,
    ) -> None:
        """Declare a link made of ``parts``.

        ``pose`` places the link frame: in its parent link's frame (``frame="parent"``, the same as
        giving the parent joint an origin) or in the composition frame (``frame="world"``).
        ``inertia`` is the tensor about the centre of mass (``Inertia`` or ``(ixx, iyy, izz[, ixy,
        ixz, iyz])``); ``com`` its frame in the link frame (default: the centroid of the parts).
        ``element`` is how messages name the link (``"object 'Arm'"``). ``contact``: the surface
        parameters of its colliders (friction, restitution, stiffness ...; docs/contact.md).
        """
        label = element or f"link {name!r}"
        self._unique(self._links, name, "link", label, src)
        if mass is not None and density is not None:
            raise ParseError("give mass or density, not both", element=label, loc=src)
        tensor: Inertia | None
        if inertia is None or isinstance(inertia, Inertia):
            tensor = inertia
        else:
            vals = [float(v) for v in inertia]
            if len(vals) not in (3, 6):
                raise ParseError("inertia needs 3 or 6 numbers (ixx iyy izz [ixy ixz iyz])", element=label, loc=src)
            vals += [0.0] * (6 - len(vals))
            tensor = Inertia(vals[0], vals[1], vals[2], vals[3], vals[4], vals[5], src=src)
        if tensor is not None:
            problem = inertia_problem(tensor)
            if problem is not None:
                raise ParseError(f"invalid inertia tensor: {problem}", element=label, loc=tensor.src or src)
        part_list = [p if isinstance(p, Part) else Part(p) for p in parts]
        self._links[name] = _LinkSpec(
            name=name,
            parts=part_list,
            mass=mass,
            density=density,
            inertia=tensor,
            com=_pose(com),
            pose=_pose(pose),
            frame=_frame(frame, label, src),
            color=color,
            material=material,
            element=label,
            src=src,
            display_name=display_name,
            contact=contact,
        )

    def joint(
        self,
        name: str,
        type: str | JointType,
        parent: str,
        child: str,
        *,
        origin: PoseLike | None = None,
        frame: Frame = "parent",
        axis: AxisLike | None = None,
        limits: Range | None = None,
        lower: float | None = None,
        upper: float | None = None,
        unit: str = "rad",
        effort: float | None = None,
        velocity: float | None = None,
        damping: float | None = None,
        friction: float | None = None,
        mimic: str | None = None,
        multiplier: float | None = None,
        offset: float | None = None,
        armature: float | None = None,
        safety: SafetyController | None = None,
        src: SourceLoc | None = None,
        limit_src: SourceLoc | None = None,
        display_name: str | None = None,
    ) -> None:
        """Declare a joint ``parent`` → ``child``.

        ``limits=deg(-90, 90)`` or ``lower=-90, upper=90, unit="deg"``; ``unit`` ("rad", "deg", "m",
        "cm", "mm") applies to ``lower``, ``upper`` and the mimic ``offset``. ``velocity`` is SI
        (rad/s or m/s), ``effort`` N·m or N. ``origin`` places the joint frame in the parent link
        (``frame="parent"``) or in the composition (``frame="world"``); without it the origin comes
        from the links' poses. ``mimic`` names the leader joint.
        """
        label = f"joint {name!r}"
        self._unique(self._joints, name, "joint", label, src)
        jtype = joint_type(type, label, src)
        k = _unit_factor(unit, jtype, label, src)
        if limits is not None and (lower is not None or upper is not None):
            raise ParseError("give limits=... or lower/upper, not both", element=label, loc=src)
        lo = limits.lower if limits is not None else (None if lower is None else lower * k)
        hi = limits.upper if limits is not None else (None if upper is None else upper * k)
        limit = None
        if any(v is not None for v in (lo, hi, effort, velocity)):
            limit = Limit(lower=lo, upper=hi, effort=_opt(effort), velocity=_opt(velocity), src=limit_src or src)
        dynamics = None
        if damping is not None or friction is not None:
            dynamics = Dynamics(damping=_opt(damping), friction=_opt(friction), src=src)
        mim = None
        if mimic is not None:
            mim = Mimic(
                joint=mimic, multiplier=_opt(multiplier), offset=None if offset is None else offset * k, src=src
            )
        ax = None
        if axis is not None:
            try:
                ax = axis_vector(axis)
            except ValueError as exc:
                raise ParseError(str(exc), element=label, loc=src) from None
            if not any(ax):
                raise ParseError("axis is the zero vector", element=label, loc=src)
        joint = Joint(
            name=name,
            type=jtype,
            parent=parent,
            child=child,
            axis=ax,
            limit=limit,
            dynamics=dynamics,
            mimic=mim,
            safety_controller=safety,
            armature=_opt(armature),
            display_name=display_name,
            src=src,
        )
        self._joints[name] = _JointSpec(joint, _pose(origin), _frame(frame, label, src))

    def loop_joint(
        self,
        name: str,
        link1: str,
        link2: str,
        *,
        type: str = "spherical",
        origin1: PoseLike | None = None,
        origin2: PoseLike | None = None,
        frame: Frame = "parent",
        axis: AxisLike | None = None,
        src: SourceLoc | None = None,
    ) -> None:
        """A joint that closes a loop between two links of the tree.

        ``origin1``/``origin2`` are the joint frame on each link (in that link's frame, or both in
        the composition frame with ``frame="world"``).
        """
        label = f"loop_joint {name!r}"
        self._unique(self._loops, name, "loop_joint", label, src)
        if type not in JOINT_TYPES or JOINT_TYPES[type] in (JointType.FLOATING, JointType.PLANAR):
            raise ParseError(f"unknown loop joint type {type!r}", element=label, loc=src)
        ax = None if axis is None else axis_vector(axis)
        loop = LoopJoint(
            name=name,
            type=JOINT_TYPES[type].value,
            link1=LoopFrame(link1, src=src),
            link2=LoopFrame(link2, src=src),
            axis=ax,
            src=src,
        )
        fr = _frame(frame, label, src)
        self._loops[name] = (loop, _Placed(link1, _pose(origin1), fr), _Placed(link2, _pose(origin2), fr))

    def frame(
        self,
        name: str,
        parent: str,
        pose: PoseLike | None = None,
        *,
        frame: Frame = "parent",
        src: SourceLoc | None = None,
    ) -> None:
        """A massless named frame on ``parent`` (a tool centre point, a sensor mount)."""
        label = f"fixed_frame {name!r}"
        self._unique(self._frames, name, "fixed_frame", label, src)
        self._frames[name] = (
            FixedFrame(name, parent, src=src),
            _Placed(parent, _pose(pose), _frame(frame, label, src)),
        )

    def sensor(
        self,
        name: str,
        type: str | SensorType,
        parent: str,
        *,
        pose: PoseLike | None = None,
        frame: Frame = "parent",
        update_rate: float | None = None,
        topic: str | None = None,
        noise: float | None = None,
        camera: CameraSpec | None = None,
        ray: RaySpec | None = None,
        isaac_sim_config: str | None = None,
        src: SourceLoc | None = None,
    ) -> None:
        """A sensor riding on link ``parent``; ``type`` is camera, depth, lidar (= ray), imu, force_torque,
        contact or gps."""
        label = f"sensor {name!r}"
        self._unique(self._sensors, name, "sensor", label, src)
        if isinstance(type, SensorType):
            stype = type
        elif type in SENSOR_TYPES:
            stype = SENSOR_TYPES[type]
        else:
            raise ParseError(f"unknown sensor type {type!r} (one of {', '.join(SENSOR_TYPES)})", element=label, loc=src)
        sensor = Sensor(
            name=name,
            type=stype,
            parent=parent,
            update_rate=_opt(update_rate),
            topic=topic,
            noise=_opt(noise),
            camera=camera,
            ray=ray,
            isaac_sim_config=isaac_sim_config,
            src=src,
        )
        self._sensors[name] = (sensor, _Placed(parent, _pose(pose), _frame(frame, label, src)))

    def actuator(
        self,
        joint: str,
        *,
        type: str | None = "transmission_interface/SimpleTransmission",
        interface: str | None = None,
        reduction: float | None = None,
        name: str | None = None,
        src: SourceLoc | None = None,
    ) -> None:
        """A motor on ``joint``, written as a transmission (``name`` defaults to ``<joint>_transmission``)."""
        self._actuators.append(_Actuator(joint, name, type, interface, _opt(reduction), src))

    def has_link(self, name: str) -> bool:
        return name in self._links

    def has_joint(self, name: str) -> bool:
        return name in self._joints

    # ---- building ---------------------------------------------------------------------------
    def build(self) -> Robot:
        """Check references and the tree, place everything, resolve meshes, verify; return the IR."""
        self._check_references()
        parent_of = self._check_tree()
        world, local = self._world_poses(parent_of)
        robot = Robot(
            name=self.name,
            display_name=self.display_name,
            src=self.src,
            source_file=self.source_file,
            fixed_base=self.fixed_base,
        )
        roots = [n for n in self._links if n not in parent_of]
        if len(roots) == 1 and not _is_identity(world[roots[0]]):
            robot.placement = _clean_pose(matrix_pose(world[roots[0]]))
        resolver = PackageResolver(explicit=dict(self.options.package_paths), input_file=self.source_file)
        base_dir = os.path.dirname(os.path.abspath(self.source_file)) if self.source_file else None
        for spec in self._links.values():
            robot.links.append(self._make_link(spec, resolver, base_dir))
        for jspec in self._joints.values():
            joint = jspec.joint
            if joint.child in local:
                # Given in the parent frame: keep the author's numbers exactly.
                given = local[joint.child]
                joint.origin = None if given.is_identity() else Pose(xyz=given.xyz, rpy=given.rpy, src=given.src)
            else:
                rel = np.linalg.inv(world[joint.parent]) @ world[joint.child]
                joint.origin = None if _is_identity(rel) else _clean_pose(matrix_pose(rel))
            robot.joints.append(joint)
        for loop, side1, side2 in self._loops.values():
            loop.link1.origin = self._local(side1, world)
            loop.link2.origin = self._local(side2, world)
            robot.loop_joints.append(loop)
        for fixed, placed in self._frames.values():
            fixed.origin = self._local(placed, world)
            robot.fixed_frames.append(fixed)
        for sensor, placed in self._sensors.values():
            sensor.origin = self._local(placed, world)
            robot.sensors.append(sensor)
        robot.transmissions.extend(self._transmissions())
        for finding in check(robot):
            self.findings.items.append(finding)
        return robot

    # ---- internals --------------------------------------------------------------------------
    def _unique(self, table: Mapping[str, object], name: str, kind: str, label: str, src: SourceLoc | None) -> None:
        if not isinstance(name, str) or not name:
            raise ParseError(f"{kind} needs a non-empty name", element=label, loc=src)
        if name in table:
            first = table[name]
            first_src = _src_of(first)
            where = f" (first at {first_src})" if first_src is not None else ""
            raise ParseError(f"duplicate {kind} name {name!r}{where}", element=label, loc=src)

    def _check_references(self) -> None:
        links = self._links
        for spec in self._joints.values():
            j = spec.joint
            label = f"joint {j.name!r}"
            for role, target in (("parent", j.parent), ("child", j.child)):
                if target not in links:
                    raise BrokenReferenceError(
                        f"{role} link {target!r} is not defined{_suggest(target, links)}", element=label, loc=j.src
                    )
            if j.parent == j.child:
                raise ParseError(f"joint connects link {j.parent!r} to itself", element=label, loc=j.src)
            if j.mimic is not None and j.mimic.joint not in self._joints:
                raise BrokenReferenceError(
                    f"mimics joint {j.mimic.joint!r}, which is not defined{_suggest(j.mimic.joint, self._joints)}",
                    element=label,
                    loc=j.mimic.src or j.src,
                )
        placed: list[tuple[str, _Placed, SourceLoc | None]] = []
        for loop, s1, s2 in self._loops.values():
            placed += [(f"loop_joint {loop.name!r}", s1, loop.src), (f"loop_joint {loop.name!r}", s2, loop.src)]
        placed += [(f"fixed_frame {f.name!r}", p, f.src) for f, p in self._frames.values()]
        placed += [(f"sensor {s.name!r}", p, s.src) for s, p in self._sensors.values()]
        for label, p, src in placed:
            if p.link not in links:
                raise BrokenReferenceError(
                    f"link {p.link!r} is not defined{_suggest(p.link, links)}", element=label, loc=src
                )
        for fname, (fixed, _) in self._frames.items():
            if fname in links:
                raise ParseError("a frame may not share a link's name", element=f"fixed_frame {fname!r}", loc=fixed.src)
        for act in self._actuators:
            if act.joint not in self._joints:
                raise BrokenReferenceError(
                    f"joint {act.joint!r} is not defined{_suggest(act.joint, self._joints)}",
                    element=f"actuator on {act.joint!r}",
                    loc=act.src,
                )

    def _check_tree(self) -> dict[str, str]:
        if not self._links:
            raise ParseError("the composition has no links", element=f"robot {self.name!r}", loc=self.src)
        parent_of: dict[str, str] = {}
        by_child: dict[str, Joint] = {}
        for spec in self._joints.values():
            j = spec.joint
            if j.child in by_child:
                first = by_child[j.child]
                raise ParseError(
                    f"link {j.child!r} already has parent joint {first.name!r} ({first.src}); "
                    "close a loop with a loop joint instead",
                    element=f"joint {j.name!r}",
                    loc=j.src,
                )
            by_child[j.child] = j
            parent_of[j.child] = j.parent
        for start in self._links:
            seen = [start]
            cur = start
            while cur in parent_of:
                cur = parent_of[cur]
                if cur == start:
                    order = list(reversed(seen))  # parent before child
                    chain = " -> ".join([*order, order[0]])
                    joint = by_child[start]
                    raise ParseError(f"joints form a cycle: {chain}", element=f"joint {joint.name!r}", loc=joint.src)
                if cur in seen:
                    break
                seen.append(cur)
        roots = [n for n in self._links if n not in parent_of]
        if len(roots) > 1:
            second = self._links[roots[1]]
            raise ParseError(
                f"{len(roots)} links have no parent joint ({', '.join(map(repr, roots[:6]))}); "
                "connect each to the robot with a joint",
                element=second.element,
                loc=second.src,
            )
        return parent_of

    def _world_poses(self, parent_of: dict[str, str]) -> tuple[dict[str, Mat], dict[str, Pose]]:
        """Every link's pose in the composition frame, and the origins given in the parent frame."""
        joint_of = {s.joint.child: s for s in self._joints.values()}
        out: dict[str, Mat] = {}
        local: dict[str, Pose] = {}

        def world(name: str) -> Mat:
            if name in out:
                return out[name]
            spec = self._links[name]
            jspec = joint_of.get(name)
            if jspec is None:
                result = pose_matrix(spec.pose)
            elif jspec.origin is not None:
                if spec.pose is not None:
                    raise ParseError(
                        f"both joint {jspec.joint.name!r} (origin) and the link (pose) place this link; give one",
                        element=spec.element,
                        loc=spec.src,
                    )
                parent = world(jspec.joint.parent)
                if jspec.frame == "world":
                    result = pose_matrix(jspec.origin)
                else:
                    local[name] = jspec.origin
                    result = parent @ pose_matrix(jspec.origin)
            elif spec.frame == "world":
                result = pose_matrix(spec.pose)
            else:
                local[name] = spec.pose or Pose()
                result = world(jspec.joint.parent) @ pose_matrix(spec.pose)
            out[name] = result
            return result

        for name in self._links:
            world(name)
        return out, local

    def _local(self, placed: _Placed, world: dict[str, Mat]) -> Pose | None:
        if placed.pose is None:
            return None
        if placed.frame == "parent":
            return placed.pose
        rel = np.linalg.inv(world[placed.link]) @ pose_matrix(placed.pose)
        return None if _is_identity(rel) else _clean_pose(matrix_pose(rel))

    def _make_link(self, spec: _LinkSpec, resolver: PackageResolver, base_dir: str | None) -> Link:
        link = Link(name=spec.name, display_name=spec.display_name, src=spec.src, contact=spec.contact)
        kept: list[tuple[Part, Geometry, Pose | None]] = []
        for part in spec.parts:
            geom = part.geometry
            origin = _pose(part.origin)
            if isinstance(geom, Mesh):
                resolved = resolve_mesh(
                    geom,
                    element=spec.element,
                    loc=part.src or geom.src or spec.src,
                    base_dir=base_dir,
                    resolver=resolver,
                    policy=self.options.missing_mesh,
                    findings=self.findings,
                )
                if resolved is None:
                    continue
                geom = resolved
            kept.append((part, geom, origin))
            material = self._material(part, spec)
            if part.visual:
                link.visuals.append(
                    Visual(geometry=geom, origin=origin, name=part.name, material=material, src=part.src)
                )
            if part.collision:
                link.collisions.append(Collision(geometry=geom, origin=origin, name=part.name, src=part.src))
        link.inertial = self._inertial(spec, kept)
        return link

    def _material(self, part: Part, spec: _LinkSpec) -> Material | None:
        color = part.color if part.color is not None else spec.color
        name = part.material or spec.material
        if color is None:
            if name is not None:
                self.findings.info(
                    "material-without-color",
                    f"material {name!r} has no colour; robodesc does not know its look, so it is not written",
                    element=spec.element,
                    loc=part.src or spec.src,
                    stage=STAGE,
                )
            return None
        try:
            rgba: RGBA = parse_color(color)
        except (ColorError, TypeError, ValueError) as exc:
            raise ParseError(str(exc), element=spec.element, loc=part.src or spec.src) from None
        # One name per (material, colour) keeps names unique: Isaac merges materials by name.
        return Material(name=f"{name or 'color'}_{color_hex(rgba)}", color=rgba, src=part.src or spec.src)

    def _inertial(self, spec: _LinkSpec, parts: list[tuple[Part, Geometry, Pose | None]]) -> Inertial | None:
        label = spec.element
        part_masses: list[float | None] = []
        volumes: list[float | None] = []
        for part, geom, _ in parts:
            problems = value_problems(geom)  # sizes beyond the verifier's bounds overflow volume()
            if problems:
                raise ParseError(
                    f"{type(geom).__name__.lower()} {problems[0]}", element=label, loc=part.src or spec.src
                )
            vol = volume(geom)
            if vol is None and isinstance(geom, Mesh) and geom.path is not None:
                raw = mesh_volume(geom.path)
                if raw is not None:
                    s = geom.scale or (1.0, 1.0, 1.0)
                    vol = raw * abs(s[0] * s[1] * s[2])
            volumes.append(vol)
            if part.mass is not None and part.density is not None:
                raise ParseError("a part takes mass or density, not both", element=label, loc=part.src or spec.src)
            density = part.density if part.density is not None else spec.density
            if part.mass is not None:
                part_masses.append(part.mass)
            elif density is not None:
                if vol is None:
                    raise ParseError(
                        "density needs a part whose volume is known (a primitive or a watertight mesh file)",
                        element=label,
                        loc=part.src or spec.src,
                    )
                part_masses.append(density * vol)
            else:
                part_masses.append(None)
        mass: float | None = spec.mass
        if mass is None and any(m is not None for m in part_masses):
            if any(m is None for m in part_masses) and spec.density is None:
                self.findings.warn(
                    "partial-mass",
                    "some parts have no mass or density; they count as massless",
                    element=label,
                    loc=spec.src,
                    stage=STAGE,
                )
            mass = sum(m for m in part_masses if m is not None)
        if mass is None:
            if spec.inertia is not None:
                raise ParseError("an inertia tensor needs a mass", element=label, loc=spec.src)
            return None
        com = spec.com if spec.com is not None else self._centroid(parts, part_masses, volumes)
        return Inertial(mass=float(mass), origin=com, inertia=spec.inertia, src=spec.src)

    @staticmethod
    def _centroid(
        parts: list[tuple[Part, Geometry, Pose | None]], masses: list[float | None], volumes: list[float | None]
    ) -> Pose | None:
        if not parts:
            return None
        if len(parts) == 1:
            # One part: its frame is the natural inertial frame (a rotated box keeps its principal axes).
            return parts[0][2]
        if all(m is not None for m in masses) and sum(m for m in masses if m is not None) > 0:
            weights = [float(m) for m in masses if m is not None]
        elif all(v is not None for v in volumes):
            weights = [float(v) for v in volumes if v is not None]
        else:
            weights = [1.0] * len(parts)
        total = sum(weights)
        centre = [0.0, 0.0, 0.0]
        for w, (_, _, origin) in zip(weights, parts, strict=True):
            xyz = origin.xyz if origin is not None else (0.0, 0.0, 0.0)
            for i in range(3):
                centre[i] += w * xyz[i] / total
        c = (_clean(centre[0]), _clean(centre[1]), _clean(centre[2]))
        return None if c == (0.0, 0.0, 0.0) else Pose(xyz=c)

    def _transmissions(self) -> list[Transmission]:
        out: list[Transmission] = []
        used: set[str] = set()
        for act in self._actuators:
            name = act.name or f"{act.joint}_transmission"
            if name in used:
                raise ParseError(
                    f"duplicate transmission name {name!r}", element=f"actuator on {act.joint!r}", loc=act.src
                )
            used.add(name)
            interfaces = [act.interface] if act.interface else []
            out.append(
                Transmission(
                    name=name,
                    type=act.type,
                    joints=[TransmissionJoint(act.joint, list(interfaces), src=act.src)],
                    actuators=[
                        TransmissionActuator(
                            f"{act.joint}_actuator", list(interfaces), mechanical_reduction=act.reduction, src=act.src
                        )
                    ],
                    src=act.src,
                )
            )
        return out


# ---- helpers ------------------------------------------------------------------------------
def joint_type(value: str | JointType, label: str, src: SourceLoc | None) -> JointType:
    if isinstance(value, JointType):
        return value
    key = str(value).strip().lower()
    if key not in JOINT_TYPES:
        raise ParseError(
            f"unknown joint type {value!r} (one of {', '.join(JOINT_TYPES)}){_suggest(key, JOINT_TYPES)}",
            element=label,
            loc=src,
        )
    return JOINT_TYPES[key]


def _unit_factor(unit: str, jtype: JointType, label: str, src: SourceLoc | None) -> float:
    if jtype is JointType.PRISMATIC:
        if unit == "rad":  # the default: a prismatic joint's numbers are metres
            return 1.0
        if unit not in LENGTH_UNITS:
            raise ParseError(
                f"a prismatic joint's unit is a length ({', '.join(LENGTH_UNITS)})", element=label, loc=src
            )
        return LENGTH_UNITS[unit]
    if unit not in ANGLE_UNITS:
        raise ParseError(f"an angular joint's unit is an angle ({', '.join(ANGLE_UNITS)})", element=label, loc=src)
    return ANGLE_UNITS[unit]


def _frame(frame: str, label: str, src: SourceLoc | None) -> Frame:
    if frame == "parent":
        return "parent"
    if frame == "world":
        return "world"
    raise ParseError(f"frame must be 'parent' or 'world', not {frame!r}", element=label, loc=src)


def _pose(value: PoseLike | None) -> Pose | None:
    if value is None or isinstance(value, Pose):
        return value
    return Pose(xyz=_vec3(value))


def _vec3(value: Sequence[float]) -> Vec3:
    if len(value) != 3:
        raise ValueError(f"expected 3 numbers, got {len(value)}")
    return (float(value[0]), float(value[1]), float(value[2]))


def _opt(value: float | None) -> float | None:
    return None if value is None else float(value)


def _clean(value: float) -> float:
    # Poses derived from world positions carry subtraction noise (0.35 - 0.1); 12 decimals is far
    # below any physical meaning and keeps emitted numbers and golden files stable.
    return round(value, 12) + 0.0


def _clean_pose(p: Pose) -> Pose:
    return Pose(
        xyz=(_clean(p.xyz[0]), _clean(p.xyz[1]), _clean(p.xyz[2])),
        rpy=(_clean(p.rpy[0]), _clean(p.rpy[1]), _clean(p.rpy[2])),
    )


def _is_identity(m: Mat) -> bool:
    return bool(np.allclose(m, np.eye(4), atol=1e-12, rtol=0.0))


def _src_of(obj: object) -> SourceLoc | None:
    if isinstance(obj, _LinkSpec):
        return obj.src
    if isinstance(obj, _JointSpec):
        return obj.joint.src
    if isinstance(obj, tuple) and obj:
        src = getattr(obj[0], "src", None)
        return src if isinstance(src, SourceLoc) else None
    return None


def _suggest(name: str, known: object) -> str:
    import difflib

    candidates = [str(k) for k in known]  # type: ignore[attr-defined]
    close = difflib.get_close_matches(name, candidates, n=1)
    return f"; did you mean {close[0]!r}?" if close else ""


__all__ = ["Part", "RobotBuilder", "axis_vector", "joint_type", "pose"]
