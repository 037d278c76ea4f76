"""USD target (UsdPhysics for Isaac Sim and Newton). Entry point: :func:`emit_usd`.

Layers and prims are built with :mod:`robodesc.usdfile` (no usd-core at write time). Light to
import: the writer loads on first use of :func:`emit_usd`.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from robodesc.emit.usd.options import (
    COLLISION_APPROXIMATION,
    CONTACT_OFFSET,
    ISAAC_VERSION,
    LAYERED,
    MOTOR_ENVELOPE,
    PHYSICS_SCENE,
    POSITION_ITERATIONS,
    REST_OFFSET,
    VELOCITY_ITERATIONS,
    UsdOptions,
)
from robodesc.emit.usd.target import TARGET

if TYPE_CHECKING:
    from robodesc.emit.usd.emitter import PhysicsOpinions, emit_usd, physics_opinions
    from robodesc.emit.usd.world import robot_friction, write_terrain, write_world

_WRITER = ("emit_usd", "physics_opinions", "PhysicsOpinions")
# The world stage and the ground alone (the Isaac folder writes both).
_WORLD = ("write_world", "write_terrain", "robot_friction")


def __getattr__(name: str) -> Any:
    if name in _WRITER:
        return getattr(importlib.import_module("robodesc.emit.usd.emitter"), name)
    if name in _WORLD:
        return getattr(importlib.import_module("robodesc.emit.usd.world"), name)
    raise AttributeError(f"module 'robodesc.emit.usd' has no attribute {name!r}")


# The flags of the options the Isaac folder shares with USD (emit/isaac/settings.py).
__all__ = [
    "COLLISION_APPROXIMATION",
    "CONTACT_OFFSET",
    "ISAAC_VERSION",
    "LAYERED",
    "MOTOR_ENVELOPE",
    "PHYSICS_SCENE",
    "POSITION_ITERATIONS",
    "REST_OFFSET",
    "TARGET",
    "VELOCITY_ITERATIONS",
    "PhysicsOpinions",
    "UsdOptions",
    "emit_usd",
    "physics_opinions",
    "robot_friction",
    "write_terrain",
    "write_world",
]
