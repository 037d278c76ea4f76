"""Options of the MJCF emitter. Fields shared with the USD target keep USD's names and defaults,
so one ``--stiffness`` means the same SI gain for both (docs/mjcf.md)."""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field

from robodesc.emit.common.flags import flag
from robodesc.ir.diagnostics import ConfigError

DRIVE_TYPES = ("force", "acceleration")
TARGET_TYPES = ("none", "position", "velocity")
ACTUATORS = ("position", "velocity", "motor", "none")
# USD's names; MuJoCo itself only builds convex hulls of mesh colliders.
APPROXIMATIONS = ("convexHull", "convexDecomposition", "boundingCube", "boundingSphere", "none")
INTEGRATORS = ("implicitfast", "implicit", "Euler", "RK4")

# One number for every joint, or an ordered {regex: value} table (first full match wins).
Gain = float | Mapping[str, float]


@dataclass(slots=True)
class MjcfOptions:
    """What the MJCF emitter writes. Gains are SI: N·m/rad (N/m) and N·m·s/rad (N·s/m)."""

    fix_base: bool = field(
        default=True, metadata=flag("weld the root link to the world (--no-fix-base: a free joint)", kind="switch")
    )
    drive_type: str = field(default="force", metadata=flag("drive type", choices=DRIVE_TYPES))
    target_type: str = field(default="position", metadata=flag("drive target", choices=TARGET_TYPES))
    stiffness: Gain = field(default=100.0, metadata=flag("drive stiffness, SI per rad or per m", kind="rules"))
    damping: Gain = field(default=1.0, metadata=flag("drive damping, SI per rad/s or per m/s", kind="rules"))
    # The MuJoCo actuator kind; when not given it follows target_type (none -> motor).
    actuator: str = field(
        default="position",
        metadata=flag("MuJoCo actuator kind per movable joint", name="--mjcf-actuator", choices=ACTUATORS),
    )
    collision_approximation: str = field(
        default="convexHull", metadata=flag("collision mesh approximation", choices=APPROXIMATIONS)
    )
    # MuJoCo's <mesh maxhullvert>: caps the vertices of the convex hull MuJoCo builds (None: no cap).
    maxhullvert: int | None = field(
        default=None, metadata=flag("vertex cap of collision hulls", name="--mjcf-maxhullvert", type=int)
    )
    self_collision: bool = field(
        default=False, metadata=flag("collide the robot's links with each other", kind="switch")
    )
    integrator: str = field(
        default="implicitfast", metadata=flag("MuJoCo integrator", name="--mjcf-integrator", choices=INTEGRATORS)
    )
    init_pos: tuple[float, float, float] | None = field(
        default=None, metadata=flag("root position of the home keyframe (X,Y,Z)", kind="vector")
    )
    init_joint_pos: Mapping[str, float] = field(
        default_factory=dict, metadata=flag("joint positions of the home keyframe", kind="rules", rules_only=True)
    )
    # Write scene.xml beside the robot (floor, light, sky).
    scene: bool = field(
        default=True, metadata=flag("write scene.xml beside the robot", name="--mjcf-scene", kind="switch")
    )

    def check(self) -> None:
        _one_of("drive_type", self.drive_type, DRIVE_TYPES)
        _one_of("target_type", self.target_type, TARGET_TYPES)
        _one_of("actuator", self.actuator, ACTUATORS)
        _one_of("collision_approximation", self.collision_approximation, APPROXIMATIONS)
        _one_of("integrator", self.integrator, INTEGRATORS)
        for name in ("stiffness", "damping"):
            gain = getattr(self, name)
            if isinstance(gain, Mapping):
                for pattern, value in gain.items():
                    try:
                        re.compile(pattern)
                    except re.error as exc:
                        raise ConfigError(f"{name}: bad regular expression {pattern!r}: {exc}") from None
                    _non_negative(f"{name}[{pattern!r}]", value)
            else:
                _non_negative(name, gain)
        if self.maxhullvert is not None and (not isinstance(self.maxhullvert, int) or self.maxhullvert < 4):
            raise ConfigError(f"maxhullvert must be an integer >= 4 (MuJoCo's minimum), got {self.maxhullvert!r}")


def _one_of(name: str, value: str, allowed: tuple[str, ...]) -> None:
    if value not in allowed:
        raise ConfigError(f"{name} must be one of {', '.join(allowed)}; got {value!r}")


def _non_negative(name: str, value: object) -> None:
    if not isinstance(value, int | float) or isinstance(value, bool) or not value >= 0:
        raise ConfigError(f"{name} must be a number >= 0, got {value!r}")
