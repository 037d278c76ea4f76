"""Mesh assets: every mesh under ``meshes/`` beside robot.xml, so the folder moves as one (as
mujoco_menagerie's do); STL and OBJ copied, every other format converted to OBJ.

MuJoCo reads STL, OBJ and MSH only. A COLLADA (or any trimesh-readable) file is read through
robodesc's own readers (:func:`robodesc.meshes.data.build_mesh`, scale applied) and written as an
OBJ under ``meshes/``. Copied and converted files are named after their content (a hash): two
sources with the same bytes are one file, and a later run that fails validation leaves the files an
earlier robot.xml refers to untouched. Only files from where the robot lives are copied (the input's
folder and its packages, meshes/roots.py); any other file, and every file under ``--mesh-paths
absolute``, is referenced where it is.
"""

from __future__ import annotations

import hashlib
import math
import os
import xml.etree.ElementTree as ET

from robodesc._files import escapes, write_atomic
from robodesc.emit.common.numbers import fmt_vec
from robodesc.emit.common.paths import PathMode, file_reference
from robodesc.emit.mjcf.context import MjcfContext
from robodesc.emit.mjcf.objsplit import split_by_material
from robodesc.ir.diagnostics import ConfigError
from robodesc.ir.geometry import RGBA, Mesh, Vec3
from robodesc.meshes.buffers import MeshData, MeshReadError, flat_box, obj_bytes
from robodesc.meshes.data import build_mesh
from robodesc.meshes.roots import allowed_roots, outside_roots

READABLE = (".stl", ".obj")
MESH_DIR = "meshes"
# MuJoCo reads binary STL only, and refuses more faces than this: other STL files are converted to OBJ.
STL_FACE_LIMIT = 200000
# The thin box's half thickness, m.
FLAT_HALF = 5e-5


