"""The SDF model robodesc reads, and the models it nests: files, ``model.config`` and ``<include>``.

A file is read with the hardened parser (frontends/xml_safety.py). Its ``<model>`` and every model
nested in it (written in place or brought in by ``<include>``) become one :class:`Scope` each,
named as libsdformat scopes them (``arm::hand``). Includes resolve through ``--model-path`` and
Gazebo's environment variables as a world's do (:mod:`.model_path`); a missing one is a warning and
the model is read without it. An included model's relative paths must stay inside its folder.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, field

from lxml import etree

from robodesc.frontends.sdf.model_path import model_roots, resolve_uri
from robodesc.frontends.sdf.values import loc, tag
from robodesc.frontends.xml_safety import parse_xml, read_file
from robodesc.ir.diagnostics import Findings, ParseError, SourceLoc

STAGE = "frontend:sdf"
# The versions whose model semantics robodesc applies (libsdformat converts 1.4 to 1.6 forward).
VERSIONS = ("1.4", "1.5", "1.6", "1.7", "1.8", "1.9", "1.10", "1.11")
# Includes nested deeper than this are a loop of models including each other.
MAX_DEPTH = 16


@dataclass(slots=True)
class Scope:
    """One ``<model>``: ``name`` is its scoped name ("" for the model read), ``pose`` the element
    that places it in its parent (an include's ``<pose>`` over the model's own)."""

    name: str
    element: etree._Element
    file: str
    version: str
    # Folder relative URIs resolve against; ``confined``: they may not leave it (an included model).
    folder: str
    confined: bool
    parent: Scope | None = None
    pose: etree._Element | None = None
    pose_file: str = ""
    static: bool = False
    children: list[Scope] = field(default_factory=list)

    def scoped(self, name: str) -> str:
        return f"{self.name}::{name}" if self.name else name

    @property
    def frame(self) -> str:
        """The scoped name of this model's frame."""
        return self.name or "__model__"


@dataclass(slots=True)
class Source:
    file: str
    top: Scope
    roots: list[str]

    def scopes(self) -> list[Scope]:
        out: list[Scope] = []
        stack = [self.top]
        while stack:
            scope = stack.pop(0)
            out.append(scope)
            stack[0:0] = scope.children
        return out


def sdf_file_of(path: str) -> str:
    """The SDF file a path names: the file itself, or the one a model folder's ``model.config``
    names (the highest version it lists)."""
    config = os.path.join(path, "model.config") if os.path.isdir(path) else path
    if os.path.basename(config) != "model.config":
        return path
    if not os.path.isfile(config):
        raise ParseError("a model folder needs a model.config", loc=SourceLoc(path))
    root = parse_xml(read_file(config), config)
    best: tuple[tuple[int, ...], str] | None = None
    for sdf in root.iter("sdf"):
        name = (sdf.text or "").strip()
        version = tuple(int(p) for p in (sdf.get("version") or "0").split(".") if p.isdigit())
        if name and (best is None or version > best[0]):
            best = (version, name)
    if best is None:
        raise ParseError("model.config names no <sdf> file", loc=loc(config, root))
    folder = os.path.dirname(os.path.abspath(config))
    found = os.path.realpath(os.path.join(folder, best[1]))
    if os.path.commonpath([found, os.path.realpath(folder)]) != os.path.realpath(folder):
        raise ParseError(f"model.config names {best[1]!r}, outside its folder; refused", loc=loc(config, root))
    if not os.path.isfile(found):
        raise ParseError(f"model.config names {best[1]!r}, which is not there", loc=loc(config, root))
    return found


def read_source(path: str, findings: Findings, model_path: Sequence[str] = ()) -> Source:
    confined = os.path.isdir(path) or os.path.basename(path) == "model.config"
    file = sdf_file_of(path)
    roots = model_roots(file, model_path)
    model, version = _model_of(file, findings, top=True)
    top = Scope("", model, file, version, os.path.dirname(os.path.abspath(file)), confined)
    top.static = _static(model)
    _nest(top, findings, roots, depth=0)
    return Source(file, top, roots)


