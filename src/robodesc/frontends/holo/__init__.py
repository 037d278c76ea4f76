"""HoloScript ``.holo`` compositions: lexer, parser and lowering to the IR through the builder.

This package's ``__init__`` is the frontend's front door; the parser loads when a file is read."""

from __future__ import annotations

from robodesc.frontends.contract import Frontend
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot


def read_holo(path: str, options: LoadOptions, findings: Findings) -> Robot:
    from robodesc.frontends.holo.lower import holo_frontend

    return holo_frontend(path, options, findings)


FRONTEND = Frontend(name="holo", label="HoloScript (.holo)", suffixes=(".holo",), read=read_holo)

__all__ = ["FRONTEND"]
