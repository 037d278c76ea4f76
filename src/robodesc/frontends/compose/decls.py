"""Declarations read from a composition file, before they go to the builder.

They are plain values in SI, so that templates can be renamed and mirrored without knowing the
file's units, and then fed to :class:`~robodesc.frontends.compose.builder.RobotBuilder` in one place.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from robodesc.frontends.compose.builder import Frame, Part, RobotBuilder
from robodesc.ir.contact import Contact
from robodesc.ir.diagnostics import Findings, SourceLoc
from robodesc.ir.geometry import Inertia, Mesh, Pose, Vec3
from robodesc.ir.inertia import from_tensor, tensor
from robodesc.ir.model import CameraSpec, JointType, RaySpec, SafetyController
from robodesc.ir.transforms import matrix_to_rpy, rpy_to_matrix


@dataclass(slots=True)
class ActuatorDecl:
    type: str | None = "transmission_interface/SimpleTransmission"
    interface: str | None = None
    reduction: float | None = None
    name: str | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class LinkDecl:
    name: str
    parts: list[Part] = field(default_factory=list)
    mass: float | None = None
    density: float | None = None
    inertia: Inertia | None = None
    com: Pose | None = None
    pose: Pose | None = None
    frame: Frame = "parent"
    element: str | None = None
    src: SourceLoc | None = None
    contact: Contact | None = None


@dataclass(slots=True)
class JointDecl:
    name: str
    type: JointType
    parent: str
    child: str
    origin: Pose | None = None
    frame: Frame = "parent"
    axis: Vec3 | None = None
    lower: float | None = None
    upper: float | None = None
    effort: float | None = None
    velocity: float | None = None
    damping: float | None = None
    friction: float | None = None
    mimic: str | None = None
    multiplier: float | None = None
    offset: float | None = None
    armature: float | None = None
    safety: SafetyController | None = None
    actuator: ActuatorDecl | None = None
    src: SourceLoc | None = None
    limit_src: SourceLoc | None = None


@dataclass(slots=True)
class LoopDecl:
    name: str
    type: str
    link1: str
    link2: str
    origin1: Pose | None = None
    origin2: Pose | None = None
    frame: Frame = "parent"
    axis: Vec3 | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class FrameDecl:
    name: str
    parent: str
    pose: Pose | None = None
    frame: Frame = "parent"
    src: SourceLoc | None = None


@dataclass(slots=True)
class SensorDecl:
    name: str
    type: str
    parent: str
    pose: Pose | None = None
    frame: Frame = "parent"
    update_rate: float | None = None
    topic: str | None = None
    noise: float | None = None
    camera: CameraSpec | None = None
    ray: RaySpec | None = None
    isaac_sim_config: str | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class Decls:
    links: list[LinkDecl] = field(default_factory=list)
    joints: list[JointDecl] = field(default_factory=list)
    loops: list[LoopDecl] = field(default_factory=list)
    frames: list[FrameDecl] = field(default_factory=list)
    sensors: list[SensorDecl] = field(default_factory=list)

    def extend(self, other: Decls) -> None:
        self.links += other.links
        self.joints += other.joints
        self.loops += other.loops
        self.frames += other.frames
        self.sensors += other.sensors


def apply(decls: Decls, builder: RobotBuilder) -> None:
    """Declare everything on ``builder`` (names are checked there)."""
    for ln in decls.links:
        builder.link(
            ln.name,
            *ln.parts,
            mass=ln.mass,
            density=ln.density,
            inertia=ln.inertia,
            com=ln.com,
            pose=ln.pose,
            frame=ln.frame,
            element=ln.element,
            src=ln.src,
            contact=ln.contact,
        )
    for j in decls.joints:
        builder.joint(
            j.name,
            j.type,
            j.parent,
            j.child,
            origin=j.origin,
            frame=j.frame,
            axis=j.axis,
            lower=j.lower,
            upper=j.upper,
            effort=j.effort,
            velocity=j.velocity,
            damping=j.damping,
            friction=j.friction,
            mimic=j.mimic,
            multiplier=j.multiplier,
            offset=j.offset,
            armature=j.armature,
            safety=j.safety,
            src=j.src,
            limit_src=j.limit_src,
        )
        if j.actuator is not None:
            a = j.actuator
            builder.actuator(j.name, type=a.type, interface=a.interface, reduction=a.reduction, name=a.name, src=a.src)
    for lp in decls.loops:
        builder.loop_joint(
            lp.name,
            lp.link1,
            lp.link2,
            type=lp.type,
            origin1=lp.origin1,
            origin2=lp.origin2,
            frame=lp.frame,
            axis=lp.axis,
            src=lp.src,
        )
    for fr in decls.frames:
        builder.frame(fr.name, fr.parent, fr.pose, frame=fr.frame, src=fr.src)
    for s in decls.sensors:
        builder.sensor(
            s.name,
            s.type,
            s.parent,
            pose=s.pose,
            frame=s.frame,
            update_rate=s.update_rate,
            topic=s.topic,
            noise=s.noise,
            camera=s.camera,
            ray=s.ray,
            isaac_sim_config=s.isaac_sim_config,
            src=s.src,
        )


# ---- template instances -----------------------------------------------------------------
def renamed(decls: Decls, prefix: str, suffix: str) -> Decls:
    """A copy with every name the declarations define wrapped in ``prefix``/``suffix``.

    References to names defined elsewhere (the robot's ``base`` a leg attaches to) are kept.
    """
    out = copy.deepcopy(decls)
    links = {ln.name for ln in out.links}
    joints = {j.name for j in out.joints}

    def lk(name: str) -> str:
        return f"{prefix}{name}{suffix}" if name in links else name

    def jn(name: str) -> str:
        return f"{prefix}{name}{suffix}" if name in joints else name

    for ln in out.links:
        ln.name = lk(ln.name)
    for j in out.joints:
        j.name, j.parent, j.child = jn(j.name), lk(j.parent), lk(j.child)
        if j.mimic is not None:
            j.mimic = jn(j.mimic)
        if j.actuator is not None and j.actuator.name is not None:
            j.actuator.name = f"{prefix}{j.actuator.name}{suffix}"
    for lp in out.loops:
        lp.name, lp.link1, lp.link2 = f"{prefix}{lp.name}{suffix}", lk(lp.link1), lk(lp.link2)
    for fr in out.frames:
        fr.name, fr.parent = f"{prefix}{fr.name}{suffix}", lk(fr.parent)
    for s in out.sensors:
        s.name, s.parent = f"{prefix}{s.name}{suffix}", lk(s.parent)
    return out


_MIRROR_AXES = {"x": 0, "y": 1, "z": 2}


def mirrored(decls: Decls, plane_normal: str, findings: Findings, element: str, loc: SourceLoc | None) -> Decls:
    """A copy reflected through the plane normal to ``plane_normal`` ("y" mirrors left ↔ right).

    Positions flip that coordinate; rotations are conjugated (R → M R M); a rotation axis is a
    pseudovector (a → −M a) so that the same joint angle gives the mirror-image motion; a prismatic
    axis is a plain vector (a → M a); inertia tensors become M I M. Meshes cannot be mirrored
    without a negative scale, which consumers handle badly: they are kept and reported.
    """
    m = np.eye(3)
    m[_MIRROR_AXES[plane_normal], _MIRROR_AXES[plane_normal]] = -1.0
    out = copy.deepcopy(decls)

    def pose(p: Pose | None) -> Pose | None:
        if p is None:
            return None
        xyz = m @ np.asarray(p.xyz, dtype=float)
        rot = m @ rpy_to_matrix(p.rpy) @ m
        rpy = matrix_to_rpy(rot)
        return Pose(xyz=_vec(xyz), rpy=(_c(rpy[0]), _c(rpy[1]), _c(rpy[2])), src=p.src)

    def vec(a: Vec3 | None, pseudo: bool) -> Vec3 | None:
        if a is None:
            return None
        v = m @ np.asarray(a, dtype=float)
        return _vec(-v if pseudo else v)

    for ln in out.links:
        ln.pose, ln.com = pose(ln.pose), pose(ln.com)
        if ln.inertia is not None:
            mirrored_tensor = from_tensor(m @ tensor(ln.inertia) @ m)
            mirrored_tensor.src = ln.inertia.src
            ln.inertia = mirrored_tensor
        for part in ln.parts:
            part.origin = pose(
                part.origin
                if isinstance(part.origin, Pose) or part.origin is None
                else Pose(xyz=_vec(np.asarray(part.origin, dtype=float)))
            )
            if isinstance(part.geometry, Mesh):
                findings.warn(
                    "mirror-mesh",
                    f"mesh {part.geometry.uri!r} of link {ln.name!r} is placed mirrored but its shape is not "
                    "mirrored (that needs a negative scale); supply a mirrored mesh",
                    element=element,
                    loc=loc,
                    stage="compose",
                )
    for j in out.joints:
        j.origin = pose(j.origin)
        # URDF's default axis is +X; mirroring must act on it even when it was not written.
        axis = j.axis if j.axis is not None else (1.0, 0.0, 0.0) if j.type.dof > 0 else None
        j.axis = vec(axis, pseudo=j.type is not JointType.PRISMATIC)
    for lp in out.loops:
        lp.origin1, lp.origin2 = pose(lp.origin1), pose(lp.origin2)
        lp.axis = vec(lp.axis, pseudo=lp.type != "prismatic")
    for fr in out.frames:
        fr.pose = pose(fr.pose)
    for s in out.sensors:
        s.pose = pose(s.pose)
    return out


def _c(v: float) -> float:
    return round(float(v), 12) + 0.0


def _vec(v: NDArray[np.float64]) -> Vec3:
    return (_c(v[0]), _c(v[1]), _c(v[2]))
