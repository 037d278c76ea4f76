"""What a compile is told about the world around the robot (``--world``, ``--terrain``, ``--spawn``)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(slots=True)
class WorldOptions:
    # An SDF world file (``--world FILE``); its static models, includes and physics.
    file: str | None = None
    # A bare terrain (``--terrain FILE``): a mesh (STL, PLY, OBJ, DAE) or a grey PNG height image.
    terrain: str | None = None
    # A height image's extent X, Y and its height range Z (m); required with a PNG terrain.
    terrain_size: tuple[float, float, float] | None = None
    # The heightfield's cell (m) where a target needs one (MJCF); None: the default, 2 cm.
    terrain_resolution: float | None = None
    # Where the robot stands: X, Y (its height from the terrain under its feet) or X, Y, Z; None: the
    # world's own include pose, else the origin.
    spawn: tuple[float, ...] | None = None
    # Several copies of the robot (``--spawn`` given more than once): every copy's point, ``spawn``
    # the first. Empty: one robot.
    copies: tuple[tuple[float, ...], ...] = ()
    # Folders searched for model:// URIs before the Gazebo environment variables.
    model_path: tuple[str, ...] = ()
    # A YAML file of cord fields (frontends/world/cords.py), added to the world (or to an empty one).
    cords: str | None = None

    @property
    def given(self) -> bool:
        return self.file is not None or self.terrain is not None or self.cords is not None
