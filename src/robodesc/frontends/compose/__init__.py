"""Compositions: robots written as parts (Python builder, YAML, HoloScript ``.holo``) → IR.

``register(frontends)`` adds the file readers to :data:`robodesc.frontends.load.FRONTENDS`.
"""

from __future__ import annotations

from collections.abc import Callable, MutableMapping

from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot

Frontend = Callable[[str, LoadOptions, Findings], Robot]


def register(frontends: MutableMapping[str, Frontend]) -> None:
    """Register ``.yaml``, ``.yml`` and ``.holo``."""
    from robodesc.frontends.compose.yaml_format import load_yaml
    from robodesc.frontends.holo.lower import holo_frontend

    frontends[".yaml"] = load_yaml
    frontends[".yml"] = load_yaml
    frontends[".holo"] = holo_frontend


__all__ = ["register"]
