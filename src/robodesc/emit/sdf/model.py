"""IR robot → one articulated SDF ``<model>`` element.

Poses: by default each joint is posed relative to its parent link with the URDF origin and each
child link relative to its joint, so the source's numbers go through unchanged; with
``PoseFrames.MODEL`` links are posed in the model frame (forward kinematics at zero). Either way the
joint frame coincides with the child link frame at zero, which is URDF's joint frame, so the axis
is written ``expressed_in`` the child link. Links without ``<inertial>`` get an explicit zero
mass: SDF's default (1 kg, unit inertia) would invent a body.
"""

from __future__ import annotations

import math

from lxml import etree

from robodesc.emit.common.approximation import mode_for
from robodesc.emit.common.decomposition import Decomposer, PartFile, decomposer
from robodesc.emit.common.numbers import fmt, fmt_vec
from robodesc.emit.common.paths import file_reference, mesh_reference
from robodesc.emit.sdf.names import STAGE, Namespace
from robodesc.emit.sdf.options import PoseFrames, SdfFlavour, SdfOptions, version_at_least
from robodesc.emit.sdf.sensors import (
    HARMONIC_SYSTEMS,
    classic_ft_plugin,
    required_systems,
    sensor_element,
    system_plugin,
)
from robodesc.emit.sdf.surface import add_surface
from robodesc.ir.diagnostics import Findings
from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Inertial, Material, Mesh, Pose, Sphere
from robodesc.ir.model import Joint, JointType, Link, LoopJoint, Robot, Sensor, SensorType
from robodesc.ir.transforms import Mat, forward_kinematics

E = etree.SubElement

# SDF's convention for "no position limit" (its own default for revolute joints).
UNLIMITED = 1e16
# SDF 1.7's <specular> default is black; a little specular light keeps coloured meshes readable.
SPECULAR = (0.1, 0.1, 0.1, 1.0)
# The fixed joint that welds the root to the world when the base is fixed.
FIX_BASE_JOINT = "world_joint"
# Deeper trees are posed in the model frame: sdformat resolves a ``relative_to`` pose by walking the
# frame graph to the model frame, one walk per link, so relative poses cost depth² (Drake took 4.3 s
# to parse a 600-link chain posed relatively, 0.3 s posed in the model frame; 50,000 links: days).
RELATIVE_POSES_UP_TO = 256

_JOINT_TYPE = {
    JointType.FIXED: "fixed",
    JointType.REVOLUTE: "revolute",
    JointType.CONTINUOUS: "revolute",
    JointType.PRISMATIC: "prismatic",
    JointType.SPHERICAL: "ball",
}
_LOOP_TYPE = {"fixed": "fixed", "revolute": "revolute", "continuous": "revolute", "prismatic": "prismatic"}
_LOOP_TYPE.update({"spherical": "ball", "ball": "ball", "universal": "universal"})


def precise_pose(m: Mat) -> Pose:
    """Like ``matrix_pose``, but pitch from ``atan2``: ``asin`` loses ~1e-8 near ±90° pitch."""
    cp = math.hypot(float(m[0, 0]), float(m[1, 0]))
    pitch = math.atan2(-float(m[2, 0]), cp)
    if cp > 1e-12:
        roll = math.atan2(float(m[2, 1]), float(m[2, 2]))
        yaw = math.atan2(float(m[1, 0]), float(m[0, 0]))
    else:  # gimbal lock: put everything in yaw
        roll = 0.0
        yaw = math.atan2(-float(m[0, 1]), float(m[1, 1]))
    return Pose(xyz=(float(m[0, 3]), float(m[1, 3]), float(m[2, 3])), rpy=(roll, pitch, yaw))


def pose_text(pose: Pose) -> str:
    return fmt_vec((*pose.xyz, *pose.rpy))


