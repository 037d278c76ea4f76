"""Options of the USD emitter and how per-joint gains are looked up."""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass

from robodesc.ir.diagnostics import ConfigError

DRIVE_TYPES = ("force", "acceleration")
TARGET_TYPES = ("none", "position", "velocity")
APPROXIMATIONS = ("convexHull", "convexDecomposition", "boundingCube", "boundingSphere", "none")
FORMATS = (".usda", ".usdc", ".usd")

# A gain is one number for every joint, or an ordered {regex: value} table (first full match wins).
Gain = float | Mapping[str, float]


@dataclass(slots=True)
class UsdOptions:
    """What the USD emitter writes. Gains are SI (per rad for revolute joints, per m for prismatic);
    the emitter converts angular ones to USD's per-degree units."""

    fix_base: bool = True
    drive_type: str = "force"
    target_type: str = "position"
    stiffness: Gain = 100.0
    damping: Gain = 1.0
    collision_approximation: str = "convexHull"
    # False: one file. True: interface layer + Payload/ folder (contents, geometry, materials, physics).
    layered: bool = False
    solver_position_iterations: int | None = None
    solver_velocity_iterations: int | None = None
    self_collision: bool = False
    contact_offset: float | None = None  # m, PhysxCollisionAPI on every collider
    rest_offset: float | None = None
    physics_scene: bool = False  # a /PhysicsScene sibling of the robot (outside the default prim)
    # Initial joint positions (rad or m) by joint name: the joint state and the position target.
    # None or a missing joint: 0, clamped into the limits. The Isaac folder gives its default pose.
    initial_positions: Mapping[str, float] | None = None

    def check(self) -> None:
        _one_of("drive_type", self.drive_type, DRIVE_TYPES)
        _one_of("target_type", self.target_type, TARGET_TYPES)
        _one_of("collision_approximation", self.collision_approximation, APPROXIMATIONS)
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
        for name in ("solver_position_iterations", "solver_velocity_iterations"):
            value = getattr(self, name)
            if value is not None and (not isinstance(value, int) or value < 1 or value > 255):
                raise ConfigError(f"{name} must be an integer in 1..255, got {value!r}")


def _one_of(name: str, value: str, allowed: tuple[str, ...]) -> None:
    if value not in allowed:
        raise ConfigError(f"{name} must be one of {', '.join(allowed)}; got {value!r}")


def _non_negative(name: str, value: object) -> None:
    if not isinstance(value, int | float) or isinstance(value, bool) or not value >= 0:
        raise ConfigError(f"{name} must be a number >= 0, got {value!r}")
