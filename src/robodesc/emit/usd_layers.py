"""Where the USD emitter's opinions go, and writing them atomically.

Single file: one anonymous layer, exported at the end (text through ``write_atomic``, crate files
through a temporary file in the target folder and ``os.replace``).

Layered (NVIDIA's converter layout)::

    robot.usda                  interface: stage metadata, /robot with a payload, /PhysicsScene
    Payload/Contents.usda       /robot itself; sublayers the three below
    Payload/Physics.usda        bodies, masses, colliders' physics APIs, joints, articulation
    Payload/Materials.usda      /robot/Looks and material bindings
    Payload/Geometry.usdc       link transforms, visual and collision shapes, frames, sensors

Everything is written into a staging folder beside the output, then moved into place (the payload
folder first, the interface file last, so a reader never sees an interface without its payload).
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Callable
from dataclasses import dataclass, field

from pxr import Sdf, Usd, UsdGeom, UsdPhysics

from robodesc.emit.files import replace_dir_atomic, write_atomic
from robodesc.emit.usd_context import GEOMETRY, MATERIALS, PHYSICS, check_identifier
from robodesc.ir.model import Robot

PAYLOAD_DIR = "Payload"
CONTENTS = "Contents"
# Strongest first; the three never disagree, the order only matters to someone layering over them.
SUBLAYERS = (("Physics", PHYSICS), ("Materials", MATERIALS), ("Geometry", GEOMETRY))


@dataclass
class LayerSet:
    stage: Usd.Stage
    root: Sdf.Layer
    ext: str
    layered: bool
    roles: dict[str, Sdf.Layer] = field(default_factory=dict)
    staging: str | None = None
    payload_dir: str = ""
    scene_author: Callable[[Usd.Stage], None] | None = None

    @staticmethod
    def create(path: str, layered: bool) -> LayerSet:
        ext = os.path.splitext(path)[1].lower()
        if not layered:
            root = Sdf.Layer.CreateAnonymous("robot" + ext)
            return LayerSet(Usd.Stage.Open(root), root, ext, False)
        out_dir = os.path.dirname(os.path.abspath(path))
        os.makedirs(out_dir, exist_ok=True)
        staging = tempfile.mkdtemp(prefix=".robodesc-usd-", dir=out_dir)
        sub_ext = ".usda" if ext == ".usda" else ".usdc"
        payload = os.path.join(staging, PAYLOAD_DIR)
        os.makedirs(payload)
        contents = Sdf.Layer.CreateNew(os.path.join(payload, CONTENTS + sub_ext))
        roles: dict[str, Sdf.Layer] = {}
        names = []
        for stem, role in SUBLAYERS:
            # Mesh arrays are the bulk of an asset: always binary (as NVIDIA's converter does).
            name = stem + (".usdc" if role == GEOMETRY else sub_ext)
            roles[role] = Sdf.Layer.CreateNew(os.path.join(payload, name))
            names.append(f"./{name}")
        contents.subLayerPaths = names
        stage = Usd.Stage.Open(contents)
        return LayerSet(
            stage,
            contents,
            ext,
            True,
            roles,
            staging,
            os.path.join(out_dir, PAYLOAD_DIR),
        )

    def add_physics_scene(self, author: Callable[[Usd.Stage], None]) -> None:
        if not self.layered:
            author(self.stage)
        else:
            self.scene_author = author

    def discard(self) -> None:
        if self.staging is not None and os.path.isdir(self.staging):
            shutil.rmtree(self.staging, ignore_errors=True)


def write_layers(layers: LayerSet, robot: Robot, path: str) -> None:
    if not layers.layered:
        _export(layers.root, path)
        return
    assert layers.staging is not None
    for layer in layers.roles.values():
        layer.Save()
    layers.root.Save()
    staged_interface = os.path.join(layers.staging, os.path.basename(path))
    interface = Sdf.Layer.CreateNew(staged_interface)
    _interface(interface, layers, robot)
    interface.Save()
    out_dir = os.path.dirname(os.path.abspath(path))
    replace_dir_atomic(os.path.join(layers.staging, PAYLOAD_DIR), os.path.join(out_dir, PAYLOAD_DIR))
    os.replace(staged_interface, path)


def _interface(layer: Sdf.Layer, layers: LayerSet, robot: Robot) -> None:
    stage = Usd.Stage.Open(layer, load=Usd.Stage.LoadNone)
    UsdGeom.SetStageMetersPerUnit(stage, 1.0)
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    UsdPhysics.SetStageKilogramsPerUnit(stage, 1.0)
    name = check_identifier(robot.name, f"robot {robot.name!r}", robot.src)
    robot_path = Sdf.Path.absoluteRootPath.AppendChild(name)
    prim = UsdGeom.Xform.Define(stage, robot_path).GetPrim()
    stage.SetDefaultPrim(prim)
    Usd.ModelAPI(prim).SetKind("component")
    Usd.ModelAPI(prim).SetAssetName(robot.name)
    if robot.display_name:
        prim.SetDisplayName(robot.display_name)
    contents = os.path.basename(layers.root.realPath)
    prim.GetPayloads().AddPayload(Sdf.Payload(f"./{PAYLOAD_DIR}/{contents}", robot_path))
    if layers.scene_author is not None:
        layers.scene_author(stage)


def _export(layer: Sdf.Layer, path: str) -> None:
    ext = os.path.splitext(path)[1].lower()
    if ext == ".usda":
        write_atomic(path, layer.ExportToString())
        return
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=".robodesc-", suffix=ext, dir=directory)
    os.close(fd)
    try:
        if not layer.Export(tmp):
            raise OSError(f"usd could not write {tmp}")
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
