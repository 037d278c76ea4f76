"""Copy every resolved mesh and texture next to the output, for emitters (``copy_meshes``).

Not in the pipeline (it needs the output folder): an emitter calls
``copy_meshes(robot, out_dir, ctx)`` before writing. Files go to ``<out_dir>/meshes/``; two different
sources with the same file name get ``<stem>_1<ext>``, ``<stem>_2<ext>`` ... in encounter order (the
same source file is copied once). ``Mesh.path`` (and ``Material.texture_path``) point at the copy,
``Mesh.uri`` becomes ``meshes/<name>`` and the package reference is dropped, so every path mode
writes a portable reference. With ``convert_meshes`` (e.g. ``{".dae": ".obj"}``) files with those
suffixes are converted through trimesh instead of copied, with a finding.

Limitation: files a mesh refers to internally (textures inside a DAE or OBJ's .mtl) are not copied.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from typing import Any

from robodesc.ir.geometry import Material, Mesh
from robodesc.ir.model import Robot
from robodesc.passes.context import PassContext

NAME = "copy_meshes"
SUBDIR = "meshes"


class _Copier:
    def __init__(self, out_dir: str, ctx: PassContext) -> None:
        self.dir = os.path.join(os.path.abspath(out_dir), SUBDIR)
        self.ctx = ctx
        self.done: dict[tuple[str, str], str] = {}  # (source, target suffix) -> copied file name
        self.taken: set[str] = set()

    def _name_for(self, source: str, suffix: str) -> str:
        stem = os.path.splitext(os.path.basename(source))[0]
        name, i = f"{stem}{suffix}", 0
        while name.lower() in self.taken:  # case-insensitive file systems
            i += 1
            name = f"{stem}_{i}{suffix}"
        self.taken.add(name.lower())
        return name

    def place(self, source: str, element: str, convert: bool) -> str | None:
        """The copied file's name inside ``meshes/``, or ``None`` when the source cannot be used."""
        suffix = os.path.splitext(source)[1]
        target_suffix = self.ctx.options.convert_meshes.get(suffix.lower(), suffix) if convert else suffix
        key = (os.path.abspath(source), target_suffix)
        if key in self.done:
            return self.done[key]
        name = self._name_for(source, target_suffix)
        os.makedirs(self.dir, exist_ok=True)
        target = os.path.join(self.dir, name)
        fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=target_suffix, dir=self.dir)
        os.close(fd)
        try:
            if target_suffix != suffix:
                import trimesh

                loaded: Any = trimesh.load(source, force="mesh")
                # Geometry only: an exported .mtl would land beside every converted file under one name.
                trimesh.Trimesh(vertices=loaded.vertices, faces=loaded.faces, process=False).export(tmp)
                self.ctx.info(
                    "mesh-converted",
                    f"{os.path.basename(source)!r} converted to {name!r}, geometry only "
                    f"(the target cannot read {suffix})",
                    element=element,
                    stage=NAME,
                )
            else:
                shutil.copyfile(source, tmp)
            os.chmod(tmp, 0o666 & ~_umask())  # mkstemp made it 0600; a copy gets the usual mode
            os.replace(tmp, target)
        except Exception as exc:
            if os.path.exists(tmp):
                os.unlink(tmp)
            self.ctx.warn("mesh-not-copied", f"{source!r} could not be copied: {exc}", element=element, stage=NAME)
            return None
        self.done[key] = name
        return name


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def copy_meshes(robot: Robot, out_dir: str, ctx: PassContext) -> Robot:
    copier = _Copier(out_dir, ctx)
    copied = 0

    def mesh(m: Mesh, element: str) -> None:
        nonlocal copied
        if m.path is None or not os.path.isfile(m.path):
            ctx.warn("mesh-not-copied", f"mesh {m.uri!r} has no file to copy", element=element, stage=NAME)
            return
        name = copier.place(m.path, element, convert=True)
        if name is not None:
            m.path = os.path.join(copier.dir, name)
            m.uri = f"{SUBDIR}/{name}"
            m.package = None
            copied += 1

    def texture(mat: Material, element: str) -> None:
        nonlocal copied
        if mat.texture_path is None or not os.path.isfile(mat.texture_path):
            return
        name = copier.place(mat.texture_path, element, convert=False)
        if name is not None:
            mat.texture_path = os.path.join(copier.dir, name)
            mat.texture = f"{SUBDIR}/{name}"
            copied += 1

    for mat in robot.materials:
        texture(mat, f"material {mat.name!r}")
    for link in robot.links:
        label = f"link {link.name!r}"
        for visual in link.visuals:
            if isinstance(visual.geometry, Mesh):
                mesh(visual.geometry, label)
            if visual.material is not None:
                texture(visual.material, label)
        for collision in link.collisions:
            if isinstance(collision.geometry, Mesh):
                mesh(collision.geometry, label)
    if copied:
        ctx.info(
            "meshes-copied",
            f"{len(copier.done)} file(s) written to {copier.dir} for {copied} reference(s)",
            element=f"robot {robot.name!r}",
            stage=NAME,
        )
    return robot