class MeshAssets:
    """One ``<mesh>`` asset per (file, scale, collider or not), named after the file."""

    def __init__(self, ctx: MjcfContext) -> None:
        self.ctx = ctx
        self._by_key: dict[tuple[str, tuple[float, float, float] | None, bool], str] = {}
        self._names: set[str] = set()
        self._parts: dict[tuple[str, tuple[float, float, float] | None], list[tuple[str, RGBA | None]] | None] = {}
        self._roots: list[str] | None = None

    @property
    def roots(self) -> list[str]:
        """Where mesh files may be read from into the output (meshes/roots.py)."""
        if self._roots is None:
            self._roots = allowed_roots(self.ctx.robot)
        return self._roots

    def asset(self, mesh: Mesh, element: str, collider: bool) -> str | None:
        """The asset name for ``mesh``; None (with a warning) when MuJoCo could not load it."""
        ctx = self.ctx
        if mesh.path is None or not os.path.isfile(mesh.path):
            ctx.warn(
                "mjcf-missing-mesh",
                f"mesh {mesh.uri!r} does not exist: this geometry is left out (MuJoCo cannot load a missing file)",
                element,
                mesh.src,
            )
            return None
        # The hull cap only matters for colliders: visual meshes get their own asset without it.
        capped = collider and ctx.options.maxhullvert is not None
        key = (mesh.path, mesh.scale, capped)
        if key in self._by_key:
            return self._by_key[key]
        outside = outside_roots(mesh.path, self.roots)
        if outside is not None and not _referenced_as_is(mesh.path):
            # The rule of --copy-meshes and USD: converting is copying the file's content.
            ctx.warn(
                "mjcf-mesh-not-read",
                f"mesh {outside}; it is not converted to OBJ and this shape is left out "
                "(--copy-meshes refuses the same file)",
                element,
                mesh.src,
            )
            return None
        data = _loadable(mesh)
        if isinstance(data, str):
            # The source's mesh, not robodesc's output: MuJoCo would refuse the whole model for it.
            ctx.warn("mjcf-bad-mesh", f"mesh {mesh.uri!r} cannot be loaded ({data}): left out", element, mesh.src)
            return None
        ext = os.path.splitext(mesh.path)[1].lower()
        el = ET.Element("mesh")
        if ext == ".stl" and not 0 < _stl_faces(mesh.path) <= STL_FACE_LIMIT:
            ext = ".stl-unreadable"  # ASCII or over the limit: converted below
        if ext == ".obj" and obj_layout_mixed(mesh.path):
            ctx.warn(
                "mjcf-obj-layout",
                f"mesh {mesh.uri!r} mixes faces with and without normals or texture coordinates "
                "(`f 1/1/1 ...` and `f 1 2 3`), which MuJoCo refuses or misreads: converted to a plain OBJ "
                "(points and faces)",
                element,
                mesh.src,
            )
            ext = ".obj-mixed"  # converted below
        if ext in READABLE:
            file = self._copy(mesh, element)
            scale = mesh.scale
        else:
            file = self._convert(mesh.path, data)
            scale = None  # applied while converting
            ctx.info("mjcf-mesh-converted", f"{mesh.uri} converted to {file} (MuJoCo reads STL and OBJ)", element)
        name = self._name(os.path.splitext(os.path.basename(mesh.path))[0], capped)
        el.set("name", name)
        el.set("file", file)
        # MuJoCo computes every mesh's inertia even though geoms add no mass here
        # (inertiafromgeom="false"); an open or thin mesh has too little volume for the default
        # and would be refused, its surface is always enough.
        el.set("inertia", "shell")
        if scale is not None and scale != (1.0, 1.0, 1.0):
            el.set("scale", fmt_vec(scale))
        if capped:
            el.set("maxhullvert", str(ctx.options.maxhullvert))
        ctx.asset.append(el)
        self._by_key[key] = name
        return name

    def part_asset(self, rel: str, mesh: Mesh) -> str:
        """The asset of a convex part written under meshes/ (already scaled, see
        emit/common/decomposition.py); MuJoCo's hull of it is the part itself."""
        key = (rel, None, True)
        if key in self._by_key:
            return self._by_key[key]
        stem = os.path.splitext(os.path.basename(rel))[0].rsplit("_", 1)[0]  # without the digest
        name = self._name(stem, False)
        el = ET.SubElement(self.ctx.asset, "mesh", name=name, file=rel)
        el.set("inertia", "shell")  # see asset()
        if self.ctx.options.maxhullvert is not None:
            el.set("maxhullvert", str(self.ctx.options.maxhullvert))
        self._by_key[key] = name
        return name

    def flat_box(self, mesh: Mesh, element: str) -> tuple[Vec3, Vec3] | None:
        """(half sizes, centre) of a box standing in for a flat mesh; None for a solid one."""
        if mesh.path is None or not os.path.isfile(mesh.path):
            return None
        data = _loadable(mesh, min_vertices=3)
        if isinstance(data, str):
            return None  # asset() leaves it out and says why
        box = flat_box(data, 2 * FLAT_HALF)
        if box is None:
            return None
        self.ctx.warn(
            "mjcf-flat-mesh",
            f"mesh {mesh.uri!r} is flat: MuJoCo cannot build its convex hull, so a box of its extent "
            f"({FLAT_HALF * 2:g} m thick) stands in for it",
            element,
            mesh.src,
        )
        size, centre = box
        return (size[0] / 2, size[1] / 2, size[2] / 2), centre

    def visual_parts(self, mesh: Mesh) -> list[tuple[str, RGBA | None]] | None:
        """A multi-material OBJ visual as one asset per material, with that material's colour;
        None when the file is not such an OBJ."""
        if mesh.path is None or not mesh.path.lower().endswith(".obj") or not os.path.isfile(mesh.path):
            return None
        if outside_roots(mesh.path, self.roots) is not None:
            return None  # its parts would copy its content: referenced whole, where it is
        key = (mesh.path, mesh.scale)
        if key in self._parts:
            return self._parts[key]
        try:
            parts = split_by_material(mesh.path)
        except (ValueError, IndexError):
            parts = None  # a face MuJoCo would refuse too: the file is referenced whole
        out = None
        if parts is not None:
            out = []
            stem = os.path.splitext(os.path.basename(mesh.path))[0]
            for part in parts:
                el = ET.SubElement(self.ctx.asset, "mesh")
                el.set("name", self._name(f"{stem}_{part.material}", False))
                el.set("file", self._write(f"{stem}_{_safe(part.material)}", part.text))
                el.set("inertia", "shell")  # open parts of a closed mesh: see asset()
                if mesh.scale is not None and mesh.scale != (1.0, 1.0, 1.0):
                    el.set("scale", fmt_vec(mesh.scale))
                out.append((el.get("name", ""), part.rgba))
        self._parts[key] = out
        return out

    def _copy(self, mesh: Mesh, element: str) -> str:
        """``meshes/<stem>_<hash><ext>``, a copy of the file under the output folder; the file's own
        reference where the user asked for absolute paths, the file is already in the output folder
        (--copy-meshes put it there) or it lies outside where the robot lives."""
        from robodesc.meshes.roots import outside_roots

        assert mesh.path is not None
        ctx = self.ctx
        if ctx.mesh_paths is PathMode.ABSOLUTE or _inside(mesh.path, ctx.out_dir):
            return _reference(ctx, mesh)
        why = outside_roots(mesh.path, self.roots)
        if why is not None:
            ctx.warn("mjcf-mesh-not-copied", f"{why}: referenced where it is, not copied", element, mesh.src)
            return _reference(ctx, mesh)
        with open(mesh.path, "rb") as handle:
            data = handle.read()
        stem, ext = os.path.splitext(os.path.basename(mesh.path))
        return self._write(stem, data, ext.lower())

    def _name(self, stem: str, capped: bool) -> str:
        base = stem + ("_hull" if capped else "")
        name, n = base, 1
        while name in self._names:
            n += 1
            name = f"{base}_{n}"
        self._names.add(name)
        return name

    def _convert(self, path: str, data: MeshData) -> str:
        return self._write(os.path.splitext(os.path.basename(path))[0], obj_text(data))

    def _write(self, stem: str, text: bytes, ext: str = ".obj") -> str:
        digest = hashlib.sha256(text).hexdigest()[:12]
        rel = f"{MESH_DIR}/{stem}_{digest}{ext}"
        target = os.path.join(self.ctx.out_dir, MESH_DIR, f"{stem}_{digest}{ext}")
        real = escapes(self.ctx.out_dir, target)
        if real is not None:  # as --copy-meshes refuses (passes/copy_meshes.check_inside)
            raise ConfigError(
                f"{os.path.join(self.ctx.out_dir, MESH_DIR)!r} leads to {real!r}, outside the output folder: "
                "robodesc writes the converted meshes only inside the output path, never through a link that "
                "leaves it. Remove the link or choose another output"
            )
        if not os.path.isfile(target):
            os.makedirs(os.path.dirname(target), exist_ok=True)
            write_atomic(target, text)
        self.ctx.written[f"mesh:{rel}"] = target
        return rel


