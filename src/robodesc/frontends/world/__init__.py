"""World inputs: an SDF world (``.world``, ``.sdf`` with a ``<world>``) or a bare terrain (a mesh or
a height image), read into :class:`robodesc.ir.world.World` (docs/worlds.md)."""

from robodesc.frontends.world.load import is_world_file, load_world

__all__ = ["is_world_file", "load_world"]
