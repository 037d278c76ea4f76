"""``.xacro`` → URDF text, through the ``xacro`` package.

``$(find pkg)`` is answered by robodesc's :class:`PackageResolver` (so ``--package NAME=DIR`` works
without a ROS install), and every file xacro opens, includes too, passes the same hostile-XML check
as plain URDF first.
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import xml.parsers.expat
from collections.abc import Iterator, Mapping
from typing import Any

from lxml import etree

from robodesc.frontends.packages import PackageResolver
from robodesc.frontends.xml_safety import parse_xml, read_file, refuse_hostile
from robodesc.ir.diagnostics import Findings, ParseError, SourceLoc

STAGE = "frontend:xacro"


@contextlib.contextmanager
def _patched_xacro(resolver: PackageResolver) -> Iterator[Any]:
    import xacro
    from xacro import substitution_args

    original_find = substitution_args._eval_find
    original_parse = xacro.parse

    def find(pkg: str) -> str:
        found = resolver.find_package(pkg)
        if found is None:
            raise xacro.XacroException(
                f"package {pkg!r} not found (give it with --package {pkg}=DIR, or set ROS_PACKAGE_PATH / AMENT_PREFIX_PATH)"
            )
        return found[0]

    def parse(inp: Any, filename: str | None = None) -> Any:
        if inp is None and filename is not None:
            path = os.path.join(xacro.root_dir, filename) if hasattr(xacro, "root_dir") else filename
            try:
                data = read_file(path)
            except ParseError:
                return original_parse(inp, filename)  # let xacro report it in its own words
            refuse_hostile(data, path)
            return original_parse(data.decode("utf-8"), filename)
        return original_parse(inp, filename)

    substitution_args._eval_find = find
    xacro.parse = parse
    try:
        yield xacro
    finally:
        substitution_args._eval_find = original_find
        xacro.parse = original_parse


def expand_xacro(path: str, args: Mapping[str, str], resolver: PackageResolver, findings: Findings) -> str:
    """Expand ``path`` with xacro ``args`` and return URDF text."""
    loc = SourceLoc(path)
    refuse_hostile(read_file(path), path)
    stderr = io.StringIO()
    with _patched_xacro(resolver) as xacro, contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(stderr):
        try:
            doc = xacro.process_file(path, mappings=dict(args))
        except ParseError:
            raise
        except xacro.XacroException as exc:
            raise ParseError(f"xacro: {_clean(str(exc))}", loc=loc) from None
        except xml.parsers.expat.ExpatError as exc:
            raise ParseError(f"xacro: malformed XML: {exc}", loc=loc) from None
        except Exception as exc:  # xacro surfaces user errors as NameError, KeyError, ...
            raise ParseError(f"xacro: {type(exc).__name__}: {_clean(str(exc))}", loc=loc) from None
        finally:
            xacro.init_stacks(None)
    for line in stderr.getvalue().splitlines():
        if line.strip():
            findings.warn("xacro", _clean(line), loc=loc, stage=STAGE)
    # xacro writes few, very long lines; re-indent so that file:line in messages is useful.
    # `robodesc expand` prints this same text.
    root = parse_xml(doc.toxml(), path)
    etree.indent(root, space="  ")
    text: str = etree.tostring(root, encoding="unicode")
    return text


def _clean(text: str) -> str:
    return re.sub(r"\x1b\[[0-9;]*m", "", text).strip()
