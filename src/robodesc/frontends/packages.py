"""Finding the files that robot descriptions refer to.

Mesh and texture URIs come as ``package://pkg/path``, ``model://name/path``, ``file://``, absolute or
relative paths. A ROS package is looked up, in order, in: the caller's explicit ``NAME=DIR`` map; the
``package.xml`` files above the input file (the package it belongs to) and beside that package
(its workspace); ``ROS_PACKAGE_PATH``; ``AMENT_PREFIX_PATH`` (``<prefix>/share/<pkg>``); last, a
folder of that name above the input file or beside one of its folders, as pybullet and most
downloaded robot folders expect (``upkie_description/urdf/upkie.urdf`` naming
``package://upkie_description/meshes/...``). A ``package://`` or ``model://`` path that climbs
out of its package root through ``..`` is refused.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from urllib.parse import unquote, urlparse

from robodesc.ir.diagnostics import BrokenReferenceError, PathEscapeError

_NAME_RE = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")
_MODEL_PATH_VARS = ("GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "GAZEBO_MODEL_PATH", "SDF_PATH")
# How many folders above the input a package named by its folder is looked for.
FOLDER_LEVELS = 6
# The ``how`` of a package found only by its folder's name: frontends say so in a warning.
BY_FOLDER_NAME = "a folder of that name near the input (no package.xml)"


@dataclass(slots=True, frozen=True)
class Resolved:
    """Where a URI points. ``package`` is ``(name, path inside it)`` for package-relative URIs."""

    path: str
    package: tuple[str, str] | None = None
    how: str = ""


def package_xml_name(directory: str) -> str | None:
    """The ``<name>`` declared by ``directory/package.xml``, or ``None``."""
    try:
        with open(os.path.join(directory, "package.xml"), "rb") as handle:
            head = handle.read(65536)
    except OSError:
        return None
    match = _NAME_RE.search(head)
    return match.group(1).decode("utf-8", "replace") if match else None


@dataclass
class PackageResolver:
    """Resolves package names and URIs. Cheap to build; look-ups are cached."""

    explicit: Mapping[str, str] = field(default_factory=dict)
    input_file: str | None = None
    environ: Mapping[str, str] = field(default_factory=lambda: dict(os.environ))
    _cache: dict[str, tuple[str, str] | None] = field(default_factory=dict)
    _crawled: dict[str, str] | None = None

    def find_package(self, name: str) -> tuple[str, str] | None:
        """``(root directory, how it was found)`` or ``None``."""
        if name not in self._cache:
            self._cache[name] = self._find(name)
        return self._cache[name]

    def roots(self) -> list[str]:
        """The root folders of the packages given with --package and of every package looked up and found."""
        found = [os.path.abspath(d) for d in self.explicit.values()]
        found += [hit[0] for hit in self._cache.values() if hit is not None]
        return list(dict.fromkeys(found))

    def _find(self, name: str) -> tuple[str, str] | None:
        if name in self.explicit:
            return os.path.abspath(self.explicit[name]), "given with --package"
        if self.input_file:
            found = self._near_input(name)
            if found:
                return found
        crawled = self._crawl_ros_package_path()
        if name in crawled:
            return crawled[name], "ROS_PACKAGE_PATH"
        for prefix in _split(self.environ.get("AMENT_PREFIX_PATH", "")):
            candidate = os.path.join(prefix, "share", name)
            if os.path.isdir(candidate):
                return os.path.abspath(candidate), "AMENT_PREFIX_PATH"
        if self.input_file:
            return self._folder_near_input(name)
        return None

    def _folder_near_input(self, name: str) -> tuple[str, str] | None:
        """A folder called ``name`` that holds the input, or stands beside one of its folders."""
        assert self.input_file is not None
        here = os.path.dirname(os.path.abspath(self.input_file))
        for _ in range(FOLDER_LEVELS):
            if os.path.basename(here) == name:
                return here, BY_FOLDER_NAME
            beside = os.path.join(here, name)
            if os.path.isdir(beside):
                return beside, BY_FOLDER_NAME
            parent = os.path.dirname(here)
            if parent == here:
                break
            here = parent
        return None

    def _near_input(self, name: str) -> tuple[str, str] | None:
        assert self.input_file is not None
        here = os.path.dirname(os.path.abspath(self.input_file))
        own_root: str | None = None
        while True:
            declared = package_xml_name(here)
            if declared is not None:
                own_root = own_root or here
                if declared == name:
                    return here, "package.xml above the input file"
            parent = os.path.dirname(here)
            if parent == here:
                break
            here = parent
        if own_root is None:
            return None
        # A workspace keeps its packages side by side: look beside the input's own package.
        workspace = os.path.dirname(own_root)
        try:
            entries = sorted(os.listdir(workspace))
        except OSError:
            return None
        for entry in entries:
            candidate = os.path.join(workspace, entry)
            if os.path.isdir(candidate) and package_xml_name(candidate) == name:
                return candidate, "package.xml beside the input's package"
        candidate = os.path.join(workspace, name)
        if os.path.isdir(candidate):
            return candidate, "folder of that name beside the input's package (it has no package.xml)"
        return None

    def _crawl_ros_package_path(self) -> dict[str, str]:
        if self._crawled is None:
            found: dict[str, str] = {}
            for entry in _split(self.environ.get("ROS_PACKAGE_PATH", "")):
                for dirpath, dirnames, _files in os.walk(entry):
                    depth = dirpath[len(entry) :].count(os.sep)
                    declared = package_xml_name(dirpath)
                    if declared is not None:
                        found.setdefault(declared, os.path.abspath(dirpath))
                        dirnames[:] = []  # packages do not nest
                    elif depth >= 5:
                        dirnames[:] = []
                    else:
                        dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
            self._crawled = found
        return self._crawled

    # ---- URIs ------------------------------------------------------------------------------
    def resolve(self, uri: str, base_dir: str | None) -> Resolved:
        """Resolve a URI to a path (which may not exist). Raises for unknown packages or escapes."""
        if uri.startswith("package://"):
            rest = uri[len("package://") :]
            name, _, inner = rest.partition("/")
            found = self.find_package(name)
            if found is None:
                raise BrokenReferenceError(
                    f"package {name!r} not found (give it with --package {name}=DIR, or set "
                    "ROS_PACKAGE_PATH / AMENT_PREFIX_PATH)"
                )
            root, how = found
            return Resolved(_inside(root, unquote(inner), uri), (name, inner), how)
        if uri.startswith("model://"):
            rest = uri[len("model://") :]
            name, _, inner = rest.partition("/")
            for var in _MODEL_PATH_VARS:
                for entry in _split(self.environ.get(var, "")):
                    root = os.path.join(entry, name)
                    if os.path.isdir(root):
                        return Resolved(_inside(root, unquote(inner), uri), None, var)
            found = self.find_package(name)
            if found is not None:
                return Resolved(_inside(found[0], unquote(inner), uri), (name, inner), found[1])
            raise BrokenReferenceError(f"model {name!r} not found on {', '.join(_MODEL_PATH_VARS)} nor as a package")
        if uri.startswith("file://"):
            parsed = urlparse(uri)
            path = (
                unquote(parsed.netloc + parsed.path) if parsed.netloc not in ("", "localhost") else unquote(parsed.path)
            )
            return Resolved(
                os.path.normpath(path if os.path.isabs(path) else os.path.join(base_dir or ".", path)), None, "file URI"
            )
        if "://" in uri:
            raise BrokenReferenceError(f"unsupported URI scheme in {uri!r}")
        if os.path.isabs(uri):
            return Resolved(os.path.normpath(uri), None, "absolute path")
        return Resolved(os.path.normpath(os.path.join(base_dir or os.getcwd(), uri)), None, "relative path")


def _inside(root: str, inner: str, uri: str) -> str:
    root = os.path.abspath(root)
    path = os.path.normpath(os.path.join(root, inner))
    if path != root and not path.startswith(root + os.sep):
        raise PathEscapeError(f"{uri!r} leaves its package root {root!r} through '..'; refused")
    return path


def _split(value: str) -> list[str]:
    return [p for p in value.split(os.pathsep) if p]
