"""The MJCF (MuJoCo XML) target: robot.xml, scene.xml and the meshes MuJoCo reads (docs/mjcf.md).

Light to import (the target table loads every target to build the command line): the writer, and
numpy behind it, load on first use of an entry point."""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from robodesc.emit.mjcf.options import MjcfOptions
from robodesc.emit.mjcf.target import TARGET

if TYPE_CHECKING:
    from robodesc.emit.mjcf.emitter import build_mjcf, emit_mjcf


def __getattr__(name: str) -> Any:
    if name in ("build_mjcf", "emit_mjcf"):
        return getattr(importlib.import_module("robodesc.emit.mjcf.emitter"), name)
    raise AttributeError(f"module 'robodesc.emit.mjcf' has no attribute {name!r}")


__all__ = ["TARGET", "MjcfOptions", "build_mjcf", "emit_mjcf"]
