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

_LAZY = {"SdfResult", "build_sdf", "emit_sdf"}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(importlib.import_module("robodesc.emit.sdf.emitter"), name)
    raise AttributeError(f"module 'robodesc.emit.sdf' has no attribute {name!r}")


__all__ = ["TARGET", "PoseFrames", "SdfFlavour", "SdfOptions", "SdfProp", "SdfResult", "build_sdf", "emit_sdf"]
