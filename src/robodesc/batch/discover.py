"""Which files in a folder are robots: URDF and xacro files whose root is a named ``<robot>`` and
that no other file includes, composition YAML (``robot:`` and ``links:``), ``.holo`` files, and
Python files defining ``build()`` with robodesc's builder."""

from __future__ import annotations

import os
import re

from robodesc.batch.jobs import robot_stem

_SKIP_DIRS = {"__pycache__", "node_modules", "build", "install", "log"}
_INCLUDE = re.compile(r"<xacro:include\b[^>]*\bfilename\s*=\s*[\"']([^\"']+)[\"']", re.S)
_ROOT = re.compile(r"<(?:[\w-]+:)?robot\b([^>]*)>", re.S)


def _head(path: str, size: int = 65536) -> str:
    with open(path, "rb") as handle:
        return handle.read(size).decode("utf-8", "replace")


def _xml_robot(path: str) -> tuple[bool, list[str]]:
    """Whether the file's root is a named ``<robot>``, and the files it includes."""
    text = re.sub(r"<!--.*?-->", "", _head(path, 1 << 22), flags=re.S)
    root = _ROOT.search(text)
    named = root is not None and re.search(r"\bname\s*=", root.group(1)) is not None
    return named, [m.group(1) for m in _INCLUDE.finditer(text)]


def _yaml_robot(path: str) -> bool:
    import yaml

    try:
        with open(path, encoding="utf-8") as handle:
            data = yaml.safe_load(handle)
    except (OSError, UnicodeDecodeError, yaml.YAMLError):
        return False
    return isinstance(data, dict) and "robot" in data and "links" in data


def _python_robot(path: str) -> bool:
    text = _head(path)
    return "robodesc" in text and re.search(r"^def build\(", text, re.M) is not None


def is_robot_file(path: str) -> bool:
    lower = path.lower()
    if lower.endswith((".urdf", ".xacro")):
        return _xml_robot(path)[0]
    if lower.endswith((".yaml", ".yml")):
        return _yaml_robot(path)
    if lower.endswith(".holo"):
        return True
    if lower.endswith(".py"):
        return _python_robot(path)
    return False


def discover(folder: str) -> list[tuple[str, str]]:
    """``(path, job id)`` for every robot under ``folder``, in sorted path order; the id is the path
    relative to ``folder`` without its robot suffix (``models/spirit/urdf/spirit``)."""
    found: list[str] = []
    included: set[str] = set()
    for here, dirs, names in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in _SKIP_DIRS)
        for name in sorted(names):
            path = os.path.join(here, name)
            lower = name.lower()
            if lower.endswith((".urdf", ".xacro")):
                named, includes = _xml_robot(path)
                included.update(os.path.basename(inc.replace("\\", "/")) for inc in includes)
                if named:
                    found.append(path)
            elif is_robot_file(path):
                found.append(path)
    out = []
    for path in sorted(found):
        if path.lower().endswith(".xacro") and os.path.basename(path) in included:
            continue  # a macro file another robot includes, not a robot of its own
        rel = os.path.relpath(path, folder)
        job_id = os.path.join(os.path.dirname(rel), robot_stem(rel)).replace(os.sep, "/")
        out.append((path, job_id))
    return out
