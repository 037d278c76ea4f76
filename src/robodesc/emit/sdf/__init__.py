"""SDF target (Gazebo Harmonic, SDFormat 1.9-1.11). Entry points: :func:`emit_sdf`, :func:`build_sdf`.

Light to import (the target table loads every target's ``TARGET`` and options to build the command
line): the writer, and numpy behind it, load on first use of an entry point."""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from robodesc.emit.sdf.options import PoseFrames, SdfFlavour, SdfOptions, SdfProp
from robodesc.emit.sdf.target import TARGET

if TYPE_CHECKING:
    from robodesc.emit.sdf.emitter import SdfResult, build_sdf, emit_sdf
    from robodesc.emit.sdf.sensors import sensor_element
    from robodesc.emit.sdf.topics import CLOCK, Topic, sensor_topics
    from robodesc.emit.sdf.world import world_element

# Public names other targets use (ROS 2 writes SDF's world and sensors), by the module that has them.
_LAZY = {
    "SdfResult": "emitter",
    "build_sdf": "emitter",
    "emit_sdf": "emitter",
    "sensor_element": "sensors",
    "CLOCK": "topics",
    "Topic": "topics",
    "sensor_topics": "topics",
    "world_element": "world",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(importlib.import_module(f"robodesc.emit.sdf.{_LAZY[name]}"), name)
    raise AttributeError(f"module 'robodesc.emit.sdf' has no attribute {name!r}")


__all__ = [
    "CLOCK",
    "TARGET",
    "PoseFrames",
    "SdfFlavour",
    "SdfOptions",
    "SdfProp",
    "SdfResult",
    "Topic",
    "build_sdf",
    "emit_sdf",
    "sensor_element",
    "sensor_topics",
    "world_element",
]
