"""Bodies (one per link, named as the link), their inertials, geoms and joints.

A body's frame is its link's frame: ``pos``/``quat`` of a child body are the URDF joint origin, and
the joint sits at the body origin with the URDF axis, so no axis is re-expressed.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np

from robodesc.emit.common.approximation import mode_for
from robodesc.emit.common.decomposition import Decomposer, decomposer
from robodesc.emit.common.numbers import fmt_vec
from robodesc.emit.mjcf.contact_params import apply_contact
from robodesc.emit.mjcf.context import MjcfContext, num, set_pose
from robodesc.emit.mjcf.meshes import MeshAssets
from robodesc.ir.diagnostics import UnsupportedError
from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Inertial, Material, Mesh, Pose, Sphere
from robodesc.ir.inertia import rotate, tensor
from robodesc.ir.model import Joint, JointType, Link
from robodesc.ir.rigid import Frame, pose_frame, rpy_rotation
from robodesc.validation.options import TOKEN_MASS

# A moving body needs mass and inertia above mjMINVAL; a massless one gets these (said in a warning).
STUB_MASS = TOKEN_MASS  # what validation then takes for a token mass, not a changed one
STUB_INERTIA = 1e-6
# The smallest principal moment written, relative to the largest (see _body_frame_inertia).
SMALLEST_MOMENT = 1e-6


class BodyWriter:
    def __init__(self, ctx: MjcfContext) -> None:
        self.ctx = ctx
        self.meshes = MeshAssets(ctx)
        self.children = ctx.robot.child_joints()
        self.materials = {m.name: m for m in ctx.robot.materials}
        self._decomposer: Decomposer | None = None

    def worldbody(self, root_pose: Frame, floating: bool) -> ET.Element:
        world = ET.Element("worldbody")
        root = self.ctx.robot.root
        if root.name == "world":
            # The URDF convention for "welded (or jointed) to the ground": MuJoCo's own world body.
            self._geoms(world, root)
            for joint in self.children.get(root.name, []):
                self._child(world, joint)
            return world
        body = ET.SubElement(world, "body", name=root.name)
        set_pose(body, root_pose)
        if floating:
            ET.SubElement(body, "freejoint", name=root.name)
            self.ctx.qpos_joints.append((root.name, "free", None))
        self._fill(body, root, moving=floating)
        return world

    def _fill(self, body: ET.Element, link: Link, moving: bool) -> None:
        """The body's own content, then every body below it, depth first in the links' order: a
        loop over an explicit stack, since a chain may be hundreds of bodies deep (one Python
        frame per level would reach the recursion limit before MuJoCo's own depth limit)."""
        todo: list[tuple[ET.Element | None, Joint | None, ET.Element, Link, bool]] = [(None, None, body, link, moving)]
        while todo:
            parent, joint, body_el, link_, moving_ = todo.pop()
            if joint is not None and parent is not None:
                body_el = ET.SubElement(parent, "body", name=link_.name)
                set_pose(body_el, joint.origin)
                self._joint(body_el, joint)
            self.ctx.bodies[link_.name] = body_el
            self._inertial(body_el, link_, moving_)
            self._geoms(body_el, link_)
            for child in reversed(self.children.get(link_.name, [])):
                # Only a body with a joint of its own must have mass in MuJoCo: a welded one without
                # any is part of its parent's (a stub there would add to the robot's total).
                moved = child.type is not JointType.FIXED
                todo.append((body_el, child, body_el, self.ctx.robot.link(child.child), moved))

    def _child(self, parent: ET.Element, joint: Joint) -> None:
        link = self.ctx.robot.link(joint.child)
        body = ET.SubElement(parent, "body", name=link.name)
        set_pose(body, joint.origin)
        self._joint(body, joint)
        self._fill(body, link, moving=joint.type is not JointType.FIXED)

    # ---- joints -------------------------------------------------------------------------------
    def _joint(self, body: ET.Element, joint: Joint) -> None:
        t = joint.type
        if t is JointType.FIXED:
            return  # a body without a joint is welded to its parent
        if t in (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC):
            el = ET.SubElement(body, "joint", name=joint.name)
            if t is JointType.PRISMATIC:
                el.set("type", "slide")
            el.set("axis", fmt_vec(joint.effective_axis))
            self._range(el, joint)
            self._dynamics(el, joint)
            self.ctx.qpos_joints.append((joint.name, "slide" if t is JointType.PRISMATIC else "hinge", joint.name))
        elif t is JointType.SPHERICAL:
            el = ET.SubElement(body, "joint", name=joint.name, type="ball")
            self._dynamics(el, joint)
            self.ctx.qpos_joints.append((joint.name, "ball", joint.name))
        elif t is JointType.PLANAR:
            self._planar(body, joint)
        elif t is JointType.FLOATING:
            # MuJoCo allows a free joint only on a body whose parent is the world.
            raise UnsupportedError(
                "a floating joint below the root has no MuJoCo equivalent (a free joint must be on a "
                "top-level body); make it the root or give it another type",
                element=f"joint {joint.name!r}",
                loc=joint.src,
            )

    def _planar(self, body: ET.Element, joint: Joint) -> None:
        """URDF planar: translation in the plane normal to the axis and rotation about it, as two
        slides and a hinge named ``<joint>_TX``, ``<joint>_TY``, ``<joint>_RZ``, as MuJoCo's own URDF
        loader names them (validation compares them so)."""
        n = np.asarray(joint.effective_axis, dtype=float)
        n = n / np.linalg.norm(n)
        helper = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        u = np.cross(n, helper)
        u /= np.linalg.norm(u)
        v = np.cross(n, u)
        for suffix, kind, axis in (("_TX", "slide", u), ("_TY", "slide", v), ("_RZ", "hinge", n)):
            el = ET.SubElement(body, "joint", name=joint.name + suffix, type=kind, axis=fmt_vec(float(a) for a in axis))
            self._dynamics(el, joint)
            self.ctx.qpos_joints.append((joint.name + suffix, kind, None))
        self.ctx.info(
            "mjcf-planar",
            f"planar joint written as two slides and a hinge ({joint.name}_TX, {joint.name}_TY, {joint.name}_RZ)",
            f"joint {joint.name!r}",
            joint.src,
        )

    def _range(self, el: ET.Element, joint: Joint) -> None:
        limit = joint.limit
        if joint.type is JointType.CONTINUOUS:
            return  # autolimits: no range, unlimited
        if limit is None or limit.lower is None or limit.upper is None:
            self.ctx.warn(
                "mjcf-no-limit", "joint has no lower/upper limit: written unlimited", f"joint {joint.name!r}", joint.src
            )
            return
        el.set("range", f"{num(limit.lower)} {num(limit.upper)}")

    def _dynamics(self, el: ET.Element, joint: Joint) -> None:
        dyn = joint.dynamics
        if dyn is not None:
            if dyn.damping:
                el.set("damping", num(dyn.damping))
            if dyn.friction:
                el.set("frictionloss", num(dyn.friction))
            if dyn.spring_stiffness:
                el.set("stiffness", num(dyn.spring_stiffness))
                if dyn.spring_reference:
                    el.set("springref", num(dyn.spring_reference))
        if joint.armature:
            el.set("armature", num(joint.armature))

    # ---- mass -----------------------------------------------------------------------------------
    def _inertial(self, body: ET.Element, link: Link, moving: bool) -> None:
        inertial = link.inertial
        mass = inertial.mass if inertial is not None else None
        if mass is None or not mass > 0:
            if moving and not self._welded_mass(link):
                self.ctx.warn(
                    "mjcf-massless-body",
                    f"a moving body without mass: MuJoCo refuses it, so it gets {STUB_MASS:g} kg and a "
                    f"{STUB_INERTIA:g} kg·m² diagonal inertia",
                    f"link {link.name!r}",
                    link.src,
                )
                ET.SubElement(
                    body, "inertial", pos="0 0 0", mass=num(STUB_MASS), diaginertia=fmt_vec([STUB_INERTIA] * 3)
                )
            elif body.find("joint") is not None or body.find("freejoint") is not None:
                # Mass carried by welded children: MuJoCo takes it as the moving body's own, but
                # MJCF with inertiafromgeom="false" asks every jointed body for an <inertial>, and
                # readers that hold to that (Newton's add_mjcf) refuse the body without one.
                ET.SubElement(body, "inertial", pos="0 0 0", mass="0", diaginertia="0 0 0")
            return
        assert inertial is not None
        el = ET.SubElement(body, "inertial")
        origin = inertial.origin
        el.set("pos", fmt_vec(origin.xyz if origin is not None else (0.0, 0.0, 0.0)))
        el.set("mass", num(mass))
        if inertial.inertia is None:
            return
        values, raised = _body_frame_inertia(inertial)
        if raised:
            self.ctx.warn(
                "mjcf-inertia-floor",
                f"principal moment {raised[0]:.3g} kg·m² is below {SMALLEST_MOMENT:g} of the largest "
                f"({raised[1]:.3g}); MuJoCo refuses such a tensor, so every moment was raised by {raised[2]:.3g}",
                f"link {link.name!r}",
                inertial.src,
            )
        el.set("fullinertia", fmt_vec(values))

    def _welded_mass(self, link: Link) -> bool:
        """MuJoCo counts the mass of bodies welded below a moving body as its own."""
        for joint in self.children.get(link.name, []):
            if joint.type is not JointType.FIXED:
                continue
            child = self.ctx.robot.link(joint.child)
            m = child.inertial.mass if child.inertial is not None else None
            if (m is not None and m > 0) or self._welded_mass(child):
                return True
        return False

    # ---- geometry ---------------------------------------------------------------------------------
    def _geoms(self, body: ET.Element, link: Link) -> None:
        label = f"link {link.name!r}"
        for i, collision in enumerate(link.collisions):
            given = link.collision_contact(collision)
            # A foot gets menagerie's foot class only where the source says nothing of its contact:
            # Talos's Gazebo soles (kd 1: damping ratio 0.03) with priority over the floor tipped it over.
            foot = self.ctx.options.feet.get(link.name) == i and given is None
            for geom in self._collision_geoms(link, collision.geometry, f"{label} collision {i}"):
                geom.set("class", "foot" if foot else "collision")
                _place(geom, collision.origin)
                apply_contact(self.ctx, geom, link, given, f"{label} collision {i}")
                body.append(geom)
        for i, visual in enumerate(link.visuals):
            if isinstance(visual.geometry, Mesh):
                parts = self.meshes.visual_parts(visual.geometry)
                if parts is not None:
                    for name, rgba in parts:
                        piece = ET.SubElement(body, "geom", type="mesh", mesh=name)
                        piece.set("class", "visual")
                        set_pose(piece, visual.origin)
                        colour = rgba if rgba is not None else self._rgba(visual.material)
                        if colour is not None:
                            piece.set("rgba", fmt_vec(colour))
                    continue
            el = self._geom(visual.geometry, f"{label} visual {i}", collider=False)
            if el is None:
                continue
            el.set("class", "visual")
            _place(el, visual.origin)
            rgba = self._rgba(visual.material)
            if rgba is not None:
                el.set("rgba", fmt_vec(rgba))
            body.append(el)

    def _collision_geoms(self, link: Link, geometry: Geometry, element: str) -> list[ET.Element]:
        """The geoms of one collision: one, or one per convex part under convexDecomposition."""
        if isinstance(geometry, Mesh) and mode_for(self.ctx.options.collision_approximation, link.name) == (
            "convexDecomposition"
        ):
            if self._decomposer is None:
                self._decomposer = decomposer(self.ctx.options, self.ctx.out_dir)
                # The parts it writes are listed with the target's other files.
                self._decomposer.written = self.ctx.written

            def warn(code: str, message: str) -> None:
                self.ctx.warn(code, message, element, geometry.src)

            def info(code: str, message: str) -> None:
                self.ctx.info(code, message, element, geometry.src)

            parts = self._decomposer.parts(geometry, warn, info)
            if parts is not None:
                return [
                    ET.Element("geom", type="mesh", mesh=self.meshes.part_asset(part.rel, geometry)) for part in parts
                ]
        el = self._geom(geometry, element, collider=True)
        return [] if el is None else [el]

    def _rgba(self, material: Material | None) -> tuple[float, float, float, float] | None:
        if material is None:
            return None
        if material.color is None and material.name in self.materials:
            material = self.materials[material.name]
        return material.color

    def _geom(self, geometry: Geometry, element: str, collider: bool) -> ET.Element | None:
        el = ET.Element("geom")
        if isinstance(geometry, Box):
            el.set("type", "box")
            el.set("size", fmt_vec(s / 2 for s in geometry.size))
        elif isinstance(geometry, Sphere):
            el.set("type", "sphere")
            el.set("size", num(geometry.radius))
        elif isinstance(geometry, Cylinder):
            el.set("type", "cylinder")
            el.set("size", f"{num(geometry.radius)} {num(geometry.length / 2)}")
        elif isinstance(geometry, Capsule) and geometry.length == 0:
            # The same shape exactly; MuJoCo refuses a capsule whose half length is 0.
            el.set("type", "sphere")
            el.set("size", num(geometry.radius))
        elif isinstance(geometry, Capsule):
            el.set("type", "capsule")
            el.set("size", f"{num(geometry.radius)} {num(geometry.length / 2)}")
        elif isinstance(geometry, Mesh):
            flat = self.meshes.flat_box(geometry, element)
            if flat is not None:
                el.set("type", "box")
                el.set("size", fmt_vec(flat[0]))
                if any(flat[1]):
                    el.set("robodesc-offset", fmt_vec(flat[1]))  # composed with the origin by the caller
                return el
            name = self.meshes.asset(geometry, element, collider)
            if name is None:
                return None
            el.set("type", "mesh")
            el.set("mesh", name)
        else:  # pragma: no cover - the IR has no other shape
            return None
        return el


def _place(el: ET.Element, origin: Pose | None) -> None:
    """The geom's pose: its origin, then the centre of a box standing in for a flat mesh."""
    offset = el.attrib.pop("robodesc-offset", None)
    if offset is None:
        set_pose(el, origin)
        return
    x, y, z = (float(v) for v in offset.split())
    set_pose(el, pose_frame(origin) @ Frame(translation=(x, y, z)))


def _body_frame_inertia(inertial: Inertial) -> tuple[tuple[float, ...], tuple[float, float, float] | None]:
    """The tensor in the body's axes: MJCF's ``fullinertia`` takes no ``quat``, so a rotated inertial
    frame is turned into the body frame (exactly the source's numbers when it is not rotated).

    A principal moment below SMALLEST_MOMENT of the largest (a rod's axial moment written as 1e-15)
    makes MuJoCo's eigen-decomposition give a non-positive value, which it refuses: every moment is
    then raised by the gap, keeping the axes. Returns the six numbers and (smallest, largest, added)
    when that happened."""
    assert inertial.inertia is not None
    i = inertial.inertia
    origin = inertial.origin
    m = tensor(i)
    if origin is not None and origin.rpy != (0.0, 0.0, 0.0):
        m = rotate(m, np.asarray(rpy_rotation(origin.rpy)))
    raised = None
    eig = np.linalg.eigvalsh(m)
    if eig[2] > 0 and eig[0] < SMALLEST_MOMENT * eig[2]:
        delta = float(SMALLEST_MOMENT * eig[2] - eig[0])
        m = m + delta * np.eye(3)
        raised = (float(eig[0]), float(eig[2]), delta)
    elif origin is None or origin.rpy == (0.0, 0.0, 0.0):
        return (i.ixx, i.iyy, i.izz, i.ixy, i.ixz, i.iyz), None
    return tuple(float(x) for x in (m[0, 0], m[1, 1], m[2, 2], m[0, 1], m[0, 2], m[1, 2])), raised


def bounding_radius(geometry: Geometry) -> float:
    """A radius that contains the shape around its origin (0 for meshes, whose size is not read)."""
    if isinstance(geometry, Box):
        return 0.5 * math.sqrt(sum(s * s for s in geometry.size))
    if isinstance(geometry, Sphere):
        return geometry.radius
    if isinstance(geometry, Cylinder):
        return math.hypot(geometry.radius, geometry.length / 2)
    if isinstance(geometry, Capsule):
        return geometry.radius + geometry.length / 2
    return 0.0