class SdfModelEmitter:
    """One method per IR node, like :class:`robodesc.emit.urdf.UrdfEmitter`."""

    def __init__(self, robot: Robot, options: SdfOptions, findings: Findings, *, in_world: bool) -> None:
        self.robot = robot
        self.options = options
        self.findings = findings
        self.version = options.resolved_version()
        self.classic = options.flavour is SdfFlavour.CLASSIC
        self.in_world = in_world
        self.names = Namespace()
        self.materials = {m.name: m for m in robot.materials}
        self.fix_base_name = FIX_BASE_JOINT
        self._decomposer: Decomposer | None = None
        self.pose_frames = options.pose_frames

    # ---- the model -----------------------------------------------------------------------
    def model(
        self, parent: etree._Element | None, name: str, *, static: bool = False, pose: Pose | None = None
    ) -> etree._Element:
        """``name`` is the model's SDF name, already made valid and unique by the caller."""
        robot = self.robot
        el = etree.Element("model", name=name) if parent is None else E(parent, "model", name=name)
        if pose is not None:
            E(el, "pose").text = pose_text(pose)
        if static:
            E(el, "static").text = "true"
        self._claim_names()
        sdf_joint = {j.name for j in robot.joints if j.type in _JOINT_TYPE}
        parent_joint = robot.parent_joint()
        world_pose = None
        if self.pose_frames is PoseFrames.RELATIVE and (depth := robot.tree_depth()) > RELATIVE_POSES_UP_TO:
            self.pose_frames = PoseFrames.MODEL
            self.findings.info(
                "sdf-model-poses",
                f"the tree is {depth} joints deep: links are posed in the model frame (forward kinematics at "
                f"zero) instead of relative to their joints, which sdformat resolves in time that grows with "
                f"the square of the depth (relative poses up to {RELATIVE_POSES_UP_TO} deep)",
                element=f"robot {robot.name!r}",
                stage=STAGE,
            )
        if self.pose_frames is PoseFrames.MODEL:
            # Every joint at 0, mimic joints included: SDF's zero pose has no mimic offsets applied.
            world_pose = forward_kinematics(robot, {j.name: 0.0 for j in robot.joints})
        ft_by_joint = self._force_torque_sensors()
        for link in robot.links:
            link_el = self.link(el, link)
            pj = parent_joint.get(link.name)
            if world_pose is not None:
                if pj is not None:
                    _insert_pose(link_el, precise_pose(world_pose[link.name]), None)
            elif pj is not None and pj.name in sdf_joint:
                _insert_pose(link_el, None, self.names.get("joint", pj.name))
            elif pj is not None:
                _insert_pose(link_el, pj.origin, self.names.get("link", pj.parent))
        for joint in robot.joints:
            self.joint(el, joint, ft_by_joint.get(joint.name, []))
        if self.options.loop_joints:
            for loop in robot.loop_joints:
                self.loop_joint(el, loop)
        elif robot.loop_joints:
            self.findings.warn(
                "sdf-loop-dropped",
                f"{len(robot.loop_joints)} loop joint(s) not written (loop joints are off)",
                element=f"robot {robot.name!r}",
                stage=STAGE,
            )
        for frame in robot.fixed_frames:
            link_name = self.names.get("link", frame.parent)
            f = E(el, "frame", name=self.names.get("frame", frame.name), attached_to=link_name)
            _insert_pose(f, frame.origin, link_name)
        if self.options.fix_base:
            roots = robot.root_links()
            if roots:
                j = E(el, "joint", name=self.fix_base_name, type="fixed")
                E(j, "parent").text = "world"
                E(j, "child").text = self.names.get("link", roots[0].name)
        self._model_plugins(el)
        self._dropped_summary()
        return el

    def _claim_names(self) -> None:
        robot, f, ns = self.robot, self.findings, self.names
        for link in robot.links:
            ns.claim("link", link.name, f, loc=link.src)
        for joint in robot.joints:
            ns.claim("joint", joint.name, f, loc=joint.src)
        if self.options.loop_joints:
            for loop in robot.loop_joints:
                ns.claim("loop_joint", loop.name, f, loc=loop.src)
        for frame in robot.fixed_frames:
            ns.claim("frame", frame.name, f, loc=frame.src, label="fixed_frame")
        if self.options.fix_base:
            # Claimed last and kept apart, so the weld never shadows a real joint's mapping.
            self.fix_base_name = ns.claim("fix_base", FIX_BASE_JOINT, Findings())

    def _force_torque_sensors(self) -> dict[str, list[Sensor]]:
        """SDF puts force-torque sensors in a joint: the one named, else the one leading to the link."""
        parent_joint = self.robot.parent_joint()
        out: dict[str, list[Sensor]] = {}
        for sensor in self.robot.sensors:
            if sensor.type is not SensorType.FORCE_TORQUE:
                continue
            joint = sensor.parent_joint or (parent_joint[sensor.parent].name if sensor.parent in parent_joint else None)
            if joint is None:
                self.findings.warn(
                    "sdf-sensor-dropped",
                    "a force-torque sensor must sit in a joint, and its link is the root",
                    element=f"sensor {sensor.name!r}",
                    loc=sensor.src,
                    stage=STAGE,
                )
                continue
            out.setdefault(joint, []).append(sensor)
        return out

    # ---- links ---------------------------------------------------------------------------
    def link(self, parent: etree._Element, link: Link) -> etree._Element:
        el = E(parent, "link", name=self.names.get("link", link.name))
        self.inertial(el, link)
        local = Namespace()
        for i, visual in enumerate(link.visuals):
            v = E(el, "visual", name=local.claim("visual", visual.name or f"visual_{i}", self.findings, loc=visual.src))
            _insert_pose(v, visual.origin, None)
            self.geometry(v, visual.geometry, f"link {link.name!r} visual {i}")
            if visual.material is not None:
                self.material(v, visual.material)
        collisions: list[str] = []
        for i, collision in enumerate(link.collisions):
            cname = local.claim("collision", collision.name or f"collision_{i}", self.findings, loc=collision.src)
            label = f"link {link.name!r} collision {i}"
            geometry = collision.geometry
            parts = self._parts(link, geometry, label) if isinstance(geometry, Mesh) else None
            pieces: list[tuple[str, Geometry]] = [(cname, geometry)]
            if parts is not None:
                # One <collision> per convex part, each with the collision's pose and surface.
                pieces = [
                    (local.claim("collision", f"{cname}_part{k}", self.findings), _part_mesh(part))
                    for k, part in enumerate(parts)
                ]
            for name, shape in pieces:
                collisions.append(name)
                c = E(el, "collision", name=name)
                _insert_pose(c, collision.origin, None)
                self.geometry(c, shape, label, collider=mode_for(self.options.collision_approximation, link.name))
                add_surface(c, link.collision_contact(collision), self.findings, label)
        for sensor in self.robot.sensors:
            if sensor.parent != link.name or sensor.type is SensorType.FORCE_TORQUE:
                continue
            if sensor.type is SensorType.CONTACT and not collisions:
                self.findings.warn(
                    "sdf-sensor-dropped",
                    f"a contact sensor needs a collision on link {link.name!r}, which has none",
                    element=f"sensor {sensor.name!r}",
                    loc=sensor.src,
                    stage=STAGE,
                )
                continue
            sensor_element(
                el,
                self.robot,
                sensor,
                name=local.claim("sensor", sensor.name, self.findings, loc=sensor.src),
                link=self.names.get("link", link.name),
                flavour=self.options.flavour,
                version=self.version,
                contact_collisions=collisions,
            )
        return el

    def inertial(self, parent: etree._Element, link: Link) -> None:
        inertial = link.inertial or Inertial()
        el = E(parent, "inertial")
        if inertial.origin is not None and not inertial.origin.is_identity():
            E(el, "pose").text = pose_text(inertial.origin)
        if link.inertial is not None and inertial.mass is None:
            self.findings.warn(
                "sdf-zero-mass",
                "<inertial> has no mass; written as 0 (SDF's default would be 1 kg)",
                element=f"link {link.name!r}",
                loc=inertial.src or link.src,
                stage=STAGE,
            )
        E(el, "mass").text = fmt(inertial.mass or 0.0)
        if inertial.inertia is None and (inertial.mass or 0.0) > 0:
            self.findings.warn(
                "sdf-zero-inertia",
                "<inertial> has a mass but no tensor; written as zero (SDF's default would be unit inertia)",
                element=f"link {link.name!r}",
                loc=inertial.src or link.src,
                stage=STAGE,
            )
        i = inertial.inertia
        values = (i.ixx, i.ixy, i.ixz, i.iyy, i.iyz, i.izz) if i is not None else (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        t = E(el, "inertia")
        for tag, value in zip(("ixx", "ixy", "ixz", "iyy", "iyz", "izz"), values, strict=True):
            E(t, tag).text = fmt(value)

    def _parts(self, link: Link, mesh: Mesh, label: str) -> list[PartFile] | None:
        """The convex parts of a mesh collider under convexDecomposition (None: the mesh as given)."""
        if mode_for(self.options.collision_approximation, link.name) != "convexDecomposition":
            return None
        if self.options.out_dir is None:
            self.findings.warn(
                "sdf-decomposition-no-folder",
                "convexDecomposition writes its parts as files beside the SDF: give -o FILE.sdf; "
                "the mesh is written as given",
                element=label,
                loc=mesh.src,
                stage=STAGE,
            )
            return None
        if self._decomposer is None:
            self._decomposer = decomposer(self.options, self.options.out_dir)

        def warn(code: str, message: str) -> None:
            self.findings.warn(code, message, element=label, loc=mesh.src, stage=STAGE)

        def info(code: str, message: str) -> None:
            self.findings.info(code, message, element=label, loc=mesh.src, stage=STAGE)

        return self._decomposer.parts(mesh, warn, info)

    @property
    def written(self) -> dict[str, str]:
        """Files written beside the SDF (convex parts), by role."""
        return self._decomposer.written if self._decomposer is not None else {}

    def geometry(self, parent: etree._Element, geom: Geometry, label: str, collider: str | None = None) -> None:
        g = E(parent, "geometry")
        if isinstance(geom, Box):
            E(E(g, "box"), "size").text = fmt_vec(geom.size)
        elif isinstance(geom, Cylinder):
            c = E(g, "cylinder")
            E(c, "radius").text = fmt(geom.radius)
            E(c, "length").text = fmt(geom.length)
        elif isinstance(geom, Sphere):
            E(E(g, "sphere"), "radius").text = fmt(geom.radius)
        elif isinstance(geom, Capsule):
            if version_at_least(self.version, "1.9"):
                c = E(g, "capsule")
                E(c, "radius").text = fmt(geom.radius)
                E(c, "length").text = fmt(geom.length)
            else:
                self.findings.warn(
                    "sdf-capsule",
                    f"SDF {self.version} has no <capsule>; written as a cylinder of the full length",
                    element=label,
                    loc=geom.src,
                    stage=STAGE,
                )
                c = E(g, "cylinder")
                E(c, "radius").text = fmt(geom.radius)
                E(c, "length").text = fmt(geom.length + 2 * geom.radius)
        elif isinstance(geom, Mesh):
            m = E(g, "mesh")
            if collider in ("convexHull", "convexDecomposition") and version_at_least(self.version, "1.11"):
                # SDF 1.11 (Gazebo Harmonic) asks Gazebo for the hull; a convexDecomposition collider
                # here is a convex part, or the whole mesh when the decomposition fell back.
                m.set("optimization", "convex_hull")
            E(m, "uri").text = mesh_reference(geom, self.options.path_mode, self.options.out_dir)
            if geom.scale is not None:
                E(m, "scale").text = fmt_vec(geom.scale)

    def material(self, parent: etree._Element, material: Material) -> None:
        mat = self.materials.get(material.name, material) if material.is_reference() else material
        if mat.color is None and mat.texture is None:
            return
        el = E(parent, "material")
        if mat.color is not None:
            E(el, "ambient").text = fmt_vec(mat.color)
            E(el, "diffuse").text = fmt_vec(mat.color)
            E(el, "specular").text = fmt_vec(SPECULAR)
        if mat.texture is not None:
            ref = file_reference(mat.texture, mat.texture_path, None, self.options.path_mode, self.options.out_dir)
            E(E(E(el, "pbr"), "metal"), "albedo_map").text = ref

    # ---- joints --------------------------------------------------------------------------
    def joint(self, parent: etree._Element, joint: Joint, ft_sensors: list[Sensor]) -> None:
        label = f"joint {joint.name!r}"
        kind = _JOINT_TYPE.get(joint.type)
        if kind is None:
            self.findings.warn(
                "sdf-joint-dropped",
                f"SDF has no {joint.type.value} joint; link {joint.child!r} is written as a free body "
                "at its zero-position pose",
                element=label,
                loc=joint.src,
                stage=STAGE,
            )
            return
        name = self.names.get("joint", joint.name)
        el = E(parent, "joint", name=name, type=kind)
        child = self.names.get("link", joint.child)
        if self.pose_frames is PoseFrames.RELATIVE:
            _insert_pose(el, joint.origin, self.names.get("link", joint.parent))
        E(el, "parent").text = self.names.get("link", joint.parent)
        E(el, "child").text = child
        if joint.type.dof == 1:
            axis = E(el, "axis")
            E(axis, "xyz", expressed_in=child).text = fmt_vec(joint.effective_axis)
            self._limit(axis, joint)
            self._dynamics(axis, joint)
            self._mimic(axis, joint)
        elif joint.dynamics is not None and joint.type is JointType.SPHERICAL:
            self.findings.info(
                "sdf-dynamics-dropped",
                "ball joints take no <dynamics> in SDF",
                element=label,
                loc=joint.src,
                stage=STAGE,
            )
        for sensor in ft_sensors:
            sensor_element(
                el,
                self.robot,
                sensor,
                name=sensor.name,
                link=self.names.get("link", sensor.parent),
                flavour=self.options.flavour,
                version=self.version,
                contact_collisions=[],
            )

    def _limit(self, axis: etree._Element, joint: Joint) -> None:
        lim = joint.limit
        values: list[tuple[str, float]] = []
        if joint.type is JointType.CONTINUOUS:
            values += [("lower", -UNLIMITED), ("upper", UNLIMITED)]
        elif lim is not None:
            values += [(t, v) for t, v in (("lower", lim.lower), ("upper", lim.upper)) if v is not None]
        if lim is not None:
            values += [(t, v) for t, v in (("effort", lim.effort), ("velocity", lim.velocity)) if v is not None]
        if values:
            el = E(axis, "limit")
            for tag, value in values:
                E(el, tag).text = fmt(value)

    def _dynamics(self, axis: etree._Element, joint: Joint) -> None:
        dyn = joint.dynamics
        if dyn is None:
            return
        values = [
            (tag, getattr(dyn, tag))
            for tag in ("damping", "friction", "spring_reference", "spring_stiffness")
            if getattr(dyn, tag) is not None
        ]
        if values:
            el = E(axis, "dynamics")
            for tag, value in values:
                E(el, tag).text = fmt(value)

    def _mimic(self, axis: etree._Element, joint: Joint) -> None:
        mimic = joint.mimic
        if mimic is None:
            return
        if not version_at_least(self.version, "1.11"):
            self.findings.warn(
                "sdf-mimic-dropped",
                f"mimic of {mimic.joint!r} dropped: SDF {self.version} has no <mimic> (write SDF 1.11 to keep it)",
                element=f"joint {joint.name!r}",
                loc=mimic.src or joint.src,
                stage=STAGE,
            )
            return
        # SDF 1.11: follower = multiplier * (leader - reference) + offset; URDF has no reference.
        el = E(axis, "mimic", joint=self.names.get("joint", mimic.joint), axis="axis")
        E(el, "multiplier").text = fmt(mimic.multiplier if mimic.multiplier is not None else 1.0)
        E(el, "offset").text = fmt(mimic.offset if mimic.offset is not None else 0.0)
        E(el, "reference").text = "0"

    def loop_joint(self, parent: etree._Element, loop: LoopJoint) -> None:
        label = f"loop_joint {loop.name!r}"
        kind = _LOOP_TYPE.get(loop.type)
        if kind is None:
            self.findings.warn(
                "sdf-loop-dropped", f"SDF has no {loop.type!r} joint", element=label, loc=loop.src, stage=STAGE
            )
            return
        child = self.names.get("link", loop.link2.link)
        el = E(parent, "joint", name=self.names.get("loop_joint", loop.name), type=kind)
        _insert_pose(el, loop.link2.origin, child)
        E(el, "parent").text = self.names.get("link", loop.link1.link)
        E(el, "child").text = child
        if kind in ("revolute", "prismatic"):
            E(E(el, "axis"), "xyz").text = fmt_vec(loop.axis or (1.0, 0.0, 0.0))
        self.findings.warn(
            "sdf-loop-joint",
            f"closes a kinematic loop between {loop.link1.link!r} and {loop.link2.link!r}; Gazebo accepts it, "
            "tree-only consumers (Drake's MultibodyPlant) reject it. Its frame is the link2 side "
            "(the link1 origin is not kept)",
            element=label,
            loc=loop.src,
            stage=STAGE,
        )

    # ---- plugins and what SDF cannot say --------------------------------------------------
    def _model_plugins(self, el: etree._Element) -> None:
        robot = self.robot
        if self.classic:
            for sensor in robot.sensors:
                if sensor.type is SensorType.FORCE_TORQUE:
                    classic_ft_plugin(el, robot, sensor, self.names.get("link", sensor.parent))
            return
        if self.in_world:
            return
        for system in required_systems(robot.sensors):
            if system.world_only:
                kinds = sorted({s.type.value for s in robot.sensors if HARMONIC_SYSTEMS[s.type] is system})
                self.findings.info(
                    "sdf-world-plugin",
                    f"{', '.join(kinds)} sensors need the world to load {system.filename} "
                    f"({system.name}); it only works at world level (write --world to get it)",
                    element=f"robot {robot.name!r}",
                    stage=STAGE,
                )
            else:
                system_plugin(el, system)

    def _dropped_summary(self) -> None:
        robot = self.robot
        what: list[str] = []
        exts = (
            len(robot.extensions)
            + sum(len(x.extensions) for x in robot.links)
            + sum(len(x.extensions) for x in robot.joints)
        )
        if exts:
            what.append(f"{exts} kept extension element(s) (<gazebo> blocks ...)")
        if robot.transmissions:
            what.append(f"{len(robot.transmissions)} transmission(s)")
        if robot.ros2_controls:
            what.append(f"{len(robot.ros2_controls)} ros2_control block(s) (use --ros2)")
        for attr, text in (
            ("safety_controller", "safety controller(s)"),
            ("calibration", "calibration(s)"),
            ("armature", "armature value(s)"),
        ):
            n = sum(1 for j in robot.joints if getattr(j, attr) is not None)
            if n:
                what.append(f"{n} joint {text}")
        if what:
            self.findings.info(
                "sdf-not-written",
                "SDF has no place for: " + "; ".join(what),
                element=f"robot {robot.name!r}",
                stage=STAGE,
            )


def _part_mesh(part: PartFile) -> Mesh:
    """A convex part as the IR's mesh: its file beside the SDF, already scaled."""
    return Mesh(uri=part.rel, path=part.path)


def _insert_pose(el: etree._Element, pose: Pose | None, relative_to: str | None) -> None:
    """A ``<pose>`` as the element's first child (identity poses are left out unless anchored)."""
    if relative_to is None and (pose is None or pose.is_identity()):
        return
    p = etree.Element("pose")
    if relative_to is not None:
        p.set("relative_to", relative_to)
    if pose is not None and not pose.is_identity():
        p.text = pose_text(pose)
    el.insert(0, p)
