"""A hardened XML reader for untrusted robot files.

Robot descriptions arrive from the internet. The parser therefore never expands entities, never
loads a DTD, never touches the network, and refuses any ``<!DOCTYPE``: URDF and SDF have no use for
one, and it is how XML external-entity (local file disclosure) and entity-expansion ("billion
laughs") attacks start. Files above :data:`MAX_BYTES` are refused before parsing.
"""

from __future__ import annotations

import codecs
import contextlib
import os
import re
import stat

from lxml import etree

from robodesc.ir.diagnostics import Findings, ParseError, SourceLoc

MAX_BYTES = 256 * 1024 * 1024
_DOCTYPE = re.compile(rb"<!DOCTYPE", re.IGNORECASE)
_ENTITY = re.compile(rb"<!ENTITY", re.IGNORECASE)
# An XML declaration anywhere in the prolog, and what may stand before it without harm.
_DECLARATION = re.compile(rb"<\?xml(\s[^>]*?)?\?>")
_PROLOG_NOISE = re.compile(rb"\A(?:\xef\xbb\xbf)?(?:\s|<!--.*?-->)*", re.DOTALL)
_ATTR = re.compile(rb"""(version|encoding)\s*=\s*["']([^"']*)["']""")
STAGE = "frontend:xml"


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


def parse_xml(data: bytes | str, file: str | None, findings: Findings | None = None) -> etree._Element:
    """Parse ``data`` safely and return the root element. ``file`` is used for messages only.

    Two things every ROS parser (urdfdom's TinyXML2) reads without complaint are accepted here too,
    each with a warning in ``findings``: an XML declaration that is not the first thing in the file
    or names a version other than 1.0, and anything after the root element's end (NUL padding,
    a second document, editor garbage)."""
    raw = data.encode("utf-8") if isinstance(data, str) else data
    refuse_hostile(raw, file)
    raw = _tolerant_declaration(raw, file, findings)
    try:
        root = etree.fromstring(raw, _parser())
    except etree.XMLSyntaxError as exc:
        if "Namespace prefix" in str(exc.msg):
            declared = _declare_prefixes(raw, file, findings)
            if declared is not None:
                return parse_xml(declared, file, findings)
        end = _root_end(raw, exc) if "Extra content at the end" in str(exc.msg) else None
        if end is None:
            raise _syntax_error(exc, file) from None
        line = raw.count(b"\n", 0, end) + 1
        if findings is not None:
            findings.warn(
                "trailing-content",
                f"{len(raw) - end} bytes after the root element's end were ignored "
                f"({_describe(raw[end:])}); urdfdom and pybullet stop reading there too",
                loc=SourceLoc(file, line),
                stage=STAGE,
            )
        try:
            root = etree.fromstring(raw[:end], _parser())
        except etree.XMLSyntaxError as again:
            raise _syntax_error(again, file) from None
    if root is None:
        raise ParseError("empty document", loc=SourceLoc(file))
    return root


_PREFIXED = re.compile(rb"""(?:<|\s)([A-Za-z_][\w.-]*):[A-Za-z_][\w.-]*(?=[\s=/>])""")
_XMLNS = re.compile(rb"""xmlns:([A-Za-z_][\w.-]*)\s*=""")
_ROOT_START = re.compile(rb"<([A-Za-z_][\w.:-]*)")


