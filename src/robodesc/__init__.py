"""robodesc: a compiler for robot descriptions (URDF, xacro, compositions → URDF, SDF, USD).

The public API lives in :mod:`robodesc.api` and is re-exported here. It is imported on first use
(PEP 562), so that ``import robodesc.ir`` or ``robodesc.meshes`` does not load the whole pipeline and
no stage's import can come back round to this package.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from robodesc._version import __version__

if TYPE_CHECKING:
    from robodesc.api import (
        CompileResult,
        check,
        compile_for_gazebo,
        compile_for_isaac_sim,
        compile_for_ros2,
        compile_to,
        compile_to_sdf,
        compile_to_urdf,
        compile_to_usd,
        isaac_physics_layer,
        load,
        validate,
    )

__all__ = [
    "CompileResult",
    "__version__",
    "check",
    "compile_for_gazebo",
    "compile_for_isaac_sim",
    "compile_for_ros2",
    "compile_to",
    "compile_to_sdf",
    "compile_to_urdf",
    "compile_to_usd",
    "isaac_physics_layer",
    "load",
    "validate",
]


def __getattr__(name: str) -> Any:
    # compile_to_<target> exists for every target of the table (robodesc.api.__getattr__).
    if name in __all__ or name.startswith("compile_to_"):
        from robodesc import api

        return getattr(api, name)
    raise AttributeError(f"module 'robodesc' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
