"""The stage a user of the Isaac Sim 6 route opens: a root layer that sublayers robodesc's physics
layer (``<robot>_physics.usda``) over the USD Isaac Sim 6's importer wrote, and selects the
importer's ``Physics = "physx"`` variant.

Why a root layer of its own: the importer leaves its ``Physics`` variant set unselected, so its
asset has no rigid bodies, joints or colliders until a stronger layer selects one; and the physics
layer must be the stronger of the two sublayers, which only a layer above both can say. Neither
input file is edited. The same file, without the physics layer, is the importer-only route
(``importer_settings.json`` alone), which is how ``tests/consumers/isaac6_layer.py`` runs both
routes in PhysX.
"""

from __future__ import annotations

import os
from collections.abc import Sequence

from robodesc._files import write_atomic
from robodesc.usdfile.spec import Layer
from robodesc.usdfile.usda import usda_text

# The importer's variant set that holds its physics, and the variant PhysX (and Isaac Sim) read.
PHYSICS_VARIANT = ("Physics", "physx")


def composed_stage(robot_prim: str, sublayers: Sequence[str], *, scene: bool = False) -> Layer:
    """The root layer: ``sublayers`` strongest first (the physics layer, then the import), the
    importer's physics variant selected on ``robot_prim`` (the import's default prim, ``/`` or
    not), and a bare ``/PhysicsScene`` when ``scene`` (when no sublayer brings one: the physics
    layer carries the preset's scene only with ``--physics-scene``)."""
    name = robot_prim.strip("/")
    if not name or "/" in name:
        raise ValueError(f"not a root prim: {robot_prim!r}")
    layer = Layer(default_prim=name, meters_per_unit=1.0, kilograms_per_unit=1.0, up_axis="Z")
    layer.sublayers = list(sublayers)
    over = layer.prim(f"/{name}", specifier="over")
    over.variant_selections[PHYSICS_VARIANT[0]] = PHYSICS_VARIANT[1]
    if scene:
        layer.prim("/PhysicsScene", "PhysicsScene")
    return layer


def write_composed_stage(path: str, robot_prim: str, sublayers: Sequence[str], *, scene: bool = False) -> str:
    """Write :func:`composed_stage` to ``path``, each sublayer named relative to ``path``'s folder
    where it can be (the three files then move together), absolute otherwise (another drive)."""
    folder = os.path.dirname(os.path.abspath(path))
    named = []
    for sub in sublayers:
        absolute = os.path.abspath(sub)
        try:
            rel = os.path.relpath(absolute, folder)
        except ValueError:  # Windows: another drive has no relative path
            rel = absolute
        named.append(rel if rel.startswith("..") else f"./{rel}")
    write_atomic(path, usda_text(composed_stage(robot_prim, named, scene=scene)))
    return path
