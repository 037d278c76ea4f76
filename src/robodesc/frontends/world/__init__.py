"""World inputs: an SDF world (``.world``, ``.sdf`` with a ``<world>``) or a bare terrain (a mesh or
a height image), read into :class:`robodesc.ir.world.World` (docs/worlds.md).

The readers load on first use: ``robodesc.options`` imports this package's options on every run, and
a compile without a world must not pay for numpy."""

from __future__ import annotations

from typing import Any

__all__ = ["is_world_file", "load_world"]


def __getattr__(name: str) -> Any:
    if name in __all__:
        from robodesc.frontends.world import load

        return getattr(load, name)
    raise AttributeError(name)
