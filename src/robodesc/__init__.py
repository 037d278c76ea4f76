"""robodesc: a compiler for robot descriptions (URDF, xacro, compositions → URDF, SDF, USD).

The public API lives in :mod:`robodesc.api` and is re-exported here.
"""

__version__ = "0.1.0"

from robodesc.api import (
    CompileResult,
    compile_for_gazebo,
    compile_for_isaac_sim,
    compile_for_ros2,
    compile_to_sdf,
    compile_to_urdf,
    compile_to_usd,
    load,
    validate,
)

__all__ = [
    "CompileResult",
    "__version__",
    "compile_for_gazebo",
    "compile_for_isaac_sim",
    "compile_for_ros2",
    "compile_to_sdf",
    "compile_to_urdf",
    "compile_to_usd",
    "load",
    "validate",
]