def _declare_prefixes(raw: bytes, file: str | None, findings: Findings | None) -> bytes | None:
    """Declare namespace prefixes the file uses without declaring them (``<drake:acceleration>``):
    urdfdom and pybullet ignore namespaces, libxml2 refuses. The elements stay unknown elements,
    kept verbatim. Returns None when there is nothing to declare."""
    used = {m.group(1) for m in _PREFIXED.finditer(raw)} - {m.group(1) for m in _XMLNS.finditer(raw)}
    used -= {b"xml", b"xmlns"}
    if not used:
        return None
    prolog = _PROLOG_NOISE.match(raw)
    start = _ROOT_START.search(raw, prolog.end() if prolog is not None else 0)
    if start is None:
        return None
    names = sorted(p.decode("ascii", "replace") for p in used)
    decls = b"".join(b' xmlns:%s="urn:robodesc:undeclared:%s"' % (p, p) for p in sorted(used))
    if findings is not None:
        findings.warn(
            "undeclared-prefix",
            f"namespace prefix(es) {', '.join(names)} used without a declaration; declared for reading "
            "(urdfdom and pybullet ignore namespaces)",
            loc=SourceLoc(file, raw.count(b"\n", 0, start.start()) + 1),
            stage=STAGE,
        )
    return raw[: start.end()] + decls + raw[start.end() :]


def _syntax_error(exc: etree.XMLSyntaxError, file: str | None) -> ParseError:
    line, column = exc.position if exc.position else (None, None)
    message = str(exc.msg).split(", line ")[0]
    return ParseError(f"malformed XML: {message}", loc=SourceLoc(file, line, column))


def _describe(tail: bytes) -> str:
    stripped = tail.strip()
    if not stripped.strip(b"\0"):
        return "NUL bytes"
    return f"starting {stripped[:30].decode('utf-8', 'replace')!r}"


def _tolerant_declaration(raw: bytes, file: str | None, findings: Findings | None) -> bytes:
    """Blank out an XML declaration libxml2 would refuse: one after comments or blank lines, or
    with a version other than 1.0. Spaces keep every line number as it was; a declared encoding
    other than UTF-8 is honoured by transcoding first."""
    match = _DECLARATION.search(raw, 0, 4096)
    if match is None:
        return raw
    prolog = _PROLOG_NOISE.match(raw)
    if prolog is None or prolog.end() != match.start():
        return raw  # the declaration is not in the prolog: let the parser say what is wrong
    attrs = {k.decode(): v.decode("ascii", "replace") for k, v in _ATTR.findall(match.group(0))}
    version = attrs.get("version", "1.0")
    late = match.start() != (3 if raw.startswith(b"\xef\xbb\xbf") else 0)
    encoding = attrs.get("encoding", "utf-8")
    foreign = encoding.lower().replace("_", "-") not in ("utf-8", "utf8")
    if not late and version in ("1.0", "1.1") and not foreign:
        return raw
    if foreign:
        # An unknown or wrong encoding: read as UTF-8, and the parser reports the bad bytes.
        with contextlib.suppress(LookupError, UnicodeDecodeError):
            raw = raw.decode(codecs.lookup(encoding).name).encode("utf-8")
        match = _DECLARATION.search(raw, 0, 4096)
        assert match is not None
    why = "is not at the start of the file" if late else f"names XML version {version!r}"
    if findings is not None and (late or version not in ("1.0", "1.1")):
        findings.warn(
            "xml-declaration",
            f"the XML declaration {why}; it was ignored and the file read as XML 1.0 "
            "(urdfdom and pybullet accept it, libxml2 would not)",
            loc=SourceLoc(file, raw.count(b"\n", 0, match.start()) + 1),
            stage=STAGE,
        )
    blank = re.sub(rb"[^\n]", b" ", match.group(0))
    return raw[: match.start()] + blank + raw[match.end() :]


def _root_end(raw: bytes, exc: etree.XMLSyntaxError) -> int | None:
    """The offset just past the root element's end tag, from libxml2's "extra content" error."""
    if not exc.position:
        return None
    line, column = exc.position
    start = 0
    for _ in range(line - 1):
        start = raw.find(b"\n", start) + 1
        if start == 0:
            return None
    # libxml2 counts columns in characters: convert to bytes through the line's UTF-8 text.
    stop = raw.find(b"\n", start)
    text = raw[start : stop if stop >= 0 else len(raw)].decode("utf-8", "replace")
    offset = start + len(text[: max(column - 1, 0)].encode("utf-8"))
    head = raw[:offset].rstrip()
    return len(head) if head.endswith(b">") else None


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
