"""The viewer page: one HTML file with three.js, the viewer script, the scene data and every mesh.

Nothing is fetched when the page opens: the scripts and the stylesheet are inlined from
``assets/`` (three.js is vendored there, see ``assets/README.md``), the meshes are GLB files in
base64 (gzipped) inside the scene's JSON. So the file opens from disk, offline, in any browser with WebGL.
"""

from __future__ import annotations

import base64
import gzip
import html
import json
import os
import time
from collections.abc import Callable
from dataclasses import dataclass
from importlib import resources
from typing import Any

from robodesc._files import write_atomic
from robodesc._version import __version__
from robodesc.emit.common.staging import check_output
from robodesc.frontends.load import Source
from robodesc.ir.diagnostics import Finding, Severity
from robodesc.ir.geometry import Mesh
from robodesc.ir.model import Robot
from robodesc.meshes.buffers import MeshData, MeshReadError
from robodesc.meshes.data import MeshCache
from robodesc.meshes.roots import allowed_roots, outside_roots
from robodesc.options import CompileOptions
from robodesc.view.glb import mesh_glb
from robodesc.view.repairs import find_repairs
from robodesc.view.scene import MeshTable, build_scene
from robodesc.view.source import Loaded, load_for_view
from robodesc.view.world import world_page_data

THREE_VERSION = "0.187.0"


@dataclass(slots=True, frozen=True)
class PageResult:
    """What :func:`write_view_html` wrote: the file, its size, the robot's counts and the time."""

    path: str
    bytes: int
    links: int
    meshes: int
    findings: int
    repairs: int
    seconds: float


def asset(name: str) -> str:
    return resources.files("robodesc.view").joinpath("assets", name).read_text(encoding="utf-8")


def _script_safe(text: str) -> str:
    # Inside <script>, only "</" can end the element early; JSON allows "<\/" for the same text.
    return text.replace("</", "<\\/")


def embed_meshes(table: MeshTable, roots: list[str] | None = None) -> tuple[list[str | None], list[str]]:
    """Each mesh of the table as gzipped GLB in base64 (None when it cannot be read, or when its
    real path is outside ``roots``, the input's folder and package roots), and a note per failure
    naming the file as the source does."""
    cache = MeshCache()
    out: list[str | None] = []
    notes: list[str] = []
    for (path, scale), uri in zip(table.keys, table.uris, strict=True):
        if roots is not None and outside_roots(path, roots) is not None:
            # The rule of -t usd and --copy-meshes: embedding the geometry is copying the file.
            out.append(None)
            notes.append(f"{uri}: outside the input's folder and its packages' roots; not embedded")
            continue
        try:
            data = cache.get(path, scale)
        except MeshReadError as exc:
            out.append(None)
            notes.append(f"{uri}: {exc}")
            continue
        # gzip first: mesh arrays shrink to about half, which keeps a big robot's page small; the
        # browser inflates them itself (DecompressionStream), still without any request.
        out.append(_glb(data))
    return out, notes


def _glb(data: MeshData) -> str:
    return base64.b64encode(gzip.compress(mesh_glb(data), compresslevel=1, mtime=0)).decode("ascii")


def scene_data(loaded: Loaded) -> dict[str, Any]:
    """The page's data: the scene, the meshes as base64 GLB, the repairs, and where it came from."""
    table = MeshTable()
    roots = allowed_roots(loaded.robot)
    findings = [*loaded.findings, *_not_read(loaded.robot, roots)]
    data = build_scene(loaded.robot, findings, table)
    data["meshes"], data["mesh_notes"] = embed_meshes(table, roots)
    data["world"] = None
    if loaded.world is not None:
        # The world's meshes follow the robot's (the user named the world; its files resolved inside
        # the model path's roots when it was read).
        data["world"], ground = world_page_data(loaded.world, len(data["meshes"]))
        data["meshes"] += [_glb(mesh) for mesh in ground]
    data["mesh_files"] = [os.path.basename(path) for path, _ in table.keys]
    data["mesh_encoding"] = "glb+gzip+base64"
    data["repairs"] = find_repairs(loaded.before, loaded.robot, loaded.findings) if loaded.before is not None else []
    data["target"] = loaded.target
    data["source"] = loaded.source_name
    data["generator"] = f"robodesc {__version__}, three.js {THREE_VERSION}"
    shown = as_typed(loaded.source_name)
    data["findings"] = [{k: shown(v) if isinstance(v, str) else v for k, v in f.items()} for f in data["findings"]]
    data["mesh_notes"] = [shown(n) for n in data["mesh_notes"]]
    return data