def _loadable(mesh: Mesh, min_vertices: int = 4) -> MeshData | str:
    """The mesh (scaled), or why MuJoCo would refuse its file: unreadable, a coordinate NaN or
    infinite, fewer than ``min_vertices`` vertices (MuJoCo's minimum, 4; a flat stand-in box needs 3)."""
    assert mesh.path is not None
    try:
        data = build_mesh(mesh.path, mesh.scale)
    except MeshReadError as exc:
        return str(exc)
    if not all(math.isfinite(v) for corner in data.extent for v in corner):
        return "a vertex coordinate is NaN or infinite"
    if len(data.points) < 3 * min_vertices:
        return f"{len(data.points) // 3} vertices; MuJoCo needs at least 4"
    return data


def _referenced_as_is(path: str) -> bool:
    """Whether MuJoCo reads the file where it is (a binary STL within its face limit, an OBJ whose
    faces MuJoCo reads); any other is converted, its content written into the output."""
    ext = os.path.splitext(path)[1].lower()
    if ext == ".stl":
        return 0 < _stl_faces(path) <= STL_FACE_LIMIT
    return ext == ".obj" and not obj_layout_mixed(path)


def _stl_faces(path: str) -> int:
    """The face count of a binary STL (0 for an ASCII or broken file)."""
    try:
        with open(path, "rb") as handle:
            head = handle.read(84)
    except OSError:
        return 0
    if len(head) < 84:
        return 0
    count = int.from_bytes(head[80:84], "little")
    # Binary when the size says so (binary headers often start with "solid" too).
    return count if os.path.getsize(path) == 84 + 50 * count else 0


def obj_layout_mixed(path: str) -> bool:
    """Whether the OBJ's face corners use more than one layout (``v``, ``v/t``, ``v//n``, ``v/t/n``).

    MuJoCo indexes one normal (and texture) table per mesh: with some corners giving a normal index
    and others not, it reads past the table ("mesh_facenormal normal index out of bounds") or pairs
    the wrong normals. pybullet_data's table_square.obj is such a file."""
    layouts: set[tuple[bool, bool]] = set()
    try:
        with open(path, "rb") as handle:
            for line in handle:
                if not line.startswith(b"f ") and not line.startswith(b"f\t"):
                    continue
                for corner in line.split()[1:]:
                    parts = corner.split(b"/")
                    layouts.add((len(parts) > 1 and bool(parts[1]), len(parts) > 2 and bool(parts[2])))
                    if len(layouts) > 1:
                        return True
    except OSError:
        return False
    return False


def _safe(name: str) -> str:
    """A material name as part of a file name."""
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in name) or "material"


def _inside(path: str, folder: str) -> bool:
    real, root = os.path.realpath(path), os.path.realpath(folder)
    return real.startswith(root.rstrip(os.sep) + os.sep)


def _reference(ctx: MjcfContext, mesh: Mesh) -> str:
    """MuJoCo resolves a relative file against the model's folder and knows no package://."""
    mode = ctx.mesh_paths if ctx.mesh_paths in (PathMode.RELATIVE, PathMode.ABSOLUTE) else PathMode.RELATIVE
    return file_reference(mesh.uri, mesh.path, mesh.package, mode, ctx.out_dir)


def obj_text(data: MeshData) -> bytes:
    """A Wavefront OBJ of the mesh's (float32) points and triangles."""
    return obj_bytes(data.points, data.face_vertex_indices, "written by robodesc")
