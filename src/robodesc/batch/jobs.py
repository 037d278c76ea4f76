"""A batch job (one input, one target, one output) and what running it gave."""

from __future__ import annotations

import copy
import dataclasses
import enum
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from robodesc.ir.diagnostics import ConfigError
from robodesc.options import WORLD_NAMES, CompileOptions, build_options
from robodesc.targets import TARGETS, target_spec

# Outcomes of a job. Only the first two wrote their outputs (and only those are ever skipped later).
OK = "ok"
VALIDATION_FAILED = "validation-failed"
ERROR = "error"  # bad input or options: robodesc refused it with a message
CRASHED = "crashed"  # an unexpected exception, or the worker process died (a consumer's segfault)
TIMEOUT = "timeout"
OUTCOMES = (OK, VALIDATION_FAILED, ERROR, CRASHED, TIMEOUT)
WROTE_OUTPUTS = (OK, VALIDATION_FAILED)


@dataclass(slots=True)
class Job:
    """``id`` names the job and its folder under the batch's output root; ``input`` is the path as
    the user gave it (shown in the summary), ``path`` the absolute one every worker opens."""

    id: str
    input: str
    path: str
    target: str
    # Absolute: the file (urdf, sdf, usd) or folder (ros2, isaac) the compile writes; "" until
    # :func:`finalize` gives the default one under the batch's root.
    output: str
    options: CompileOptions
    variant: dict[str, str] | None = None  # the xacro arguments a sweep chose

    def options_dict(self) -> dict[str, Any]:
        """The options as plain JSON values (for the cache key and the job record)."""
        plain: dict[str, Any] = _plain(dataclasses.asdict(self.options))
        return plain


@dataclass(slots=True)
class JobResult:
    id: str
    status: str
    seconds: float = 0.0
    error: str = ""
    # The step a failed job stopped in: load, verify, passes, copy-meshes, emit, validate.
    stage: str = ""
    findings: list[dict[str, Any]] = field(default_factory=list)
    validation: dict[str, Any] | None = None  # the validation report as JSON, when validation ran
    files: dict[str, str] = field(default_factory=dict)  # role -> absolute path
    robot: dict[str, Any] | None = None  # name, links, joints
    deps: dict[str, str] = field(default_factory=dict)  # every file the job read -> content hash
    outputs: dict[str, str] = field(default_factory=dict)  # every file it wrote -> content hash
    detail: str = ""  # a crash's traceback
    cached: bool = False

    def as_dict(self) -> dict[str, Any]:
        """The fields as they are (already plain data), not deep-copied as ``dataclasses.asdict``
        would: the driver records every result, and copying each finding cost more than the rest."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> JobResult:
        names = {f.name for f in dataclasses.fields(cls)}
        return cls(**{k: v for k, v in data.items() if k in names})


def _plain(value: Any) -> Any:
    if isinstance(value, enum.Enum):
        return value.value
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    return value


def robot_stem(path: str) -> str:
    """``robot.urdf.xacro`` -> ``robot``."""
    from robodesc.frontends.load import frontends

    name = os.path.basename(path)
    lower = name.lower()
    # The suffixes robots' files end with, longest first: the job and its output are named by the rest.
    for suffix in sorted({s for f in frontends() for s in f.suffixes}, key=len, reverse=True):
        if lower.endswith(suffix) and len(name) > len(suffix):
            return name[: -len(suffix)]
    return name


def output_path(root: str, job_id: str, target: str, stem: str, suffix: str | None = None) -> str:
    """The job's output under ``root``: its folder (folder targets), or a file named after the robot
    with ``suffix`` when the target writes that suffix, else the target's default one."""
    folder = os.path.join(os.path.abspath(root), *job_id.split("/"))
    spec = target_spec(target)
    if spec.folder:
        return folder
    return os.path.join(folder, spec.output_name(stem, suffix if suffix in spec.suffixes else None))


def check_target(target: str, where: str) -> str:
    if target not in TARGETS:
        raise ConfigError(f"{where}: unknown target {target!r} (one of {', '.join(TARGETS)})")
    return target


def for_target(options: CompileOptions, target: str) -> CompileOptions:
    """``options`` keeping only the target options ``target`` takes (as ``compile`` does)."""
    cls = target_spec(target).options
    names = {f.name for f in dataclasses.fields(cls)} if cls is not None else set()
    out = copy.deepcopy(options)
    out.target_options = {k: v for k, v in options.target_options.items() if k in names}
    return out


def with_overrides(base: CompileOptions, target: str, values: Mapping[str, Any], where: str) -> CompileOptions:
    """``base`` with a job's own options (the API's names: ``xacro_args``, ``package_paths``,
    ``missing_mesh``, ``fix_base``, ``preset`` ...); xacro arguments and packages add to the base's."""
    from robodesc.passes.options import OPTION_NAMES

    opts = copy.deepcopy(base)
    rest = dict(values)
    for name in ("xacro_args", "package_paths"):
        given = rest.pop(name, None) or {}
        if not isinstance(given, Mapping):
            raise ConfigError(f"{where}: {name} must be a mapping of NAME: VALUE, got {given!r}")
        setattr(opts.load, name, {**getattr(opts.load, name), **{str(k): str(v) for k, v in given.items()}})
    cls = target_spec(target).options
    extra = {name: "passes" for name in OPTION_NAMES}
    if cls is not None:
        extra.update({f.name: "target_options" for f in dataclasses.fields(cls) if f.name not in ("out_dir", "props")})
    try:
        parsed = build_options(rest, extra_names=extra)
    except ConfigError as err:
        raise ConfigError(f"{where}: {err.message}") from None
    for name in rest:
        bucket = extra.get(name)
        if name in WORLD_NAMES and (name != "world" or isinstance(rest[name], str)):
            # A job's own world (a manifest's ``world:``, ``spawn:`` ...) over the command line's.
            field_name = WORLD_NAMES[name]
            setattr(opts.world, field_name, getattr(parsed.world, field_name))
            if name == "spawn":
                opts.world.copies = parsed.world.copies
        elif bucket is not None:
            getattr(opts, bucket)[name] = getattr(parsed, bucket)[name]
        elif hasattr(parsed.load, name):
            setattr(opts.load, name, getattr(parsed.load, name))
        else:
            setattr(opts, name, getattr(parsed, name))
    return opts


def finalize(jobs: list[Job], root: str, suffix: str | None = None) -> list[Job]:
    """Make ids unique (two jobs may not share a folder: later ones get ``-2``, ``-3`` ... in input
    order) and give every job without an output of its own the one under ``root``."""
    taken: set[str] = set()
    for job in jobs:
        parts = job.id.split("/")
        if job.id.startswith("/") or any(p in ("", ".", "..") for p in parts):
            raise ConfigError(f"job id {job.id!r}: a job's folder must stay inside the output folder")
        new, count = job.id, 1
        while new in taken:
            count += 1
            new = f"{job.id}-{count}"
        taken.add(new)
        job.id = new
        if not job.output:
            job.output = output_path(root, job.id, job.target, robot_stem(job.path), suffix)
    return jobs
