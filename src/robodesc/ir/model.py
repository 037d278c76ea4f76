"""Links, joints and the robot: the structure of the IR.

Conventions shared by every frontend, pass and emitter:
- SI units everywhere (m, kg, rad, N, N·m); emitters convert (USD wants degrees).
- ``None`` means "the input did not say"; a default is applied by whoever needs a value,
  never written into the IR silently.
- ``src`` records where a node came from; ``display_name`` keeps the original name after
  sanitization.
- ``extensions`` keeps unmodelled child elements verbatim, ``extra_attrs`` unmodelled attributes.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field

from robodesc.ir.contact import Contact
from robodesc.ir.diagnostics import SourceLoc
from robodesc.ir.geometry import Extension, Geometry, Inertial, Material, Pose, Vec3


@dataclass(slots=True)
class Visual:
    geometry: Geometry
    origin: Pose | None = None
    name: str | None = None
    material: Material | None = None
    src: SourceLoc | None = None
    extensions: list[Extension] = field(default_factory=list)


@dataclass(slots=True)
class Collision:
    geometry: Geometry
    origin: Pose | None = None
    name: str | None = None
    src: SourceLoc | None = None
    extensions: list[Extension] = field(default_factory=list)
    # This collider's own surface parameters (over its link's, ``Link.contact``).
    contact: Contact | None = None


@dataclass(slots=True)
class Link:
    name: str
    inertial: Inertial | None = None
    visuals: list[Visual] = field(default_factory=list)
    collisions: list[Collision] = field(default_factory=list)
    display_name: str | None = None
    src: SourceLoc | None = None
    extensions: list[Extension] = field(default_factory=list)
    extra_attrs: dict[str, str] = field(default_factory=dict)
    # Surface parameters of every collider of the link (Gazebo's per-link tags), and whether the
    # link collides with the robot's other links (Gazebo's selfCollide); None: not given.
    contact: Contact | None = None
    self_collide: bool | None = None

    def collision_contact(self, collision: Collision) -> Contact | None:
        """The surface parameters that apply to ``collision``: its own over the link's."""
        if collision.contact is None:
            return self.contact
        return collision.contact.merged_over(self.contact)


class JointType(enum.Enum):
    FIXED = "fixed"
    REVOLUTE = "revolute"
    CONTINUOUS = "continuous"
    PRISMATIC = "prismatic"
    FLOATING = "floating"
    PLANAR = "planar"
    # Not in URDF; compositions and SDF have them.
    SPHERICAL = "spherical"

    @property
    def dof(self) -> int:
        return _DOF[self]

    @property
    def is_angular(self) -> bool:
        return self in (JointType.REVOLUTE, JointType.CONTINUOUS)

    @property
    def needs_limit(self) -> bool:
        """URDF requires ``<limit>`` on these."""
        return self in (JointType.REVOLUTE, JointType.PRISMATIC)


_DOF = {
    JointType.FIXED: 0,
    JointType.REVOLUTE: 1,
    JointType.CONTINUOUS: 1,
    JointType.PRISMATIC: 1,
    JointType.FLOATING: 6,
    JointType.PLANAR: 3,
    JointType.SPHERICAL: 3,
}


@dataclass(slots=True)
class Limit:
    """``lower``/``upper`` in rad or m, ``effort`` in N·m or N, ``velocity`` in rad/s or m/s."""

    lower: float | None = None
    upper: float | None = None
    effort: float | None = None
    velocity: float | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class Dynamics:
    damping: float | None = None
    friction: float | None = None
    # Isaac's URDF extension: a passive spring used when the drive target type is none.
    spring_stiffness: float | None = None
    spring_reference: float | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class Mimic:
    """``q = multiplier * q_leader + offset``."""

    joint: str
    multiplier: float | None = None
    offset: float | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class Drive:
    """The servo the input itself puts on a joint (an MJCF ``position``/``velocity``/``motor``), in SI
    joint space: ``stiffness`` N·m/rad (N/m), ``damping`` N·m·s/rad (N·s/m). ``kind`` is
    ``"position"``, ``"velocity"`` or ``"effort"`` (a motor: no gains). Targets use these gains where
    the user gives none (emit/common/source_drives.py)."""

    kind: str
    stiffness: float | None = None
    damping: float | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class SafetyController:
    k_velocity: float
    k_position: float | None = None
    soft_lower_limit: float | None = None
    soft_upper_limit: float | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class Calibration:
    rising: float | None = None
    falling: float | None = None
    reference_position: float | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class Joint:
    name: str
    type: JointType
    parent: str
    child: str
    origin: Pose | None = None
    axis: Vec3 | None = None
    limit: Limit | None = None
    dynamics: Dynamics | None = None
    mimic: Mimic | None = None
    safety_controller: SafetyController | None = None
    calibration: Calibration | None = None
    # Reflected rotor inertia (kg·m²): J_rotor·N². Not in URDF; set by the armature pass.
    armature: float | None = None
    # Isaac's URDF extension: keep the child as its own body when fixed joints are merged.
    dont_collapse: bool | None = None
    # The source's own actuator on this joint (MJCF); None: the input declares none.
    drive: Drive | None = None
    display_name: str | None = None
    src: SourceLoc | None = None
    extensions: list[Extension] = field(default_factory=list)
    extra_attrs: dict[str, str] = field(default_factory=dict)

    @property
    def effective_axis(self) -> Vec3:
        """URDF's default axis is +X."""
        return self.axis if self.axis is not None else (1.0, 0.0, 0.0)


