"""USD target (UsdPhysics for Isaac Sim and Newton). Entry point: :func:`emit_usd`.

Layers and prims are built with :mod:`robodesc.usdfile` (no usd-core at write time).
"""

from robodesc.emit.usd.emitter import emit_usd
from robodesc.emit.usd.options import UsdOptions
from robodesc.emit.usd.target import TARGET

__all__ = ["TARGET", "UsdOptions", "emit_usd"]
