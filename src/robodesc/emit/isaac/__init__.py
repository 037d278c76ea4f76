"""Isaac Sim target: one folder with the USD asset, the Isaac-flavoured URDF, importer settings,
an Isaac Lab ``ArticulationCfg`` module and the reports. Entry point: :func:`write_isaac_folder`
(loaded on first use, with the USD and URDF writers behind it)."""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from robodesc.emit.isaac.settings import IsaacSettings
from robodesc.emit.isaac.target import TARGET

if TYPE_CHECKING:
    from robodesc.emit.isaac.folder import findings_markdown, write_isaac_folder


def __getattr__(name: str) -> Any:
    if name in ("findings_markdown", "write_isaac_folder"):
        return getattr(importlib.import_module("robodesc.emit.isaac.folder"), name)
    raise AttributeError(f"module 'robodesc.emit.isaac' has no attribute {name!r}")


__all__ = ["TARGET", "IsaacSettings", "findings_markdown", "write_isaac_folder"]