@dataclass(slots=True)
class LoopFrame:
    """One side of a loop joint: a frame on ``link``."""

    link: str
    origin: Pose | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class LoopJoint:
    """A joint that closes a kinematic loop; outside the tree (Isaac's ``<loop_joint>``)."""

    name: str
    type: str  # "spherical" is what Isaac builds; "revolute", "fixed" ... are kept for other targets
    link1: LoopFrame
    link2: LoopFrame
    axis: Vec3 | None = None
    display_name: str | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class FixedFrame:
    """A massless named frame on a link (Isaac's ``<fixed_frame>``)."""

    name: str
    parent: str
    origin: Pose | None = None
    display_name: str | None = None
    src: SourceLoc | None = None


class SensorType(enum.Enum):
    CAMERA = "camera"
    DEPTH = "depth"
    RAY = "ray"  # lidar; Isaac's URDF spells it "ray"
    IMU = "imu"
    FORCE_TORQUE = "force_torque"
    CONTACT = "contact"
    GPS = "gps"


@dataclass(slots=True)
class CameraSpec:
    width: int | None = None
    height: int | None = None
    hfov: float | None = None  # rad
    format: str | None = None
    near: float | None = None
    far: float | None = None


@dataclass(slots=True)
class RayAxis:
    samples: int | None = None
    resolution: float | None = None
    min_angle: float | None = None  # rad
    max_angle: float | None = None


@dataclass(slots=True)
class RaySpec:
    horizontal: RayAxis | None = None
    vertical: RayAxis | None = None
    min_range: float | None = None
    max_range: float | None = None


@dataclass(slots=True)
class Sensor:
    name: str
    type: SensorType
    parent: str  # the link the sensor rides on
    origin: Pose | None = None
    # Set when the input attached the sensor to a joint (iCub's ``<parent joint=...>``); the sensor
    # then sits in that joint's frame, which is its child link's frame, and ``parent`` is that link.
    parent_joint: str | None = None
    update_rate: float | None = None
    # Isaac RTX lidar: a preset name ("Velodyne_VLS128") or a path to a JSON config.
    isaac_sim_config: str | None = None
    camera: CameraSpec | None = None
    ray: RaySpec | None = None
    topic: str | None = None
    noise: float | None = None  # Gaussian stddev, in the sensor's unit
    display_name: str | None = None
    src: SourceLoc | None = None
    extensions: list[Extension] = field(default_factory=list)


@dataclass(slots=True)
class TransmissionJoint:
    name: str
    hardware_interfaces: list[str] = field(default_factory=list)
    src: SourceLoc | None = None


@dataclass(slots=True)
class TransmissionActuator:
    name: str
    hardware_interfaces: list[str] = field(default_factory=list)
    mechanical_reduction: float | None = None
    src: SourceLoc | None = None


@dataclass(slots=True)
class Transmission:
    name: str
    type: str | None = None
    joints: list[TransmissionJoint] = field(default_factory=list)
    actuators: list[TransmissionActuator] = field(default_factory=list)
    src: SourceLoc | None = None
    extensions: list[Extension] = field(default_factory=list)


@dataclass(slots=True)
class ControlInterface:
    """A ``<command_interface>`` or ``<state_interface>`` with its ``<param>`` children."""

    name: str
    params: dict[str, str] = field(default_factory=dict)


@dataclass(slots=True)
class ControlJoint:
    name: str
    command_interfaces: list[ControlInterface] = field(default_factory=list)
    state_interfaces: list[ControlInterface] = field(default_factory=list)
    params: dict[str, str] = field(default_factory=dict)
    src: SourceLoc | None = None


