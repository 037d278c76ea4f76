"""The MJCF (MuJoCo XML) target: robot.xml, scene.xml and the meshes MuJoCo reads (docs/mjcf.md)."""

from robodesc.emit.mjcf.emitter import build_mjcf, emit_mjcf
from robodesc.emit.mjcf.options import MjcfOptions
from robodesc.emit.mjcf.target import TARGET

__all__ = ["TARGET", "MjcfOptions", "build_mjcf", "emit_mjcf"]