def _not_read(robot: Robot, roots: list[str]) -> list[Finding]:
    """A warning per mesh shape whose file is outside ``roots`` (it is not embedded)."""
    out = []
    for link in robot.links:
        shapes = [("visual", i, v.geometry, v.src) for i, v in enumerate(link.visuals)]
        shapes += [("collision", i, c.geometry, c.src) for i, c in enumerate(link.collisions)]
        for kind, i, geometry, src in shapes:
            if isinstance(geometry, Mesh) and geometry.path is not None:
                outside = outside_roots(geometry.path, roots)
                if outside is not None:
                    message = f"mesh {outside}; it is not embedded in the page (-t usd and --copy-meshes refuse it too)"
                    loc = geometry.src or src or link.src
                    out.append(
                        Finding(Severity.WARNING, "view-mesh-not-read", message, f"link {link.name!r} {kind} {i}", loc)
                    )
    return out


def as_typed(source_name: str) -> Callable[[str], str]:
    """A page is made to be shared: paths in its text name files as the user typed the input (the
    input's folder as given, the working folder left out), not where they are on this machine."""
    pairs: list[tuple[str, str]] = []
    if source_name and not source_name.startswith("<"):
        typed = os.path.dirname(source_name)
        for folder in {os.path.abspath(typed or "."), os.path.realpath(typed or ".")}:
            pairs.append((folder.rstrip(os.sep) + os.sep, typed + os.sep if typed else ""))
    for folder in {os.getcwd(), os.path.realpath(os.getcwd())}:
        pairs.append((folder.rstrip(os.sep) + os.sep, ""))
    pairs.sort(key=lambda pair: -len(pair[0]))  # the most specific folder first

    def shown(text: str) -> str:
        for absolute, relative in pairs:
            text = text.replace(absolute, relative)
        return text

    return shown


def build_page(data: dict[str, Any]) -> str:
    """The HTML text of the page for ``data`` (from :func:`scene_data`)."""
    title = f"{data['robot']}" + (f" for {data['target']}" if data.get("target") else "") + " - robodesc view"
    template = asset("page.html")
    parts = {
        "{{TITLE}}": html.escape(title),
        "{{STYLE}}": asset("viewer.css"),
        "{{THREE}}": _script_safe(asset("three-bundle.min.js")),
        "{{DATA}}": _script_safe(json.dumps(data, separators=(",", ":"), allow_nan=False)),
        "{{VIEWER}}": _script_safe(asset("viewer.js")),
    }
    # One pass over the template, so a placeholder-like text inside an inserted part stays as it is.
    out: list[str] = []
    rest = template
    while "{{" in rest:
        head, _, tail = rest.partition("{{")
        key = "{{" + tail.partition("}}")[0] + "}}"
        out.append(head)
        out.append(parts[key])
        rest = tail[len(key) - 2 :]
    out.append(rest)
    return "".join(out)


def write_view_html(
    source: Source | Loaded,
    out: str,
    *,
    options: CompileOptions | None = None,
    target: str | None = None,
) -> PageResult:
    """Write the viewer page for ``source`` (any input robodesc reads, an IR ``Robot``, or an
    already :class:`Loaded` robot) to ``out``; with ``target``, the robot as compiled for it."""
    start = time.perf_counter()
    check_output(out, folder=False, source=None if isinstance(source, Loaded) else source, example="robot.html")
    loaded = source if isinstance(source, Loaded) else load_for_view(source, options, target)
    data = scene_data(loaded)
    text = build_page(data)
    write_atomic(out, text)
    return PageResult(
        path=out,
        bytes=len(text.encode("utf-8")),
        links=len(loaded.robot.links),
        meshes=len(data["meshes"]),
        findings=len(data["findings"]),
        repairs=len(data["repairs"]),
        seconds=time.perf_counter() - start,
    )
