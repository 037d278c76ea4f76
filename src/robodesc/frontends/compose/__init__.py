"""Compositions: robots written as parts (the Python builder, YAML) -> IR. HoloScript ``.holo`` is
its own frontend (``robodesc.frontends.holo``); Python compositions are ``compose.python``.

This package is the YAML frontend's front door: it exports ``FRONTEND`` and imports the YAML reader
only when a file is read (PyYAML and the builder cost ~40 ms to import)."""

from __future__ import annotations

from robodesc.frontends.contract import Frontend
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot


def read_yaml(path: str, options: LoadOptions, findings: Findings) -> Robot:
    from robodesc.frontends.compose.yaml_format import load_yaml

    return load_yaml(path, options, findings)


def yaml_robot(path: str) -> tuple[bool, list[str]]:
    """Discovery: a YAML file is a composition when it has ``robot:`` and ``links:``."""
    import yaml

    from robodesc.frontends.contract import head_of

    try:
        data = yaml.safe_load(head_of(path, 1 << 22))
    except (OSError, yaml.YAMLError):
        return False, []
    return isinstance(data, dict) and "robot" in data and "links" in data, []


FRONTEND = Frontend(
    name="yaml",
    label="YAML compositions (.yaml, .yml)",
    suffixes=(".yaml", ".yml"),
    read=read_yaml,
    discover=yaml_robot,
)

__all__ = ["FRONTEND"]
