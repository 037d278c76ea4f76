"""Targets and frontends from outside robodesc: ``--plugin MODULE`` (``plugins=`` in the API).

A plugin is a module that exports ``TARGET`` (a :class:`~robodesc.emit.common.target.Target`),
``FRONTEND`` (a :class:`~robodesc.frontends.contract.Frontend`), or both: exactly what robodesc's own
target and frontend packages export, so a plugin is written the way a built-in is. Loading it adds
it to the target table or the frontend table. It is code and runs when loaded: only modules the user
names are loaded, and ``robodesc batch`` workers load the same ones before each job.
"""

from __future__ import annotations

import importlib
from collections.abc import Sequence

from robodesc.emit.common.target import Target
from robodesc.frontends.contract import Frontend
from robodesc.frontends.load import FRONTENDS
from robodesc.ir.diagnostics import ConfigError
from robodesc.targets import TARGETS


def load_plugins(modules: Sequence[str]) -> None:
    for name in modules:
        try:
            module = importlib.import_module(name)
        except ImportError as exc:
            raise ConfigError(f"--plugin {name}: cannot import it ({exc})") from None
        target = getattr(module, "TARGET", None)
        frontend = getattr(module, "FRONTEND", None)
        if not isinstance(target, Target) and not isinstance(frontend, Frontend):
            raise ConfigError(f"--plugin {name}: exports neither TARGET (a Target) nor FRONTEND (a Frontend)")
        if isinstance(target, Target):
            TARGETS.setdefault(target.name, name)
        if isinstance(frontend, Frontend):
            FRONTENDS.setdefault(frontend.name, name)