def _model_of(file: str, findings: Findings, *, top: bool) -> tuple[etree._Element, str]:
    root = parse_xml(read_file(file), file, findings)
    if tag(root) != "sdf":
        raise ParseError(f"root element is <{tag(root)}>, expected <sdf>", loc=loc(file, root))
    version = (root.get("version") or "").strip()
    if version not in VERSIONS:
        findings.warn(
            "sdf-version",
            f"SDF version {version!r} is not one robodesc knows ({VERSIONS[0]} to {VERSIONS[-1]}); read as 1.11",
            element="sdf",
            loc=loc(file, root),
            stage=STAGE,
        )
        version = "1.11"
    if top and any(tag(c) == "world" for c in root):
        raise ParseError(
            "this is an SDF world, not a robot: give it with --world next to the robot it holds "
            "(robodesc compile ROBOT --world FILE)",
            loc=loc(file, root),
        )
    models = [c for c in root if tag(c) == "model"]
    if not models:
        raise ParseError("an SDF model file needs a <model> element", loc=loc(file, root))
    if len(models) > 1:
        findings.warn(
            "sdf-several-models",
            f"{len(models)} <model> elements; the first, {models[0].get('name')!r}, is read",
            element=f"model {models[1].get('name')!r}",
            loc=loc(file, models[1]),
            stage=STAGE,
        )
    return models[0], version


def _static(model: etree._Element) -> bool:
    return (model.findtext("static") or "").strip().lower() in ("1", "true")


def _nest(scope: Scope, findings: Findings, roots: list[str], depth: int) -> None:
    if depth > MAX_DEPTH:
        raise ParseError(
            f"models nest more than {MAX_DEPTH} deep (models including each other?)", loc=loc(scope.file, scope.element)
        )
    for child in scope.element:
        kind = tag(child)
        if kind == "model":
            name = child.get("name") or ""
            if not name:
                raise ParseError("a nested <model> needs a name", loc=loc(scope.file, child))
            nested = Scope(
                scope.scoped(name),
                child,
                scope.file,
                scope.version,
                scope.folder,
                scope.confined,
                parent=scope,
                pose=child.find("pose"),
                pose_file=scope.file,
                static=_static(child),
            )
        elif kind == "include":
            found = _include(scope, child, findings, roots)
            if found is None:
                continue
            nested = found
        else:
            continue
        scope.children.append(nested)
        _nest(nested, findings, roots, depth + 1)


def _include(scope: Scope, element: etree._Element, findings: Findings, roots: list[str]) -> Scope | None:
    uri = (element.findtext("uri") or "").strip()
    where = loc(scope.file, element)
    folder = resolve_uri(uri, scope.file, roots) if uri else None
    if folder is None:
        findings.warn(
            "sdf-include-missing",
            f"{uri!r} is not in the model path ({os.pathsep.join(roots)}); the model is read without it, so no "
            "target has what it held (add its folder with --model-path, or GZ_SIM_RESOURCE_PATH)",
            element="include",
            loc=where,
            stage=STAGE,
        )
        return None
    try:
        file = sdf_file_of(folder)
    except ParseError as exc:
        findings.warn(
            "sdf-include-missing", f"{uri!r}: {exc.message}; left out", element="include", loc=where, stage=STAGE
        )
        return None
    model, version = _model_of(file, findings, top=False)
    name = (element.findtext("name") or "").strip() or model.get("name") or "model"
    pose = element.find("pose")
    static_el = element.find("static")
    return Scope(
        scope.scoped(name),
        model,
        file,
        version,
        os.path.dirname(os.path.abspath(file)),
        True,
        parent=scope,
        pose=pose if pose is not None else model.find("pose"),
        pose_file=scope.file if pose is not None else file,
        static=_static(model) if static_el is None else (static_el.text or "").strip().lower() in ("1", "true"),
    )
