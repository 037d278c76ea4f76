"""The contract between the pipeline and a target: what it is handed and what it hands back.

A target package exports one :class:`Target`; the pipeline looks it up by name in its target table
and knows nothing else about it. Adding a target is adding a package that exports one of these.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from robodesc.emit.common.paths import PathMode
from robodesc.ir.diagnostics import ConfigError, Finding, Findings
from robodesc.ir.model import Robot


@dataclass(slots=True)
class Emitted:
    """What an emitter produced: the main text (when it is text) and every file written."""

    text: str | None = None
    files: dict[str, str] = field(default_factory=dict)  # role -> path
    # Emitter-specific data validation needs (the SDF emitter's renamed links and joints).
    extra: dict[str, Any] = field(default_factory=dict)


@dataclass(slots=True, frozen=True)
class EmitRequest:
    """Where and how to write: ``options`` is an instance of the target's options class (or None)."""

    out: str | None
    options: Any
    mesh_paths: PathMode = PathMode.RELATIVE
    # Option names the user gave explicitly; a target may fill the others from the robot
    # (a composition's fixed base, its placement).
    given: frozenset[str] = frozenset()

    def output(self, what: str) -> str:
        """The output path, for targets that cannot write to standard output."""
        if not self.out:
            raise ConfigError(what)
        return self.out

    def default(self, name: str, value: Any) -> None:
        """Set option ``name`` from the robot (``value``) unless the user gave it or there is none."""
        if name not in self.given and value is not None:
            setattr(self.options, name, value)


EmitFunction = Callable[[Robot, EmitRequest, Findings], Emitted]
# Called once validation has run, for reports written beside the output (the Isaac folder's
# findings.md and validation.md): (robot, out, findings, validation report or None) -> role -> path.
FinishFunction = Callable[[Robot, str, list[Finding], Any], dict[str, str]]


@dataclass(slots=True, frozen=True)
class Target:
    name: str
    emit: EmitFunction
    # The options dataclass the target takes; None when it takes none.
    options: type[Any] | None = None
    # The output is a folder rather than a file.
    folder: bool = False
    # Passes the target cannot do without (USD prim names must be identifiers ...).
    passes: Mapping[str, bool] = field(default_factory=dict)
    # The preset the target implies when the user names none.
    preset: str | None = None
    # Which consumer checks the output: "urdf" (MuJoCo reads the URDF text, or the URDF a folder
    # holds), "sdf" (Drake), "usd" (MuJoCo's USD importer and usd-core's physics parser).
    validator: str = "urdf"
    finish: FinishFunction | None = None
