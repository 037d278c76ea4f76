"""A hardened XML reader for untrusted robot files.

Robot descriptions arrive from the internet. The parser therefore never expands entities, never
loads a DTD, never touches the network, and refuses any ``<!DOCTYPE``: URDF and SDF have no use for
one, and it is how XML external-entity (local file disclosure) and entity-expansion ("billion
laughs") attacks start. Files above :data:`MAX_BYTES` are refused before parsing.
"""

from __future__ import annotations

import os
import re
import stat

from lxml import etree

from robodesc.ir.diagnostics import ParseError, SourceLoc

MAX_BYTES = 256 * 1024 * 1024
_DOCTYPE = re.compile(rb"<!DOCTYPE", re.IGNORECASE)
_ENTITY = re.compile(rb"<!ENTITY", re.IGNORECASE)


def _parser() -> etree.XMLParser:
    return etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        dtd_validation=False,
        huge_tree=False,
        collect_ids=False,
        remove_comments=True,
        remove_pis=True,
    )


def refuse_hostile(data: bytes, file: str | None) -> None:
    """Raise :class:`ParseError` if ``data`` is too large or declares a DOCTYPE or entities."""
    if len(data) > MAX_BYTES:
        raise ParseError(
            f"file is {len(data) / 2**20:.0f} MiB; robodesc refuses XML above {MAX_BYTES // 2**20} MiB",
            loc=SourceLoc(file),
        )
    match = _DOCTYPE.search(data) or _ENTITY.search(data)
    if match is not None:
        line = data.count(b"\n", 0, match.start()) + 1
        raise ParseError(
            "<!DOCTYPE>/<!ENTITY> declarations are not allowed in robot descriptions "
            "(they enable external-entity and entity-expansion attacks); remove them",
            loc=SourceLoc(file, line),
        )


def parse_xml(data: bytes | str, file: str | None) -> etree._Element:
    """Parse ``data`` safely and return the root element. ``file`` is used for messages only."""
    raw = data.encode("utf-8") if isinstance(data, str) else data
    refuse_hostile(raw, file)
    try:
        root = etree.fromstring(raw, _parser())
    except etree.XMLSyntaxError as exc:
        line, column = exc.position if exc.position else (None, None)
        message = str(exc.msg).split(", line ")[0]
        raise ParseError(f"malformed XML: {message}", loc=SourceLoc(file, line, column)) from None
    if root is None:
        raise ParseError("empty document", loc=SourceLoc(file))
    return root


def read_file(path: str, limit: int = MAX_BYTES) -> bytes:
    """The bytes of the regular file ``path`` (at most ``limit`` + 1 of them, so callers can refuse
    larger files). A named pipe, device or socket is refused without blocking on it: the file is
    opened non-blocking and checked with ``fstat`` on the open descriptor, so a swap between check
    and open cannot slip a pipe in."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except FileNotFoundError:
        raise ParseError("file not found", loc=SourceLoc(path)) from None
    except IsADirectoryError:
        raise ParseError("is a directory, not a file", loc=SourceLoc(path)) from None
    except OSError as exc:
        raise ParseError(f"cannot read: {exc.strerror}", loc=SourceLoc(path)) from None
    try:
        mode = os.fstat(fd).st_mode
        if stat.S_ISDIR(mode):
            raise ParseError("is a directory, not a file", loc=SourceLoc(path))
        if not stat.S_ISREG(mode):
            raise ParseError(
                f"is a {_kind(mode)}, not a regular file; robodesc reads only regular files", loc=SourceLoc(path)
            )
        os.set_blocking(fd, True)
        with os.fdopen(fd, "rb") as handle:
            fd = -1
            return handle.read(limit + 1)
    except OSError as exc:
        raise ParseError(f"cannot read: {exc.strerror}", loc=SourceLoc(path)) from None
    finally:
        if fd >= 0:
            os.close(fd)


def read_text(path: str, limit: int = MAX_BYTES) -> str:
    """:func:`read_file` for UTF-8 text formats (YAML, ``.holo``), refusing files above ``limit``."""
    data = read_file(path, limit)
    if len(data) > limit:
        raise ParseError(f"file is larger than {limit // 2**20} MiB; refused", loc=SourceLoc(path))
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ParseError(f"not UTF-8 text (byte {exc.start})", loc=SourceLoc(path)) from None


def is_regular_file(path: str) -> bool:
    """``os.path.isfile`` under its proper name: true for regular files (after symlinks) only."""
    try:
        return stat.S_ISREG(os.stat(path).st_mode)
    except (OSError, ValueError):
        return False


def _kind(mode: int) -> str:
    if stat.S_ISFIFO(mode):
        return "named pipe"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "device"
    if stat.S_ISSOCK(mode):
        return "socket"
    return "special file"
