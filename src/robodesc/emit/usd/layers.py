"""Where the USD emitter's opinions go, and writing them atomically.

Single file: one layer, written through ``write_atomic`` as text (``.usda``) or as a crate file
(``.usdc``, and ``.usd``, whose default encoding is the crate).

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

import math
import os
from array import array
from dataclasses import dataclass, field

from robodesc._files import Content, staged_folder, write_atomic, write_files
from robodesc.emit.usd.context import GEOMETRY, MATERIALS, PHYSICS, ROLES
from robodesc.ir.diagnostics import ConfigError
from robodesc.usdfile.spec import Attribute, Layer, Payload, Prim, value_type
from robodesc.usdfile.usda import usda_text

PAYLOAD_DIR = "Payload"
CONTENTS = "Contents"
# Strongest first; the three never disagree, the order only matters to someone layering over them.
SUBLAYERS = (("Physics", PHYSICS), ("Materials", MATERIALS), ("Geometry", GEOMETRY))


@dataclass
class LayerSet:
    """The layers of one asset: ``roles`` maps each kind of opinion to the layer it goes to."""

    ext: str
    layered: bool
    main: Layer  # the single file, or the payload's Contents layer
    roles: dict[str, Layer] = field(default_factory=dict)
    interface: Layer | None = None

    @staticmethod
    def create(path: str, layered: bool) -> LayerSet:
        ext = os.path.splitext(path)[1].lower()
        main = Layer()
        if not layered:
            return LayerSet(ext, False, main, dict.fromkeys(ROLES, main))
        return LayerSet(ext, True, main, {role: Layer() for _, role in SUBLAYERS}, Layer())

    def sub_ext(self, role: str | None) -> str:
        # Mesh arrays are the bulk of an asset: always binary (as NVIDIA's converter does).
        if role == GEOMETRY or self.ext != ".usda":
            return ".usdc"
        return ".usda"


def stage_metadata(layer: Layer, default_prim: str) -> None:
    layer.default_prim = default_prim
    layer.meters_per_unit = 1.0
    layer.kilograms_per_unit = 1.0
    layer.up_axis = "Z"


def robot_prim(layer: Layer, name: str, display_name: str | None) -> Prim:
    """The default prim: an Xform of kind component, named as the asset."""
    prim = layer.prim(f"/{name}", "Xform")
    prim.kind = "component"
    prim.asset_name = name
    if display_name:
        prim.display_name = display_name
    return prim


FLOAT32_MAX = 3.4028234663852886e38


def check_float32(layer: Layer) -> None:
    """Refuse a float/half attribute whose value float32 cannot hold (the .usdc writer could not
    pack it; .usda would write ``inf``), naming the prim and attribute. The verifier bounds the
    robot's own numbers; this catches what options and unit conversion make of them (a
    ``--stiffness 1e300`` becomes 1.7e298 per degree)."""
    stack: list[tuple[str, Prim]] = [("", layer.root)]
    while stack:
        path, prim = stack.pop()
        for prop in prim.properties.values():
            if not isinstance(prop, Attribute) or prop.value is None:
                continue
            try:
                scalar = value_type(prop.type_name)[0].scalar
            except KeyError:
                continue
            if scalar not in ("float", "half"):
                continue
            value = prop.value
            if isinstance(value, array) and value.typecode == "f":
                continue  # already float32 (mesh points)
            bad = _beyond_float32(value)
            if bad is not None:
                raise ConfigError(
                    f"USD attribute {path}.{prop.name} ({prop.type_name}) would be {bad:g}, beyond float32's "
                    f"±{FLOAT32_MAX:.4g}; lower the option or value that produced it"
                )
        for name, child in prim.children.items():
            stack.append((f"{path}/{name}", child))


def _beyond_float32(value: object) -> float | None:
    if isinstance(value, float | int) and not isinstance(value, bool):
        return float(value) if math.isfinite(value) and abs(value) > FLOAT32_MAX else None
    if isinstance(value, tuple | list | array):
        try:  # a flat vector of numbers, as nearly all are: one pass in C
            if max(map(abs, value), default=0.0) <= FLOAT32_MAX:
                return None
        except TypeError:  # nested (an array of tuples) or not numbers: item by item
            pass
        for item in value:
            found = _beyond_float32(item)
            if found is not None:
                return found
    return None


def encode(layer: Layer, ext: str) -> Content:
    """The layer's file content; a .usdc layer as pieces, its mesh arrays views of the meshes."""
    check_float32(layer)
    if ext == ".usda":
        return usda_text(layer)
    from robodesc.usdfile.usdc import usdc_chunks

    return usdc_chunks(layer)


def write_layers(layers: LayerSet, path: str, robot_name: str) -> None:
    """Write the asset; ``layers.main`` (and the interface) must already hold the robot prim."""
    if not layers.layered:
        write_atomic(path, encode(layers.main, layers.ext))
        return
    assert layers.interface is not None
    contents = CONTENTS + layers.sub_ext(None)
    files: dict[str, Content] = {}
    for stem, role in SUBLAYERS:
        name = stem + layers.sub_ext(role)
        layers.main.sublayers.append(f"./{name}")
        files[name] = encode(layers.roles[role], layers.sub_ext(role))
    files[contents] = encode(layers.main, layers.sub_ext(None))
    interface = layers.interface
    stage_metadata(interface, robot_name)
    prim = interface.root.children[robot_name]
    prim.payloads.append(Payload(f"./{PAYLOAD_DIR}/{contents}", f"/{robot_name}"))
    out_dir = os.path.dirname(os.path.abspath(path))
    # The payload folder first, the interface last: a reader never sees an interface without its payload.
    with staged_folder(os.path.join(out_dir, PAYLOAD_DIR)) as staging:
        write_files(staging, files)
    write_atomic(path, encode(interface, layers.ext))
