"""An MJCF file and what it includes, read safely into one element tree.

The tree is what MuJoCo's own parser then compiles (:mod:`.compiled`), so every rule of the format
(``<default>`` classes and ``childclass``, ``angle``, ``eulerseq``, ``fromto``, frames) is MuJoCo's
rather than a copy of it. What reaches MuJoCo is checked here first, because a model file arrives
from the internet:

- Every file goes through :mod:`robodesc.frontends.xml_safety` (no DOCTYPE, no entities, a size cap).
- ``<include>`` is expanded here, not by MuJoCo: each included file must lie inside the model's
  folder (symlinks resolved), the nesting is capped and a file cannot include itself.
- Asset files (meshes, height fields) are resolved against ``meshdir``/``assetdir`` and must lie
  inside the folder too; MuJoCo gets absolute paths, so it opens nothing else.
- Plugins (``<extension>``, ``<plugin>``) would load and run native code: they are removed, with a
  warning. Textures and skins are removed too: images MuJoCo would decode (a builtin texture of any
  size it allocates) carry no mass or shape. ``<replicate>`` is capped so a small file cannot
  expand into millions of bodies.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from lxml import etree

from robodesc.frontends.xml_safety import parse_xml, read_file
from robodesc.ir.diagnostics import BrokenReferenceError, Findings, ParseError, PathEscapeError, SourceLoc

STAGE = "frontend:mjcf"
MAX_INCLUDE_DEPTH = 16
MAX_INCLUDED_FILES = 256
# Bodies ``<replicate>`` may make in all (menagerie's largest model has a few hundred bodies).
MAX_REPLICATED = 10_000
# Elements removed before MuJoCo compiles the tree, and why (the message's end).
_ALL = "URDF, SDF, USD and MJCF outputs leave it out"
# Elements removed before MuJoCo compiles the tree: (code, why, said once per file set).
_REMOVED = {
    "extension": ("mjcf-removed", "plugins load and run native code; no output has it", False),
    "plugin": ("mjcf-removed", "plugins load and run native code; no output has it", False),
    "skin": ("mjcf-removed", "skins are drawn only; no output has it", True),
    # Information only: a material keeps its 2D texture's image file (the IR's material texture).
    "texture": (
        "mjcf-texture",
        "textures are not decoded; a material's 2D texture is kept as its image file's reference, builtin "
        "textures and skyboxes (a scene's) are left out",
        True,
    ),
    # Deformables read mesh files and allocate per vertex and per count: removed before compiling.
    "flexcomp": ("mjcf-not-held", f"a flexcomp (a deformable body) has no IR form: {_ALL}", False),
    "composite": ("mjcf-not-held", f"a composite (generated bodies) has no IR form: {_ALL}", False),
    "flex": ("mjcf-not-held", f"a flex (a deformable body) has no IR form: {_ALL}", False),
}
# <size> attributes that make MuJoCo allocate (the arena, the stack): not the robot's.
_SIZE_MEMORY = ("memory", "nstack", "njmax", "nconmax", "nuserdata", "nkey")


@dataclass(slots=True)
class MjcfSource:
    """The expanded tree, the file of every element that came from an include, and the asset folders."""

    root: etree._Element
    file: str
    folder: str
    files: dict[etree._Element, str] = field(default_factory=dict)
    # Mesh assets whose file is missing: their name -> the path as written (resolved, absolute).
    missing_meshes: dict[str, str] = field(default_factory=dict)
    # Mesh asset name -> (file as written, absolute path or None).
    mesh_files: dict[str, tuple[str, str | None]] = field(default_factory=dict)
    # Texture name -> (file as written, absolute path); material name -> its texture's name. The IR's
    # materials keep the image's reference (MuJoCo never decodes it: textures are removed).
    textures: dict[str, tuple[str, str]] = field(default_factory=dict)
    material_textures: dict[str, str] = field(default_factory=dict)
    # How many includes were expanded (capped: a file may include another many times over).
    included: int = 0
    # The ``model`` names of the included files, in order (a scene names its robot's file).
    included_models: list[str] = field(default_factory=list)

    def loc(self, el: etree._Element) -> SourceLoc:
        """``file:line`` of an element, in the file it was written in."""
        return SourceLoc(self._file_of(el), line(el))

    def _file_of(self, el: etree._Element) -> str:
        node: etree._Element | None = el
        while node is not None:
            found = self.files.get(node)
            if found is not None:
                return found
            node = node.getparent()
        return self.file


def line(el: etree._Element) -> int | None:
    number = el.sourceline
    return number if isinstance(number, int) else None


def tag(el: etree._Element) -> str:
    return etree.QName(el).localname if isinstance(el.tag, str) else ""


def read_source(path: str, findings: Findings) -> MjcfSource:
    """Read ``path`` and everything it includes, and make its asset paths absolute and confined."""
    path = os.path.abspath(path)
    root = parse_xml(read_file(path), path, findings)
    if tag(root) != "mujoco":
        raise ParseError(f"root element is <{tag(root)}>, expected <mujoco>", loc=SourceLoc(path, line(root)))
    folder = os.path.realpath(os.path.dirname(path))
    source = MjcfSource(root=root, file=path, folder=folder)
    _expand_includes(source, root, path, [os.path.realpath(path)], findings)
    _check_replicate(source)
    _textures(source)
    _remove_unsafe(source, findings)
    _resolve_assets(source, findings)
    return source


def _inside(folder: str, path: str) -> bool:
    real = os.path.realpath(path)
    return real == folder or real.startswith(folder.rstrip(os.sep) + os.sep)


def _expand_includes(source: MjcfSource, node: etree._Element, file: str, chain: list[str], findings: Findings) -> None:
    for el in list(node):
        if not isinstance(el.tag, str):
            continue
        if tag(el) != "include":
            _expand_includes(source, el, file, chain, findings)
            continue
        loc = SourceLoc(file, line(el))
        name = el.get("file")
        if not name:
            raise ParseError("<include> has no file attribute", element="include", loc=loc)
        if len(chain) > MAX_INCLUDE_DEPTH:
            raise ParseError(f"includes nest deeper than {MAX_INCLUDE_DEPTH} files", element="include", loc=loc)
        # MuJoCo resolves an include against the main model's folder; a path relative to the including
        # file is accepted too, as MuJoCo 3.2+ does for nested includes.
        candidates = [os.path.join(os.path.dirname(file), name), os.path.join(os.path.dirname(source.file), name)]
        target = next((c for c in candidates if os.path.exists(c)), candidates[0])
        if not _inside(source.folder, target):
            raise PathEscapeError(
                f"<include file={name!r}> lies outside the model's folder {source.folder}; refused",
                element="include",
                loc=loc,
            )
        if not os.path.exists(target):
            raise BrokenReferenceError(f"<include file={name!r}>: file not found", element="include", loc=loc)
        real = os.path.realpath(target)
        if real in chain:
            raise ParseError(f"<include file={name!r}> includes itself (through {len(chain)} files)", loc=loc)
        source.included += 1
        if source.included > MAX_INCLUDED_FILES:
            raise ParseError(f"more than {MAX_INCLUDED_FILES} includes; refused", element="include", loc=loc)
        included = parse_xml(read_file(target), target, findings)
        if tag(included) != "mujoco":
            raise ParseError(
                f"included file's root is <{tag(included)}>, expected <mujoco>", loc=SourceLoc(target, line(included))
            )
        if included.get("model"):
            source.included_models.append(included.get("model", ""))
        _expand_includes(source, included, target, [*chain, real], findings)
        parent = el.getparent()
        assert parent is not None
        position = parent.index(el)
        parent.remove(el)
        for offset, child in enumerate(list(included)):
            if isinstance(child.tag, str):
                source.files.setdefault(child, target)
            parent.insert(position + offset, child)


def _check_replicate(source: MjcfSource) -> None:
    def count(el: etree._Element, factor: int) -> int:
        total = 0
        for child in el:
            if not isinstance(child.tag, str):
                continue
            name = tag(child)
            if name == "replicate":
                try:
                    times = int(child.get("count", "1"))
                except ValueError:
                    raise ParseError("count is not an integer", element="replicate", loc=source.loc(child)) from None
                total += count(child, factor * max(times, 0))
            else:
                total += (factor if name == "body" else 0) + count(child, factor)
            if total > MAX_REPLICATED:
                raise ParseError(
                    f"<replicate> would make more than {MAX_REPLICATED} bodies; refused",
                    element="replicate",
                    loc=source.loc(child),
                )
        return total

    count(source.root, 1)


def _textures(source: MjcfSource) -> None:
    """The image files of 2D textures, confined like meshes (a texture outside the folder is not kept)."""
    texturedir = assetdir = ""
    for compiler in source.root.iter("compiler"):
        texturedir = compiler.get("texturedir", texturedir)
        assetdir = compiler.get("assetdir", assetdir)
    base = os.path.dirname(source.file)
    for el in source.root.iter("texture"):
        parent = el.getparent()
        written = el.get("file")
        if parent is None or tag(parent) != "asset" or not written or el.get("type", "cube") != "2d":
            continue
        path = os.path.normpath(os.path.join(base, texturedir or assetdir, written))
        name = el.get("name") or os.path.splitext(os.path.basename(written))[0]
        if _inside(source.folder, path):
            source.textures[name] = (written, path)
    for el in source.root.iter("material"):
        if el.get("name") and el.get("texture"):
            source.material_textures[el.get("name", "")] = el.get("texture", "")


def _remove_unsafe(source: MjcfSource, findings: Findings) -> None:
    said: set[str] = set()
    for el in list(source.root.iter()):
        if not isinstance(el.tag, str) or not _attached(el, source.root):
            continue
        name = tag(el)
        parent = el.getparent()
        assert parent is not None
        removed = _REMOVED.get(name)
        if name == "flex" and tag(parent) == "equality":
            removed = ("mjcf-equality-not-held", f"a flex equality has no IR form: {_ALL}", False)
        if removed is not None:
            code, why, once = removed
            if not once or name not in said:
                label = el.get("name") or el.get("plugin") or el.get("instance") or ""
                say = findings.info if code == "mjcf-texture" else findings.warn
                say(
                    code,
                    f"<{name}{' ' + repr(label) if label else ''}> removed before reading: {why}",
                    element=name,
                    loc=source.loc(el),
                    stage=STAGE,
                )
                said.add(name)
            parent.remove(el)
            continue
        if name == "size":
            _drop(el, *_SIZE_MEMORY)
        for attr in ("texture", "plugin"):
            if attr in el.attrib and name in ("material", "geom", "body", "actuator", "sensor", "general", "mesh"):
                del el.attrib[attr]
        if name == "material":
            # A material that only named its texture keeps its colour.
            _drop(el, "texrepeat", "texuniform")
        if name == "layer":  # MuJoCo 3.3's <material><layer texture=...>
            parent.remove(el)


# What MuJoCo reads as a mesh file (it picks the reader by the suffix).
_ASSET_SUFFIXES = (".stl", ".obj", ".msh")


def _usable(path: str) -> bool:
    """A regular file (no pipe or device), under the size cap, with a suffix MuJoCo reads."""
    from robodesc.frontends.xml_safety import MAX_BYTES, is_regular_file

    return path.lower().endswith(_ASSET_SUFFIXES) and is_regular_file(path) and os.path.getsize(path) <= MAX_BYTES


def _drop(el: etree._Element, *attrs: str) -> None:
    for attr in attrs:
        if attr in el.attrib:
            del el.attrib[attr]


def _attached_model(source: MjcfSource, el: etree._Element, base: str, findings: Findings) -> None:
    """An ``<asset><model file>`` that ``<attach>`` places (MuJoCo 3.2+): MuJoCo reads that file itself,
    so it is checked here as an include is, and may not reach further files of its own."""
    written = el.get("file")
    parent = el.getparent()
    if written is None or parent is None or tag(parent) != "asset":
        return
    path = os.path.normpath(os.path.join(base, written))
    label = f"model {el.get('name') or written!r}"
    if not _inside(source.folder, path):
        raise PathEscapeError(
            f"<model file={written!r}> lies outside the model's folder {source.folder}; refused",
            element=label,
            loc=source.loc(el),
        )
    if not os.path.exists(path):
        raise BrokenReferenceError(f"<model file={written!r}>: file not found", element=label, loc=source.loc(el))
    attached = parse_xml(read_file(path), path, findings)
    if any(
        tag(e) in ("include", "model", "mesh", "hfield", "texture", "skin", "plugin", "extension") and e.get("file")
        for e in attached.iter()
        if isinstance(e.tag, str)
    ) or any(True for _ in attached.iter("plugin", "extension")):
        raise ParseError(
            "an attached model that reads further files (meshes, includes, models) or plugins is not supported "
            "yet; include its elements with <include> instead",
            element=label,
            loc=source.loc(el),
        )
    el.set("file", os.path.realpath(path))


def _attached(el: etree._Element, root: etree._Element) -> bool:
    """Whether ``el`` is still in the tree (not inside an element removed before it)."""
    node = el.getparent()
    while node is not None and node is not root:
        node = node.getparent()
    return node is root


def _resolve_assets(source: MjcfSource, findings: Findings) -> None:
    """Absolute, confined asset paths; ``meshdir``/``assetdir``/``texturedir`` are then dropped."""
    meshdir = assetdir = ""
    for compiler in source.root.iter("compiler"):
        meshdir = compiler.get("meshdir", meshdir)
        assetdir = compiler.get("assetdir", assetdir)
        _drop(compiler, "meshdir", "texturedir", "assetdir")
    base = os.path.dirname(source.file)
    for el in list(source.root.iter("model")):
        _attached_model(source, el, base, findings)
    _remove_height_fields(source, findings)
    for el in list(source.root.iter("mesh")):
        parent = el.getparent()
        if parent is None or tag(parent) != "asset":
            continue  # a <default>'s <mesh> holds no file
        written = el.get("file")
        if written is None:
            continue
        path = os.path.normpath(os.path.join(base, meshdir or assetdir, written))
        name = el.get("name") or os.path.splitext(os.path.basename(written))[0]
        usable = _usable(path)
        if usable and not _inside(source.folder, path):
            findings.info(
                "mjcf-asset-outside",
                f"<mesh file={written!r}> lies outside the model's folder; read as a mesh (a regular file with a "
                "mesh suffix), as URDF meshes are",
                element=f"mesh {name!r}",
                loc=source.loc(el),
                stage=STAGE,
            )
        source.mesh_files[name] = (written, path if usable else None)
        if not usable:
            source.missing_meshes[name] = path
            continue
        el.set("file", path)


def _remove_height_fields(source: MjcfSource, findings: Findings) -> None:
    """Height fields, and the geoms on them, are removed before MuJoCo compiles: the IR has no height
    field, and MuJoCo would decode a PNG (or allocate nrow x ncol samples) of any size."""
    for el in list(source.root.iter("hfield")):
        parent = el.getparent()
        if parent is not None and tag(parent) == "asset":
            parent.remove(el)
    for el in list(source.root.iter("geom")):
        parent = el.getparent()
        if parent is None or not el.get("hfield"):
            continue
        label = el.get("name") or el.get("hfield", "")
        findings.warn(
            "mjcf-shape-not-held",
            f"a height field geom ({label!r}) has no IR shape: URDF, SDF, USD and MJCF outputs leave it out",
            element="geom",
            loc=source.loc(el),
            stage=STAGE,
        )
        parent.remove(el)
