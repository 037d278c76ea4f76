"""The contract between the driver and a target: what it is handed and what it hands back.

A target package exports one :class:`Target`; the driver looks it up by name in the one target table
(``robodesc.targets``) and knows nothing else about it: its output suffixes, its options (and so its
command-line flags, :mod:`robodesc.emit.common.flags`), the passes it needs, how its output is
checked and what it writes once the check has run all come from here. Adding a target is adding a
package that exports one of these, and a line in that table.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from robodesc.emit.common.paths import PathMode
from robodesc.ir.diagnostics import ConfigError, Finding, Findings
from robodesc.ir.model import Robot
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import ValidationReport

if TYPE_CHECKING:  # the world's placement reads meshes (numpy): imported only where a world is given
    from robodesc.emit.common.world import PlacedWorld


@dataclass(slots=True)
class Emitted:
    """What an emitter produced: the main text (when it is text) and every file written."""

    text: str | None = None
    files: dict[str, str] = field(default_factory=dict)  # role -> path
    # Emitter-specific data its own check needs (the SDF emitter's renamed links and joints).
    extra: dict[str, Any] = field(default_factory=dict)


@dataclass(slots=True, frozen=True)
class EmitRequest:
    """Where and how to write: ``options`` is an instance of the target's options class (or None).

    ``out`` is where to write now (a staging path beside the final one, or None for standard
    output); ``final`` is where the output will be once the run succeeds, for targets whose files
    name each other (a scene that includes the model by its file name)."""

    out: str | None
    options: Any
    mesh_paths: PathMode = PathMode.RELATIVE
    # Option names the user gave explicitly; a target may fill the others from the robot
    # (a composition's fixed base, its placement).
    given: frozenset[str] = frozenset()
    final: str | None = None
    # The world around the robot, read and placed once before every emitter (emit/common/world.py);
    # None without --world or --terrain.
    world: PlacedWorld | None = None

    def output(self, what: str) -> str:
        """The output path, for targets that cannot write to standard output."""
        if not self.out:
            raise ConfigError(what)
        return self.out

    def default(self, name: str, value: Any) -> None:
        """Set option ``name`` from the robot (``value``) unless the user gave it or there is none."""
        if name not in self.given and value is not None:
            setattr(self.options, name, value)


@dataclass(slots=True, frozen=True)
class CheckRequest:
    """What a target's check is handed besides the robot and what was emitted: where the (staged)
    output is, whether it is a folder, and the validation options."""

    out: str | None
    options: ValidateOptions
    folder: bool = False


EmitFunction = Callable[[Robot, EmitRequest, Findings], Emitted]
# Loads what was emitted in an independent consumer and compares it with the IR; None when there is
# nothing to check (no file written and no text).
CheckFunction = Callable[[Robot, Emitted, CheckRequest], ValidationReport | None]
# Called once validation has run, for reports written beside the output (the Isaac folder's
# findings.md and validation.md): (robot, out, findings, validation report or None) -> role -> path.
FinishFunction = Callable[[Robot, str, list[Finding], ValidationReport | None], dict[str, str]]
# The names of files or folders beside a file output that the output owns and a run rewrites as a
# whole (a layered USD's payloads/ folder, an MJCF scene): the driver sets the earlier ones aside and
# restores them if the run fails. Given the target's options and the final output path.
OwnedFunction = Callable[[Any, str], tuple[str, ...]]
# A world compiled alone (a world file as the input, no robot; docs/worlds.md): the files written by
# role, and the consumer's report when validation is asked.
WorldAlone = tuple[dict[str, str], ValidationReport | None]
# (the placed world, the output path, the target's options, findings, validate) -> WorldAlone.
WorldAloneFunction = Callable[["PlacedWorld", str, Any, Findings, bool], WorldAlone]


@dataclass(slots=True, frozen=True)
class Target:
    name: str
    emit: EmitFunction
    # One line for --help: what the output is for.
    summary: str = ""
    # File targets: the output suffixes accepted (the first is the default: batch and validate name
    # their outputs with it). Empty for folder targets.
    suffixes: tuple[str, ...] = ()
    # The output must end with one of ``suffixes`` (the format follows the suffix, as USD's does).
    suffix_required: bool = False
    # The options dataclass the target takes; None when it takes none. Its fields that declare a
    # flag (emit.common.flags) are the target's command-line options.
    options: type[Any] | None = None
    # The output is a folder rather than a file.
    folder: bool = False
    # The text can go to standard output when no output path is given.
    stdout: bool = False
    # Passes the target cannot do without (USD prim names must be identifiers ...).
    passes: Mapping[str, bool] = field(default_factory=dict)
    # The preset the target implies when the user names none.
    preset: str | None = None
    # How the output is checked (validation, on by default); None: it is not.
    check: CheckFunction | None = None
    finish: FinishFunction | None = None
    owned: OwnedFunction | None = None
    # The title of the target's group of options in --help.
    options_title: str = ""
    # The target derives per-joint drive gains where the user gives none (emit/common/gains.py); a
    # target with gain options that does not writes its options' constants.
    derives_gains: bool = False
    # The target writes a world around the robot (``--world``, ``--terrain``: EmitRequest.world);
    # the pipeline refuses a world for one that cannot.
    worlds: bool = False
    # The files beside a file output that a world adds (the USD world stage): protected as ``owned``
    # is, only when a world is given.
    world_files: OwnedFunction | None = None
    # Writes a world file given as the input alone (its static models and physics, no robot);
    # None: the target holds no world without a robot.
    world_alone: WorldAloneFunction | None = None
    # What ``--copy-meshes`` copies under ``meshes/`` beside the output: the files the output refers to
    # and no other, so that the flag means one thing for every target (the output names no file
    # outside its folder). USD embeds mesh geometry and refers only to textures; MJCF's writer places
    # every mesh in its folder itself and writes no texture, so the flag changes nothing there.
    copies: frozenset[str] = frozenset({"meshes", "textures"})

    def output_name(self, stem: str, suffix: str | None = None) -> str:
        """The output path for ``stem`` (a folder for folder targets), with ``suffix`` or the default."""
        if self.folder or not self.suffixes:
            return stem
        return stem + (suffix if suffix is not None else self.suffixes[0])
