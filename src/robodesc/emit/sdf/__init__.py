"""SDF target (Gazebo Harmonic, SDFormat 1.9-1.11). Entry points: :func:`emit_sdf`, :func:`build_sdf`."""

from robodesc.emit.sdf.emitter import SdfResult, build_sdf, emit_sdf
from robodesc.emit.sdf.options import PoseFrames, SdfFlavour, SdfOptions, SdfProp
from robodesc.emit.sdf.target import TARGET

__all__ = ["TARGET", "PoseFrames", "SdfFlavour", "SdfOptions", "SdfProp", "SdfResult", "build_sdf", "emit_sdf"]
