"""Placeholder asset files for a mujoco_menagerie model folder rebuilt file by file (issue 36).

menagerie is too large to fetch here (554 MB) and its meshes cannot be read, so a model folder is
rebuilt from its XML files alone (read one by one from the upstream repository) and every file those
XMLs reference gets a stand-in of the same name, so that MuJoCo and robodesc resolve every reference:

- a mesh (``.stl``, ``.obj``): the box from (-0.01, -0.01, -0.01) to (0.03, 0.02, 0.01) m, off the
  origin and with three different sides, so that MuJoCo's recentring of a mesh and a mesh-derived
  inertia are exercised, not cancelled out (binary STL, or text OBJ);
- a texture or height field image (``.png``): a 4x4 grey PNG.

What a placeholder changes: a body whose mass or inertia MuJoCo takes from its mesh geoms gets the
box's, on the source and in every output alike (so comparisons still hold, but the numbers are not the
real robot's); contacts on mesh colliders are boxes. Existing files are never overwritten.

    python benchmarks/menagerie_placeholders.py /work/menagerie/kuka_iiwa_14 [--dry-run]

The XMLs are found as MuJoCo finds them: every ``*.xml`` in the folder (and the files they
``<include>``), each ``<compiler meshdir|texturedir|assetdir>`` applied to the files it names.
"""

from __future__ import annotations

import argparse
import glob
import io
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
import trimesh
from PIL import Image

LOW = (-0.01, -0.01, -0.01)
HIGH = (0.03, 0.02, 0.01)
MESH_SUFFIXES = (".stl", ".obj")
IMAGE_SUFFIXES = (".png",)


def placeholder_box() -> trimesh.Trimesh:
    low, high = np.array(LOW), np.array(HIGH)
    box = trimesh.creation.box(extents=high - low)
    box.apply_translation((low + high) / 2)
    return box


def _compiler_dirs(root: ET.Element) -> dict[str, str] | None:
    for compiler in root.iter("compiler"):
        asset = compiler.get("assetdir", "")
        mesh = compiler.get("meshdir", asset)
        return {"mesh": mesh, "hfield": mesh, "skin": mesh, "texture": compiler.get("texturedir", asset)}
    return None


def referenced_files(folder: str) -> dict[str, str]:
    """Every asset file the folder's XMLs name: absolute path -> the XML that names it. MuJoCo's
    ``<compiler>`` is global to the model: a file without one (a scene, an included part) takes the
    one its model's other file has (menagerie writes one per model)."""
    xmls = sorted(glob.glob(os.path.join(folder, "**", "*.xml"), recursive=True))
    roots = {xml: ET.parse(xml).getroot() for xml in xmls}
    shared = next((d for d in map(_compiler_dirs, roots.values()) if d is not None), None)
    found: dict[str, str] = {}
    for xml, root in roots.items():
        dirs = _compiler_dirs(root) or shared or {"mesh": "", "hfield": "", "skin": "", "texture": ""}
        for tag, sub in dirs.items():
            for el in root.iter(tag):
                name = el.get("file")
                if name:
                    found[os.path.normpath(os.path.join(os.path.dirname(xml), sub, name))] = xml
    return found


def write_placeholder(path: str) -> str:
    """Write the stand-in for ``path``; returns what was written ('' when its kind has none)."""
    suffix = os.path.splitext(path)[1].lower()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if suffix in MESH_SUFFIXES:
        data = placeholder_box().export(file_type=suffix[1:])
        with open(path, "wb") as handle:
            handle.write(data if isinstance(data, bytes) else data.encode())
        return "box"
    if suffix in IMAGE_SUFFIXES:
        buffer = io.BytesIO()
        Image.new("RGB", (4, 4), (128, 128, 128)).save(buffer, format="PNG")
        with open(path, "wb") as handle:
            handle.write(buffer.getvalue())
        return "image"
    return ""


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folder")
    parser.add_argument("--dry-run", action="store_true")
    args = parser.parse_args()
    written, unknown = 0, []
    for path, xml in sorted(referenced_files(args.folder).items()):
        if os.path.exists(path):
            continue
        if args.dry_run:
            print(f"would write {path} (named in {xml})")
            continue
        if write_placeholder(path):
            written += 1
        else:
            unknown.append(f"{path} (named in {xml})")
    print(f"{args.folder}: {written} placeholders written")
    for line in unknown:
        print(f"no placeholder for this kind of file: {line}", file=sys.stderr)
    return 1 if unknown else 0


if __name__ == "__main__":
    raise SystemExit(main())
