"""Every option of a compile, in one table shared by the Python API and the CLI.

The API takes them as keyword arguments; the CLI's flags map onto the same names. An unknown name
is a :class:`ConfigError` that names the closest valid one.
"""

from __future__ import annotations

import dataclasses
import difflib
import enum
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from robodesc.emit.common.paths import PathMode
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.frontends.world.options import WorldOptions
from robodesc.ir.diagnostics import ConfigError


class InvalidInertia(enum.Enum):
    """What physically invalid masses and inertias in the source do."""

    ERROR = "error"  # fail with one line per defect
    WARN = "warn"  # pass them through unchanged, as warnings (the default: the output carries them faithfully)
    REPAIR = "repair"  # repair them (from geometry where there is geometry) and report each repair


@dataclass(slots=True)
class CompileOptions:
    # ---- input (``strict`` there also makes every warning of the compile an error) ------------
    load: LoadOptions = field(default_factory=LoadOptions)
    invalid_inertia: InvalidInertia = InvalidInertia.WARN
    # Modules that add targets or frontends (robodesc.plugins), loaded before anything else.
    plugins: tuple[str, ...] = ()
    # ---- passes ------------------------------------------------------------------------------
    preset: str | None = None
    passes: dict[str, Any] = field(default_factory=dict)
    # ---- output ------------------------------------------------------------------------------
    mesh_paths: PathMode = PathMode.RELATIVE
    target_options: dict[str, Any] = field(default_factory=dict)
    validate: bool = True
    # ---- the world around the robot (--world FILE, --terrain, --spawn; docs/worlds.md) ----------
    world: WorldOptions = field(default_factory=WorldOptions)
    # Contact sensors: "" on the feet robodesc finds, a regex on the links it fully matches, None none.
    contact_sensors: str | None = None

    @property
    def strict(self) -> bool:
        """Every warning is an error (exit 2, nothing written), for pipelines that want no surprises."""
        return self.load.strict


_ENUMS: dict[str, type[enum.Enum]] = {
    "missing_mesh": MissingMesh,
    "invalid_inertia": InvalidInertia,
    "mesh_paths": PathMode,
}


def closest(name: str, candidates: list[str]) -> str:
    """``"; did you mean 'x'?"`` or an empty string."""
    match = difflib.get_close_matches(name, candidates, n=1, cutoff=0.5)
    return f"; did you mean {match[0]!r}?" if match else ""


def build_options(values: Mapping[str, Any], *, extra_names: Mapping[str, str] | None = None) -> CompileOptions:
    """Make :class:`CompileOptions` from keyword arguments.

    ``extra_names`` maps further accepted names (pass and target options) to the bucket that keeps
    them (``"passes"`` or ``"target_options"``).
    """
    extra = dict(extra_names or {})
    loading = [f.name for f in dataclasses.fields(LoadOptions)]
    known = [f.name for f in dataclasses.fields(CompileOptions) if f.name not in _BUCKETS] + loading + list(WORLD_NAMES)
    opts = CompileOptions()
    for name, value in values.items():
        if name in WORLD_NAMES and not (name == "world" and isinstance(value, bool)):
            # ``world=True`` is SDF's empty-world switch (a target option); a path is a world file.
            if name == "spawn" and value is not None and _several_points(value):
                # Several points: a copy of the robot at each (docs/worlds.md, "Several robots").
                opts.world.copies = tuple(_world_value(name, point) for point in value)
                opts.world.spawn = opts.world.copies[0]
            elif value is not None:
                setattr(opts.world, WORLD_NAMES[name], _world_value(name, value))
                if name == "model_path":
                    # An SDF model's includes resolve through the same folders as the world's.
                    opts.load.model_path = opts.world.model_path
            continue
        check_numbers(value, name)
        if name == "contact_sensors":
            opts.contact_sensors = "" if value is True else None if value is False else value
            continue
        if name in extra:
            getattr(opts, extra[name])[name] = value
            continue
        if name not in known:
            raise ConfigError(f"unknown option {name!r}{closest(name, known + sorted(extra))}")
        if name in _ENUMS and not isinstance(value, _ENUMS[name]):
            enum_type = _ENUMS[name]
            try:
                value = enum_type(value)
            except ValueError:
                allowed = ", ".join(repr(e.value) for e in enum_type)
                raise ConfigError(f"option {name}={value!r}: expected one of {allowed}") from None
        setattr(opts.load if name in loading else opts, name, value)
    return opts


