"""Options of the MJCF emitter. Fields shared with the USD target keep USD's names and defaults,
so one ``--stiffness`` means the same SI gain for both (docs/mjcf.md)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from robodesc.emit.common import approximation
from robodesc.emit.common import decomposition as decomp
from robodesc.emit.common import flags as common
from robodesc.emit.common.approximation import Approximation
from robodesc.emit.common.drives import check_drives, one_of
from robodesc.emit.common.flags import flag
from robodesc.ir.diagnostics import ConfigError

ACTUATORS = ("position", "velocity", "motor", "none")
CONES = ("pyramidal", "elliptic")
INTEGRATORS = ("implicitfast", "implicit", "Euler", "RK4")

# The friction combine rules an MJCF can say (docs/contact.md).
MJCF_COMBINE = ("min", "max")

# One number for every joint, or an ordered {regex: value} table (first full match wins).
Gain = float | Mapping[str, float]


@dataclass(slots=True)
class MjcfOptions:
    """What the MJCF emitter writes. Gains are SI: N·m/rad (N/m) and N·m·s/rad (N·s/m)."""

    fix_base: bool = field(default=True, metadata=common.FIX_BASE)
    drive_type: str = field(default="force", metadata=common.DRIVE_TYPE)
    target_type: str = field(default="position", metadata=common.TARGET_TYPE)
    stiffness: Gain = field(default=100.0, metadata=common.STIFFNESS)
    damping: Gain = field(default=1.0, metadata=common.DAMPING)
    # The MuJoCo actuator kind; when not given it follows target_type (none -> motor).
    actuator: str = field(
        default="position",
        metadata=flag("MuJoCo actuator kind per movable joint", name="--mjcf-actuator", choices=ACTUATORS),
    )
    collision_approximation: Approximation = field(default="convexHull", metadata=approximation.FLAG)
    # convexDecomposition: CoACD's parts, cached by content (emit/common/decomposition.py).
    decomposition_max_parts: int = field(default=32, metadata=decomp.MAX_PARTS)
    decomposition_timeout: float = field(default=300.0, metadata=decomp.TIMEOUT)
    decomposition_threshold: float = field(default=0.05, metadata=decomp.THRESHOLD)
    decomposition_cache: str | None = field(default=None, metadata=decomp.CACHE)
    # MuJoCo's <mesh maxhullvert>: caps the vertices of the convex hull MuJoCo builds (None: no cap).
    maxhullvert: int | None = field(
        default=None, metadata=flag("vertex cap of collision hulls", name="--mjcf-maxhullvert", type=int)
    )
    self_collision: bool = field(default=False, metadata=common.SELF_COLLISION)
    integrator: str = field(
        default="implicitfast", metadata=flag("MuJoCo integrator", name="--mjcf-integrator", choices=INTEGRATORS)
    )
    init_pos: tuple[float, float, float] | None = field(default=None, metadata=common.INIT_POS)
    init_joint_pos: Mapping[str, float] = field(default_factory=dict, metadata=common.INIT_JOINT_POS)
    # MuJoCo's friction cone and impedance ratio (<option cone impratio>). None: MuJoCo's own
    # (pyramidal, 1), except on a floating robot that stands on legs, which gets mujoco_menagerie's
    # legged choice, elliptic and 100 (target._contact_defaults; docs/mjcf.md).
    cone: str | None = field(default=None, metadata=flag("MuJoCo friction cone", name="--mjcf-cone", choices=CONES))
    impratio: float | None = field(
        default=None, metadata=flag("MuJoCo's frictional-to-normal impedance ratio", name="--mjcf-impratio", type=float)
    )
    # Not a flag: the colliders a floating robot stands on (its stance's feet: link -> the index of
    # the collider that touches the ground), which get the "foot" class (condim 6, priority 1,
    # menagerie's foot friction where the source gives none).
    feet: Mapping[str, int] = field(default_factory=dict)
    # Not a flag: the root height of a floating robot's home keyframe, set by the target from the
    # stance it chose (the body stays at its zero-pose height); None keeps the body's position.
    home_height: float | None = None
    # Not a flag: several copies of the robot in a world (--spawn given more than once), each as
    # (its root in the zero pose, its home keyframe's root height); the first is the robot's own.
    copies: tuple[tuple[tuple[float, float, float], float], ...] = ()
    # Write scene.xml beside the robot (floor, light, sky).
    scene: bool = field(
        default=True, metadata=flag("write scene.xml beside the robot", name="--mjcf-scene", kind="switch")
    )

    # MuJoCo combines two geoms' friction by the larger, or takes the higher priority geom's. "min"
    # (ODE's rule, --preset gazebo_parity) gives the robot's colliders priority 1: their own
    # friction and solref apply against the world's, which is ODE's minimum whenever the world's
    # surface grips at least as much (Gazebo's ground: mu 100). "max" is MuJoCo's own rule.
    friction_combine: str | None = field(default=None, metadata=common.FRICTION_COMBINE)

    def check(self) -> None:
        if self.friction_combine is not None and self.friction_combine not in MJCF_COMBINE:
            raise ConfigError(
                f"friction_combine {self.friction_combine!r}: MuJoCo combines friction by the larger (max) or "
                "by geom priority (min: the robot's own); it has no average or product",
                element="option 'friction_combine'",
            )
        check_drives(self)
        one_of("actuator", self.actuator, ACTUATORS)
        approximation.check(self.collision_approximation)
        decomp.check_settings(self)
        one_of("integrator", self.integrator, INTEGRATORS)
        if self.cone is not None:
            one_of("cone", self.cone, CONES)
        if self.impratio is not None and not self.impratio >= 1.0:
            raise ConfigError(f"impratio must be at least 1 (MuJoCo's minimum), got {self.impratio!r}")
        if self.maxhullvert is not None and (not isinstance(self.maxhullvert, int) or self.maxhullvert < 4):
            raise ConfigError(f"maxhullvert must be an integer >= 4 (MuJoCo's minimum), got {self.maxhullvert!r}")
