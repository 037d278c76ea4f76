"""Options of the USD emitter and how per-joint gains are looked up."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from robodesc.emit.common import approximation
from robodesc.emit.common import flags as common
from robodesc.emit.common.drives import check_drives, one_of
from robodesc.emit.common.flags import flag
from robodesc.ir.diagnostics import ConfigError

FORMATS = (".usda", ".usdc", ".usd")
COMBINE_MODES = ("average", "min", "multiply", "max")

# Flags of options the Isaac folder shares (emit/isaac/settings.py declares its fields with these).
COLLISION_APPROXIMATION = approximation.FLAG
LAYERED = flag("USD as an interface layer + payload (like NVIDIA's converter) instead of one file", kind="on")
POSITION_ITERATIONS = flag("PhysX articulation position iterations", type=int, metavar="N")
VELOCITY_ITERATIONS = flag("PhysX articulation velocity iterations", type=int, metavar="N")
CONTACT_OFFSET = flag("PhysX contact offset on every collider (default PhysX's ~2 cm)", type=float, metavar="M")
REST_OFFSET = flag("PhysX rest offset on every collider", type=float, metavar="M")
PHYSICS_SCENE = flag("add a /PhysicsScene beside the robot (outside the default prim)", kind="on")
# Isaac Sim releases by the PhysX joint vocabulary they read (docs/isaac.md, "Isaac Sim versions").
ISAAC_VERSIONS = ("4", "5", "6")
# The releases whose PhysX still reads the single-apply PhysxJointAPI (physxJoint:*).
LEGACY_JOINT_API = ("4", "5")
# The releases before PhysxJointAxisAPI (PhysX 5.6, Isaac Sim 5.0).
ISAAC_WITHOUT_JOINT_AXIS = ("4",)
ISAAC_VERSION = flag(
    "Isaac Sim release the USD targets (default 6: PhysxJointAxisAPI only; 5: also the legacy "
    "physxJoint:* spelling; 4: only the legacy spelling, no friction effort); docs/isaac.md",
    choices=ISAAC_VERSIONS,
)
MOTOR_ENVELOPE = flag(
    "read each driven joint's URDF effort and velocity as its motor's stall torque and no-load speed and "
    "write PhysxDrivePerformanceEnvelopeAPI, so PhysX lowers the torque linearly with speed; docs/usd.md",
    kind="on",
)

# A gain is one number for every joint, or an ordered {regex: value} table (first full match wins).
Gain = float | Mapping[str, float]


@dataclass(slots=True)
class UsdOptions:
    """What the USD emitter writes. Gains are SI (per rad for revolute joints, per m for prismatic);
    the emitter converts angular ones to USD's per-degree units."""

    fix_base: bool = field(default=True, metadata=common.FIX_BASE)
    drive_type: str = field(default="force", metadata=common.DRIVE_TYPE)
    target_type: str = field(default="position", metadata=common.TARGET_TYPE)
    stiffness: Gain = field(default=100.0, metadata=common.STIFFNESS)
    damping: Gain = field(default=1.0, metadata=common.DAMPING)
    collision_approximation: approximation.Approximation = field(default="convexHull", metadata=COLLISION_APPROXIMATION)
    # False: one file. True: interface layer + Payload/ folder (contents, geometry, materials, physics).
    layered: bool = field(default=False, metadata=LAYERED)
    solver_position_iterations: int | None = field(default=None, metadata=POSITION_ITERATIONS)
    solver_velocity_iterations: int | None = field(default=None, metadata=VELOCITY_ITERATIONS)
    self_collision: bool = field(default=False, metadata=common.SELF_COLLISION)
    contact_offset: float | None = field(
        default=None, metadata=CONTACT_OFFSET
    )  # m, PhysxCollisionAPI on every collider
    rest_offset: float | None = field(default=None, metadata=REST_OFFSET)
    # A /PhysicsScene sibling of the robot (outside the default prim).
    physics_scene: bool = field(default=False, metadata=PHYSICS_SCENE)
    # How PhysX combines two colliders' friction (its default: average); None leaves it to PhysX.
    friction_combine: str | None = field(default=None, metadata=common.FRICTION_COMBINE)
    default_friction: float = field(default=0.5, metadata=common.DEFAULT_FRICTION)
    isaac_version: str = field(default="6", metadata=ISAAC_VERSION)
    motor_envelope: bool = field(default=False, metadata=MOTOR_ENVELOPE)
    # Initial joint positions (rad or m) by joint name: the joint state and the position target.
    # None or a missing joint: 0, clamped into the limits. The Isaac folder gives its default pose.
    initial_positions: Mapping[str, float] | None = None

    def check(self) -> None:
        check_drives(self)
        approximation.check(self.collision_approximation)
        if self.friction_combine is not None:
            one_of("friction_combine", self.friction_combine, COMBINE_MODES)
        one_of("isaac_version", self.isaac_version, ISAAC_VERSIONS)
        for name in ("solver_position_iterations", "solver_velocity_iterations"):
            value = getattr(self, name)
            if value is not None and (not isinstance(value, int) or value < 1 or value > 255):
                raise ConfigError(f"{name} must be an integer in 1..255, got {value!r}")
