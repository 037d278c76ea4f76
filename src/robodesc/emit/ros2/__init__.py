"""ROS 2 target: ros2_control URDF, controllers, launch file, ros_gz_bridge YAML and world.
Entry point: :func:`build_ros2_package` (loaded on first use, like the SDF writer it builds on)."""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from robodesc.emit.ros2.options import CommandInterface, ControllerKind, Ros2Options
from robodesc.emit.ros2.target import TARGET

if TYPE_CHECKING:
    from robodesc.emit.ros2.package import Ros2Package, build_ros2_package, emit_ros2_package

_LAZY = {"Ros2Package", "build_ros2_package", "emit_ros2_package"}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(importlib.import_module("robodesc.emit.ros2.package"), name)
    raise AttributeError(f"module 'robodesc.emit.ros2' has no attribute {name!r}")


__all__ = [
    "TARGET",
    "CommandInterface",
    "ControllerKind",
    "Ros2Options",
    "Ros2Package",
    "build_ros2_package",
    "emit_ros2_package",
]
