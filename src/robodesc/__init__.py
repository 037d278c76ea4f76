"""robodesc: a compiler for robot descriptions (URDF, xacro, compositions → URDF, SDF, USD).

The public API lives in :mod:`robodesc.api` and is re-exported here.
"""

__version__ = "0.1.0"

from robodesc.api import CompileResult, compile_to_urdf, load

__all__ = ["CompileResult", "__version__", "compile_to_urdf", "load"]
