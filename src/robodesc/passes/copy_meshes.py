"""Copy every resolved mesh and texture next to the output, for emitters (``copy_meshes``).

Not in the pipeline (it needs the output folder): an emitter calls
``copy_meshes(robot, out_dir, ctx)`` before writing. Files go to ``<out_dir>/meshes/``; two different
sources with the same file name get ``<stem>_1<ext>``, ``<stem>_2<ext>`` ... in encounter order (the
same source file is copied once). ``Mesh.path`` (and ``Material.texture_path``) point at the copy,
``Mesh.uri`` becomes ``meshes/<name>`` and the package reference is dropped, so every path mode
writes a portable reference. With ``convert_meshes`` (e.g. ``{".dae": ".obj"}``) files with those
suffixes are converted through trimesh instead of copied, with a finding.

Only meshes and textures are copied, and only from where the robot lives (docs/security.md): a
file is copied when its real path (symlinks followed) lies inside the input's folder or a package
root the robot's ``package://`` references resolved to, and when it reads as what its suffix says
(STL, OBJ and COLLADA through robodesc's mesh readers; other formats and textures by their
signature). Anything else (an absolute path or ``file://`` URI to a system file, ``../`` out of the
input's folder, a symlink to ``/etc/passwd``) gets a ``mesh-not-copied`` warning and keeps its
original reference.

Limitation: files a mesh refers to internally (textures inside a DAE or OBJ's .mtl) are not copied.
"""

from __future__ import annotations

import os
import shutil
import stat
import tempfile
from typing import Any

from robodesc._files import escapes
from robodesc.ir.diagnostics import ConfigError
from robodesc.ir.geometry import Material, Mesh
from robodesc.ir.model import Robot
from robodesc.meshes.roots import allowed_roots, outside_roots
from robodesc.passes.context import PassContext

__all__ = ["allowed_roots", "copy_meshes", "refusal"]

NAME = "copy_meshes"
SUBDIR = "meshes"

# Signatures of the formats checked without a full read (lower-case suffix -> accepted prefixes).
_SIGNATURES: dict[str, tuple[bytes, ...]] = {
    ".glb": (b"glTF",),
    ".ply": (b"ply",),
    ".png": (b"\x89PNG",),
    ".jpg": (b"\xff\xd8\xff",),
    ".jpeg": (b"\xff\xd8\xff",),
    ".bmp": (b"BM",),
    ".tif": (b"II*\x00", b"MM\x00*"),
    ".tiff": (b"II*\x00", b"MM\x00*"),
    ".exr": (b"\x76\x2f\x31\x01",),
}
_READ_AS_MESH = (".stl", ".obj", ".dae")


def refusal(source: str, roots: list[str], texture: bool) -> str | None:
    """Why ``source`` must not be copied, or ``None``."""
    outside = outside_roots(source, roots)
    if outside is not None:
        return outside + "; not copied"
    real = os.path.realpath(source)
    try:
        mode = os.stat(real).st_mode
    except OSError as exc:
        return f"{source!r} cannot be read: {exc.strerror}"
    if not stat.S_ISREG(mode):
        return f"{source!r} is not a regular file; not copied"
    suffix = os.path.splitext(source)[1].lower()
    if not texture and suffix in _READ_AS_MESH:
        from robodesc.meshes.data import build_mesh

        try:
            build_mesh(real, None)
        except Exception as exc:  # any reader failure means: not a mesh of this kind
            return f"{source!r} does not read as a {suffix[1:].upper()} mesh ({exc}); not copied"
        return None
    signatures = _SIGNATURES.get(suffix)
    if signatures is None:
        kind = "texture" if texture else "mesh"
        return f"{source!r}: robodesc cannot check that a {suffix or 'suffix-less'} file is a {kind}; not copied"
    with open(real, "rb") as handle:
        head = handle.read(16)
    if not head.startswith(signatures):
        return f"{source!r} does not start like a {suffix[1:].upper()} file; not copied"
    return None


class _Copier:
    def __init__(self, out_dir: str, ctx: PassContext) -> None:
        self.dir = os.path.join(os.path.abspath(out_dir), SUBDIR)
        check_inside(out_dir, self.dir)
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


def check_inside(out_dir: str, target: str) -> None:
    """Refuse to write ``target`` when a symlink already in the output folder (``meshes`` pointing
    elsewhere) would carry the write outside it. Outputs are written only inside the output path."""
    if not os.path.lexists(target):
        return
    real = escapes(out_dir, target)
    if real is not None:
        raise ConfigError(
            f"--copy-meshes: {target!r} is a symlink to {real!r}, outside the output folder; robodesc writes "
            "only inside the output path, never through a link that leaves it. Remove the link or choose "
            "another output"
        )


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def copy_meshes(
    robot: Robot, out_dir: str, ctx: PassContext, kinds: frozenset[str] = frozenset({"meshes", "textures"})
) -> Robot:
    """Copy the ``kinds`` of file (``meshes``, ``textures``) the output will refer to (``Target.copies``)."""
    copier = _Copier(out_dir, ctx)
    copied = 0
    roots = allowed_roots(robot)

    def allowed(path: str, element: str, texture: bool) -> bool:
        why = refusal(path, roots, texture)
        if why is not None:
            ctx.warn("mesh-not-copied", why, element=element, stage=NAME)
        return why is None

    def mesh(m: Mesh, element: str) -> None:
        nonlocal copied
        if "meshes" not in kinds:
            return
        if m.path is None or not os.path.isfile(m.path):
            ctx.warn("mesh-not-copied", f"mesh {m.uri!r} has no file to copy", element=element, stage=NAME)
            return
        if not allowed(m.path, element, texture=False):
            return
        name = copier.place(m.path, element, convert=True)
        if name is not None:
            m.path = os.path.join(copier.dir, name)
            m.uri = f"{SUBDIR}/{name}"
            m.package = None
            copied += 1

    def texture(mat: Material, element: str) -> None:
        nonlocal copied
        if "textures" not in kinds:
            return
        if mat.texture_path is None or not os.path.isfile(mat.texture_path):
            return
        if not allowed(mat.texture_path, element, texture=True):
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
