"""The world's one door: an SDF world file, or a bare terrain made into a world of one body."""

from __future__ import annotations

import os

from robodesc.frontends.contract import head_of, xml_root
from robodesc.frontends.world.options import WorldOptions
from robodesc.ir.diagnostics import ConfigError, Findings, ParseError, SourceLoc
from robodesc.ir.geometry import Mesh
from robodesc.ir.world import HeightImage, StaticBody, World, WorldCollider

MESH_SUFFIXES = (".stl", ".ply", ".obj", ".dae")
IMAGE_SUFFIXES = (".png",)
WORLD_SUFFIXES = (".world", ".sdf")


def is_world_file(path: str) -> bool:
    """An SDF file whose document holds a ``<world>`` (a robot input never does)."""
    if not path.lower().endswith((*WORLD_SUFFIXES, ".xml")) or not os.path.isfile(path):
        return False
    head = head_of(path, 8192)
    return xml_root(head) == "sdf" and "<world" in head


def load_world(options: WorldOptions, findings: Findings) -> World | None:
    """The world the options name, or None when they name none."""
    world = _ground(options, findings)
    if options.cords is not None:
        from robodesc.frontends.world.cords import read_cords

        cords = read_cords(_existing(options.cords, "--cords"))
        if world is None:
            world = World(name="cords", file=options.cords, src=SourceLoc(options.cords))
        world.cords.extend(cords)
    return world


def _ground(options: WorldOptions, findings: Findings) -> World | None:
    if options.file is not None and options.terrain is not None:
        raise ConfigError("--world and --terrain both give the ground; give one (a world file names its terrain)")
    if options.file is not None:
        path = _existing(options.file, "--world")
        if not is_world_file(path):
            raise ParseError(
                "is not an SDF world (an <sdf> file with a <world>); a bare terrain mesh goes with --terrain",
                loc=SourceLoc(path),
            )
        from robodesc.frontends.world.sdf_world import read_sdf_world  # numpy: only for a world

        return read_sdf_world(path, findings, options.model_path)
    if options.terrain is not None:
        return terrain_world(_existing(options.terrain, "--terrain"), options)
    return None


def terrain_world(path: str, options: WorldOptions) -> World:
    """A world of one static body, the terrain, its frame the world's."""
    lower = path.lower()
    loc = SourceLoc(path)
    shape: Mesh | HeightImage
    if lower.endswith(MESH_SUFFIXES):
        shape = Mesh(uri=os.path.basename(path), path=os.path.abspath(path), src=loc)
    elif lower.endswith(IMAGE_SUFFIXES):
        if options.terrain_size is None:
            raise ConfigError(
                "a height image needs its size: --terrain-size X,Y,Z (extent in x and y, height of white, in metres)",
                element=f"--terrain {path}",
            )
        size = options.terrain_size
        if not all(v > 0 and v < float("inf") for v in size):
            raise ConfigError(f"--terrain-size {size}: three positive finite numbers (m)")
        shape = HeightImage(os.path.abspath(path), size, src=loc)
    else:
        raise ConfigError(
            f"--terrain {path}: expected a mesh ({', '.join(MESH_SUFFIXES)}) or a grey PNG height image",
        )
    stem = os.path.splitext(os.path.basename(path))[0]
    body = StaticBody(name="terrain", colliders=[WorldCollider(name=stem or "terrain", shape=shape, src=loc)], src=loc)
    return World(name=stem or "terrain", file=path, bodies=[body], src=loc)


def _existing(path: str, flag: str) -> str:
    if not os.path.isfile(path):
        raise ParseError(f"{flag}: file not found", loc=SourceLoc(path))
    return path
