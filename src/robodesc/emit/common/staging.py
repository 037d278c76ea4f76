"""Output staging: everything a compile writes goes to a place beside its output, is validated
there, and is moved into place only when the run succeeds, so a failed run leaves an earlier output
byte-identical. Also the checks of an output path made before any work is done."""

from __future__ import annotations

import os
import shutil
import stat
import tempfile
from typing import Any

from robodesc._files import replace_dir_atomic
from robodesc.ir.diagnostics import ConfigError


class OutputPathError(ConfigError):
    """The output path cannot be written as asked; found before any work is done."""


def check_output(
    out: str,
    *,
    folder: bool,
    source: Any = None,
    what: str = "-o",
    suffixes: tuple[str, ...] = (),
    example: str = "robot.urdf",
) -> None:
    """Refuse an output path that cannot work, each problem with its own message. ``suffixes``: the
    file suffixes the target writes (a folder target named like a file is refused too); ``example``:
    the file name the messages suggest (``robot.xml`` for MJCF, ``robot.html`` for ``view``)."""
    if not out:
        raise OutputPathError(f"{what}: empty path")
    lower = out.lower()
    if suffixes and not lower.endswith(suffixes):
        raise OutputPathError(
            f"{what} {out}: this target writes {' or '.join(suffixes)} files (e.g. {_example(out, suffixes[0])})"
        )
    if folder and lower.endswith(_FILE_SUFFIXES):
        raise OutputPathError(f"{what} {out}: names a file, but this target writes a folder (e.g. {_stem(out)})")
    path = os.path.abspath(out)
    if not folder and out.endswith(("/", os.sep)):
        raise OutputPathError(
            f"{what} {out}: ends with '/', so it names a folder; this output is one file (e.g. {out.rstrip('/' + os.sep) or '.'}/{example})"
        )
    if isinstance(source, str | os.PathLike) and not os.fspath(source).lstrip().startswith("<"):
        src = os.path.abspath(os.fspath(source))
        if src == path or (os.path.exists(path) and os.path.exists(src) and os.path.samefile(src, path)):
            raise OutputPathError(f"{what} {out}: is the input file; robodesc does not overwrite its input")
        real_src, real_out = os.path.realpath(src), os.path.realpath(path)
        if folder and real_src.startswith(real_out.rstrip(os.sep) + os.sep):
            raise OutputPathError(
                f"{what} {out}: holds the input file; this target replaces the whole folder, so give another one"
            )
    try:
        st = os.stat(path)
    except FileNotFoundError:
        st = None
    except NotADirectoryError:
        st = None
    except OSError as exc:
        raise OutputPathError(f"{what} {out}: cannot be examined ({exc.strerror})") from None
    if st is not None:
        if stat.S_ISDIR(st.st_mode) and not folder:
            raise OutputPathError(
                f"{what} {out}: is an existing folder; give a file name inside it (e.g. {os.path.join(out, example)})"
            )
        if not stat.S_ISDIR(st.st_mode) and folder:
            raise OutputPathError(f"{what} {out}: is an existing file; this target writes a folder")
        if not stat.S_ISDIR(st.st_mode) and not stat.S_ISREG(st.st_mode):
            raise OutputPathError(
                f"{what} {out}: is a device or special file, not a regular file; robodesc never replaces one"
            )
    # The nearest existing folder above must be a folder, and writable.
    parent = os.path.dirname(path)
    while not os.path.lexists(parent):
        up = os.path.dirname(parent)
        if up == parent:
            break
        parent = up
    if os.path.lexists(parent) and not os.path.isdir(parent):
        raise OutputPathError(f"{what} {out}: {_rel(parent)} is a file, so nothing can be written under it")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise OutputPathError(f"{what} {out}: the folder {_rel(parent)} is not writable")


# Suffixes that name a file, never a folder a target should create (``-t isaac -o out/x.usda``).
_FILE_SUFFIXES = (".urdf", ".xacro", ".sdf", ".usd", ".usda", ".usdc", ".xml", ".json", ".yaml", ".yml", ".py", ".holo")


def _stem(out: str) -> str:
    return os.path.splitext(out.rstrip("/" + os.sep))[0] or "out"


def _example(out: str, suffix: str) -> str:
    return _stem(out) + suffix


def _rel(path: str) -> str:
    rel = os.path.relpath(path)
    return path if rel.startswith(".." + os.sep + "..") else rel


