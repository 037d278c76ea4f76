"""USD target (UsdPhysics for Isaac Sim and Newton). Entry point: :func:`emit_usd`.

Layers and prims are built with :mod:`robodesc.usdfile` (no usd-core at write time).
"""

from robodesc.emit.usd.emitter import emit_usd
from robodesc.emit.usd.options import (
    COLLISION_APPROXIMATION,
    CONTACT_OFFSET,
    LAYERED,
    PHYSICS_SCENE,
    POSITION_ITERATIONS,
    REST_OFFSET,
    VELOCITY_ITERATIONS,
    UsdOptions,
)
from robodesc.emit.usd.target import TARGET

# The flags of the options the Isaac folder shares with USD (emit/isaac/settings.py).
__all__ = [
    "COLLISION_APPROXIMATION",
    "CONTACT_OFFSET",
    "LAYERED",
    "PHYSICS_SCENE",
    "POSITION_ITERATIONS",
    "REST_OFFSET",
    "TARGET",
    "VELOCITY_ITERATIONS",
    "UsdOptions",
    "emit_usd",
]