@dataclass(slots=True)
class Ros2Control:
    name: str
    type: str = "system"
    plugin: str | None = None
    hardware_params: dict[str, str] = field(default_factory=dict)
    joints: list[ControlJoint] = field(default_factory=list)
    src: SourceLoc | None = None
    # <sensor>, <gpio> and anything else inside, verbatim.
    extensions: list[Extension] = field(default_factory=list)


@dataclass(slots=True)
class Robot:
    name: str
    links: list[Link] = field(default_factory=list)
    joints: list[Joint] = field(default_factory=list)
    materials: list[Material] = field(default_factory=list)
    loop_joints: list[LoopJoint] = field(default_factory=list)
    fixed_frames: list[FixedFrame] = field(default_factory=list)
    sensors: list[Sensor] = field(default_factory=list)
    transmissions: list[Transmission] = field(default_factory=list)
    ros2_controls: list[Ros2Control] = field(default_factory=list)
    extensions: list[Extension] = field(default_factory=list)
    display_name: str | None = None
    src: SourceLoc | None = None
    # The file the robot was read from; relative mesh paths were resolved against its folder.
    source_file: str | None = None
    # Root folders of the packages the input's references were found in (--package folders,
    # $(find pkg) and package:// look-ups): meshes under them may be copied into an output even when
    # a path reached them without naming the package (xacro's $(find) gives absolute paths).
    package_roots: list[str] = field(default_factory=list)
    # Where the input placed the root link in its world (compositions give world poses); ``None``
    # = at the world origin. URDF cannot say this; world-aware targets (SDF, USD) can.
    placement: Pose | None = None
    # Whether the input fixed the root link to the world (True), declared it free (False), or did
    # not say (None). URDF cannot say this either; importers have a "fix base" option.
    fixed_base: bool | None = None
    # Joint positions (rad or m) the input names as the robot's start: ros2_control's
    # ``initial_value``. Kept here when strip_tags drops the ``<ros2_control>`` block, so that the
    # Isaac target can still start the robot where its authors said (emit/common/named_pose.py).
    initial_positions: dict[str, float] = field(default_factory=dict)

    # ---- look-ups -------------------------------------------------------------------------
    def link(self, name: str) -> Link:
        for link in self.links:
            if link.name == name:
                return link
        raise KeyError(name)

    def joint(self, name: str) -> Joint:
        for joint in self.joints:
            if joint.name == name:
                return joint
        raise KeyError(name)

    def link_map(self) -> dict[str, Link]:
        return {link.name: link for link in self.links}

    def joint_map(self) -> dict[str, Joint]:
        return {joint.name: joint for joint in self.joints}

    def child_joints(self) -> dict[str, list[Joint]]:
        """Joints by parent link name, in input order."""
        out: dict[str, list[Joint]] = {}
        for joint in self.joints:
            out.setdefault(joint.parent, []).append(joint)
        return out

    def parent_joint(self) -> dict[str, Joint]:
        """The joint that leads to each link, by child link name."""
        return {joint.child: joint for joint in self.joints}

    def root_links(self) -> list[Link]:
        children = {joint.child for joint in self.joints}
        return [link for link in self.links if link.name not in children]

    @property
    def root(self) -> Link:
        roots = self.root_links()
        if len(roots) != 1:
            raise ValueError(f"robot {self.name!r} has {len(roots)} root links")
        return roots[0]

    def tree_depth(self) -> int:
        """The number of joints on the longest path from a root link (consumers that nest bodies,
        MuJoCo and sdformat's frame graph, have limits or costs that grow with it)."""
        depth: dict[str, int] = {}
        for joint in self.topological_joints():  # parents before children
            depth[joint.child] = depth.get(joint.parent, 0) + 1
        return max(depth.values(), default=0)

    def topological_joints(self) -> list[Joint]:
        """Joints ordered so every joint's parent link is reached before its child (breadth first)."""
        by_parent = self.child_joints()
        out: list[Joint] = []
        frontier = [link.name for link in self.root_links()]
        seen: set[str] = set(frontier)
        while frontier:
            nxt: list[str] = []
            for name in frontier:
                for joint in by_parent.get(name, []):
                    if joint.child in seen:
                        continue
                    seen.add(joint.child)
                    out.append(joint)
                    nxt.append(joint.child)
            frontier = nxt
        return out

    @property
    def dof(self) -> int:
        return sum(j.type.dof for j in self.joints if j.mimic is None)

    def actuated_joints(self) -> list[Joint]:
        """Movable, non-mimic joints, in input order: what a controller commands."""
        return [j for j in self.joints if j.type.dof > 0 and j.mimic is None]

    def total_mass(self) -> float:
        return sum(
            link.inertial.mass for link in self.links if link.inertial is not None and link.inertial.mass is not None
        )