# The largest magnitude an option may have: the verifier's bound on every number of the IR
# (docs/security.md); options become numbers of the output (gains, offsets, poses) the same way.
OPTION_LIMIT = 1e30


def check_numbers(value: Any, name: str, rule: str = "") -> None:
    """Refuse (exit 2) a number that is NaN, infinite or beyond ±1e30 anywhere in an option's value
    (a number, a vector, a REGEX=VALUE table): written into a file, ``nan`` breaks every consumer
    (the Isaac Lab module's ``init_state`` did not import; USD read ``contactOffset = nan``)."""
    if isinstance(value, bool | str | enum.Enum) or value is None:
        return
    if isinstance(value, int | float):
        if not math.isfinite(value) or abs(value) > OPTION_LIMIT:
            given = f"'{rule}={value!r}'" if rule else repr(value)
            flag = "--" + name.replace("_", "-")
            raise ConfigError(f"{flag} {given}: expected a finite number within ±{OPTION_LIMIT:g}")
    elif isinstance(value, Mapping):
        for key, item in value.items():
            check_numbers(item, name, str(key) if key != ".*" else "")
    elif isinstance(value, tuple | list):
        for item in value:
            check_numbers(item, name, rule)


# Fields of CompileOptions that are not options themselves but hold them.
_BUCKETS = ("load", "passes", "target_options", "world")

# The world's keyword options (API and CLI) and the WorldOptions field each sets.
WORLD_NAMES = {
    "world": "file",
    "terrain": "terrain",
    "terrain_size": "terrain_size",
    "terrain_resolution": "terrain_resolution",
    "spawn": "spawn",
    "model_path": "model_path",
    "cords": "cords",
}


def _several_points(value: Any) -> bool:
    """``spawn=[(x, y), (x, y, z)]``: a list of points, not one point."""
    return isinstance(value, list | tuple) and bool(value) and all(isinstance(v, list | tuple) for v in value)


def _world_value(name: str, value: Any) -> Any:
    import math
    import os

    if name in ("world", "terrain", "cords"):
        return os.fspath(value)
    if name == "model_path":
        return (os.fspath(value),) if isinstance(value, str | os.PathLike) else tuple(os.fspath(v) for v in value)
    if name == "terrain_resolution":
        number = float(value)
        if not (math.isfinite(number) and number > 0):
            raise ConfigError(f"terrain_resolution={value!r}: a positive number of metres")
        return number
    numbers = tuple(float(v) for v in value)
    if not all(math.isfinite(v) for v in numbers):
        raise ConfigError(f"{name}={value!r}: finite numbers")
    return numbers


def dataclass_from_mapping(cls: type[Any], values: Mapping[str, Any], what: str) -> Any:
    """Instantiate an options dataclass from names and loosely typed values (CLI strings, enum
    values), rejecting unknown names with the closest valid one."""
    import typing

    hints = typing.get_type_hints(cls)
    names = [f.name for f in dataclasses.fields(cls)]
    kwargs: dict[str, Any] = {}
    for name, value in values.items():
        if name not in names:
            raise ConfigError(f"unknown {what} option {name!r}{closest(name, names)}")
        kwargs[name] = _coerce(hints.get(name), value, f"{what} option {name}")
    return cls(**kwargs)


def _coerce(hint: Any, value: Any, label: str) -> Any:
    import typing

    candidates = typing.get_args(hint) if typing.get_origin(hint) in (typing.Union, _UNION_TYPE) else (hint,)
    for candidate in candidates:
        if isinstance(candidate, type) and issubclass(candidate, enum.Enum):
            if isinstance(value, candidate):
                return value
            try:
                return candidate(value)
            except ValueError:
                allowed = ", ".join(repr(e.value) for e in candidate)
                raise ConfigError(f"{label}={value!r}: expected one of {allowed}") from None
    return value


_UNION_TYPE = type(int | None)
