"""Which files in a folder are robots, as the frontends say (``Frontend.discover``): URDF and xacro
files whose root is a named ``<robot>`` and that no other file includes, MJCF files with a body or an
include that no other file includes (menagerie's ``scene.xml``, not the robot file it includes), composition YAML
(``robot:`` and ``links:``), ``.holo`` files. Python compositions run when read, so a folder's
``.py`` files are robots only with ``--run-python``. Only regular files are read: a named pipe or a
device in the folder is passed over, never opened for reading."""

from __future__ import annotations

import os
import stat

from robodesc.batch.jobs import robot_stem
from robodesc.frontends.contract import Frontend, head_of
from robodesc.frontends.load import HEAD_BYTES, frontends
from robodesc.ir.diagnostics import ParseError

_SKIP_DIRS = {"__pycache__", "node_modules", "build", "install", "log"}


def _frontend(path: str, known: list[Frontend]) -> Frontend | None:
    lower = path.lower()
    matches = [f for f in known if lower.endswith(f.suffixes)]
    longest = max((max(len(s) for s in f.suffixes if lower.endswith(s)) for f in matches), default=0)
    matches = [f for f in matches if max(len(s) for s in f.suffixes if lower.endswith(s)) == longest]
    if len(matches) > 1 and _regular(path):
        # Several formats share the suffix (.xml: URDF and MJCF): the head of the file decides.
        try:
            head = head_of(path, HEAD_BYTES)
        except (ParseError, OSError):
            return None
        return next((f for f in matches if f.sniff is not None and f.sniff(head)), matches[0])
    return matches[0] if matches else None


def _regular(path: str) -> bool:
    try:
        return stat.S_ISREG(os.stat(path).st_mode)
    except OSError:
        return False


def is_robot_file(path: str, *, run_python: bool = False) -> bool:
    return _classify(path, [f for f in frontends() if run_python or not f.runs_code])[0]


def _classify(path: str, known: list[Frontend]) -> tuple[bool, list[str]]:
    frontend = _frontend(path, known)
    if frontend is None or not _regular(path):
        return False, []
    if frontend.discover is None:
        return True, []
    try:
        return frontend.discover(path)
    except (ParseError, OSError, UnicodeDecodeError):
        return False, []


def why_skipped(path: str, every: list[Frontend], run_python: bool) -> str | None:
    """Why a file with a robot suffix is not a job (None when the suffix is no robot's): the
    summary says so, so that nothing is passed over in silence."""
    frontend = _frontend(path.lower(), every)
    if frontend is None:
        return None
    if frontend.runs_code and not run_python:
        return "a Python composition: it runs when read, so only with --run-python"
    try:
        st = os.stat(path)
    except OSError:
        return "a dangling link" if os.path.islink(path) else "cannot be read"
    if stat.S_ISFIFO(st.st_mode):
        return "a named pipe, not a regular file: never opened"
    if not stat.S_ISREG(st.st_mode):
        return "not a regular file (a device or socket): never opened"
    return f"not a {frontend.name} robot (no robot found in it)"


def discover(
    folder: str, *, run_python: bool = False, skipped: list[tuple[str, str]] | None = None
) -> list[tuple[str, str]]:
    """``(path, job id)`` for every robot under ``folder``, in sorted path order; the id is the path
    relative to ``folder`` without its robot suffix (``models/spirit/urdf/spirit``). ``skipped``
    collects ``(path, why)`` for each file with a robot suffix that is not a job, and each link to
    a folder (not followed)."""
    every = frontends()
    known = [f for f in every if run_python or not f.runs_code]
    found: list[str] = []
    included: set[str] = set()
    for here, dirs, names in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in _SKIP_DIRS)
        if skipped is not None:
            skipped.extend(
                (os.path.join(here, d), "a link to a folder: not followed")
                for d in dirs
                if os.path.islink(os.path.join(here, d))
            )
        for name in sorted(names):
            path = os.path.join(here, name)
            robot, includes = _classify(path, known)
            included.update(os.path.basename(inc.replace("\\", "/")) for inc in includes)
            if robot:
                found.append(path)
            elif skipped is not None and (why := why_skipped(path, every, run_python)) is not None:
                skipped.append((path, why))
    out = []
    for path in sorted(found):
        if os.path.basename(path) in included:
            continue  # a fragment another robot includes, not a robot of its own
        rel = os.path.relpath(path, folder)
        job_id = os.path.join(os.path.dirname(rel), robot_stem(rel)).replace(os.sep, "/")
        out.append((path, job_id))
    return out
