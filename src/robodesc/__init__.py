"""robodesc: a compiler for robot descriptions (URDF, xacro, compositions → URDF, SDF, USD)."""

__version__ = "0.1.0"