class Staging:
    """Where a compile writes before it has validated: beside the output, so every relative path
    (meshes, textures, payload layers) is the same as at the final place. ``commit`` moves it into
    place; ``discard`` removes it and leaves whatever was there before untouched.

    A file output is staged as a hidden file in the same folder; a folder output as a hidden folder
    beside it. What a file output owns beside it (a layered USD's payload folder, an MJCF scene and
    its meshes) is protected with :meth:`protect`."""

    def __init__(self, out: str | None, folder: bool) -> None:
        self.final = out
        self.folder = folder
        self.path: str | None = None
        self._owned: list[tuple[str, str | None]] = []
        self._aside: list[str] = []
        self._tracked: list[tuple[str, set[str] | None]] = []
        self._made: str | None = None  # the topmost folder this run created for the output
        if out is None:
            return
        parent = os.path.dirname(os.path.abspath(out))
        missing = parent
        while not os.path.lexists(os.path.dirname(missing)) and os.path.dirname(missing) != missing:
            missing = os.path.dirname(missing)
        self._made = missing if not os.path.lexists(parent) else None
        os.makedirs(parent, exist_ok=True)
        base = os.path.basename(os.path.abspath(out))
        try:
            if folder:
                self.path = tempfile.mkdtemp(prefix=f".robodesc-{base}-", dir=parent)
                os.rmdir(self.path)  # the target creates it (as a folder it stages and moves itself)
            else:
                fd, self.path = tempfile.mkstemp(prefix=".robodesc-", suffix=f"-{base}", dir=parent)
                os.close(fd)
                os.unlink(self.path)
        except OSError as exc:  # /proc, a read-only mount: the user's path, not the staging file's
            raise OutputPathError(f"-o {out}: cannot be written ({exc.strerror})") from None

    def protect(self, names: tuple[str, ...]) -> None:
        """Files or folders beside a file output that the output owns (``Target.owned``): the
        earlier ones are set aside while the new ones are written, and restored if the run fails."""
        if self.final is None:
            return
        parent = os.path.dirname(os.path.abspath(self.final))
        for name in names:
            owned = os.path.join(parent, name)
            backup = None
            if os.path.lexists(owned):
                backup = tempfile.mkdtemp(prefix=".robodesc-old-", dir=parent)
                os.rmdir(backup)
                os.replace(owned, backup)
            self._owned.append((owned, backup))

    def track(self, name: str) -> None:
        """A folder beside a file output that the run adds files to without owning it (``meshes/``:
        MJCF's converted meshes and --copy-meshes' copies, named so that outputs in one folder can
        share it): what is in it now is recorded, and :meth:`discard` removes what the run added."""
        if self.final is None or self.folder:
            return
        where = os.path.join(os.path.dirname(os.path.abspath(self.final)), name)
        if os.path.islink(where):
            return  # nothing is written through it (the writers refuse); nothing to take back
        self._tracked.append((where, _files_under(where) if os.path.isdir(where) else None))

    def set_aside(self, name: str) -> str | None:
        """Keep a copy (hard links) of ``name`` of the staged folder while a target rewrites the
        folder as a whole; the target still reads the original (the USD reads the copied meshes)."""
        assert self.path is not None
        here = os.path.join(self.path, name)
        if not os.path.isdir(here):
            return None
        aside = tempfile.mkdtemp(prefix=".robodesc-aside-", dir=os.path.dirname(self.path))
        os.rmdir(aside)
        shutil.copytree(here, aside, copy_function=_link_or_copy)
        self._aside.append(aside)
        return aside

    def put_back(self, aside: str, name: str) -> None:
        assert self.path is not None
        os.makedirs(self.path, exist_ok=True)
        here = os.path.join(self.path, name)
        if os.path.isdir(here):
            shutil.rmtree(here)
        os.replace(aside, here)
        self._aside.remove(aside)

    def final_path(self, path: str) -> str:
        if self.path is None or self.final is None:
            return path
        if path == self.path:
            return self.final
        if self.folder and path.startswith(self.path + os.sep):
            return os.path.join(self.final, path[len(self.path) + 1 :])
        return path

    def commit(self) -> None:
        if self.path is None or self.final is None:
            return
        if self.folder:
            if os.path.isdir(self.path):
                os.chmod(self.path, _folder_mode())
                replace_dir_atomic(self.path, self.final)
        elif os.path.lexists(self.path):
            os.replace(self.path, self.final)
        for _, backup in self._owned:
            if backup is not None:
                _remove(backup)
        self._owned = []
        self._tracked = []
        self._made = None
        self.path = None

    def discard(self) -> None:
        for aside in self._aside:
            shutil.rmtree(aside, ignore_errors=True)
        self._aside = []
        if self.path is not None:
            if os.path.isdir(self.path) and not os.path.islink(self.path):
                shutil.rmtree(self.path, ignore_errors=True)
            elif os.path.lexists(self.path):
                os.unlink(self.path)
            self.path = None
        for owned, backup in reversed(self._owned):
            if os.path.lexists(owned):
                _remove(owned)
            if backup is not None:
                os.replace(backup, owned)
        self._owned = []
        for where, before in self._tracked:
            if before is None:  # the run made the folder: all of it is the run's
                if os.path.isdir(where) and not os.path.islink(where):
                    shutil.rmtree(where, ignore_errors=True)
            else:
                for path in sorted(_files_under(where) - before, reverse=True):  # children first
                    if os.path.isdir(path) and not os.path.islink(path):
                        _rmdir_empty(path)
                    else:
                        os.unlink(path)
        self._tracked = []
        if self._made is not None:  # the folders made for the output, when the run left them empty
            parent = os.path.dirname(os.path.abspath(self.final or ""))
            while _rmdir_empty(parent) and parent != self._made:
                parent = os.path.dirname(parent)
            self._made = None


def _files_under(folder: str) -> set[str]:
    """Every file, link and folder below ``folder`` (links not followed)."""
    found: set[str] = set()
    for root, dirs, files in os.walk(folder):
        found.update(os.path.join(root, name) for name in (*dirs, *files))
    return found


def _rmdir_empty(path: str) -> bool:
    try:
        os.rmdir(path)
    except OSError:
        return False
    return True


def _link_or_copy(src: str, dst: str) -> None:
    try:
        os.link(src, dst)
    except OSError:
        shutil.copy2(src, dst)


def _folder_mode() -> int:
    """0o777 less the umask: what mkdir would give (mkdtemp makes staging folders 0700)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o777 & ~mask


def _remove(path: str) -> None:
    if os.path.isdir(path) and not os.path.islink(path):
        shutil.rmtree(path, ignore_errors=True)
    else:
        os.unlink(path)
