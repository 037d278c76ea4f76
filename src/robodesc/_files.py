"""Writing outputs atomically: a reader never sees a half-written file, and a failed run leaves
whatever was there before untouched."""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from typing import BinaryIO

# A file's content: text (written as UTF-8), bytes, or pieces of bytes written one after another
# (a .usdc layer whose mesh arrays are views of the meshes' own memory, never joined into a copy).
Content = str | bytes | Sequence[bytes | memoryview]


def _write(handle: BinaryIO, data: Content) -> None:
    if isinstance(data, str):
        handle.write(data.encode("utf-8"))
    elif isinstance(data, bytes):
        handle.write(data)
    else:
        handle.writelines(data)


def write_atomic(path: str, data: Content) -> None:
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    try:
        fd, tmp = tempfile.mkstemp(prefix=".robodesc-", suffix=".tmp", dir=directory)
    except OSError as exc:  # /proc, a read-only mount: say so of the file asked for, not the temporary one
        raise OSError(exc.errno, exc.strerror, path) from None
    try:
        with os.fdopen(fd, "wb") as handle:
            _write(handle, data)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def replace_dir_atomic(staging: str, target: str) -> None:
    """Move a fully written ``staging`` folder to ``target``, replacing an older one."""
    if os.path.isdir(target):
        backup = tempfile.mkdtemp(prefix=".robodesc-old-", dir=os.path.dirname(os.path.abspath(target)))
        os.rmdir(backup)
        os.replace(target, backup)
        os.replace(staging, target)
        if os.path.islink(backup):  # a link to a folder is replaced, never written through
            os.unlink(backup)
        else:
            shutil.rmtree(backup, ignore_errors=True)
    else:
        os.replace(staging, target)


@contextmanager
def staged_folder(target: str) -> Iterator[str]:
    """A folder to fill beside ``target``; when the block ends without error it replaces ``target``
    as one unit, otherwise it is removed and ``target`` stays as it was."""
    parent = os.path.dirname(os.path.abspath(target))
    os.makedirs(parent, exist_ok=True)
    staging = tempfile.mkdtemp(prefix=".robodesc-", dir=parent)
    os.chmod(staging, folder_mode())  # mkdtemp makes it 0700; the output gets the user's usual mode
    try:
        yield staging
        replace_dir_atomic(staging, target)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise


def folder_mode() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return 0o777 & ~mask


def write_files(directory: str, files: Mapping[str, Content]) -> None:
    """Write ``{relative name: text or bytes}`` under ``directory``."""
    # Each folder made once: a file system call per file costs more than writing a small layer.
    folders = {os.path.dirname(os.path.join(directory, name)) for name in files}
    for folder in sorted(folders):
        os.makedirs(folder, exist_ok=True)
    for name, data in sorted(files.items()):
        path = os.path.join(directory, name)
        with open(path, "wb") as handle:
            _write(handle, data)


def write_folder(out: str, files: Mapping[str, Content]) -> dict[str, str]:
    """Write ``files`` into folder ``out`` as one unit; role (the file name) -> path."""
    with staged_folder(out) as staging:
        write_files(staging, files)
    return {name: os.path.join(out, name) for name in sorted(files)}


def escapes(folder: str, target: str) -> str | None:
    """The real path ``target`` would be written to when a symlink already there (``meshes``
    pointing elsewhere, or the file itself) carries the write outside ``folder``; None when it
    stays inside (or does not exist yet). Outputs are written only inside the output path."""
    path = target
    while not os.path.lexists(path):
        parent = os.path.dirname(path)
        if parent == path or not parent.startswith(folder.rstrip(os.sep)):
            return None
        path = parent
    real_out = os.path.realpath(folder)
    real = os.path.realpath(path)
    inside = real == real_out or real.startswith(real_out.rstrip(os.sep) + os.sep)
    return None if inside and not (path == target and os.path.islink(target)) else real
