"""Manifests: one row per job, in YAML or CSV.

YAML::

    defaults:                      # optional, applies to every job
      target: usd
      options: {missing_mesh: warn, fix_base: false}
    jobs:
      - input: robots/arm.urdf.xacro     # relative to the manifest's folder
        target: sdf                      # optional (else defaults, else the command line's)
        output: arm/arm.sdf              # optional, relative to the batch's output folder
        id: arm                          # optional: the job's name and folder
        args: {use_gripper: "true"}      # xacro arguments
        packages: {arm_description: robots/arm}
        options: {preset: gazebo}        # any compile option, by its Python API name
        sweep: {grid: {link_length: [0.3, 0.4]}}   # optional: this row becomes its variants

CSV: a header row, then one job per row. Columns ``input`` (required), ``target``, ``output``, ``id``,
``args`` and ``packages`` (``NAME=VALUE`` separated by ``;``), and any compile option by name
(``missing_mesh``, ``fix_base`` ...; cells are read as YAML scalars: ``true``, ``0.5``, ``warn``).
"""

from __future__ import annotations

import csv
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from robodesc.ir.diagnostics import ConfigError, ParseError, SourceLoc
from robodesc.options import closest

ROW_KEYS = ["input", "target", "output", "id", "args", "packages", "options", "sweep"]


@dataclass(slots=True)
class Row:
    where: str  # "manifest.yaml:12" for messages
    input: str  # absolute
    target: str | None = None
    output: str | None = None  # relative to the batch root, or absolute
    id: str | None = None
    options: dict[str, Any] = field(default_factory=dict)  # API names, xacro_args/package_paths included
    sweep: dict[str, Any] | None = None


def _loader() -> Any:
    """libyaml's safe loader where PyYAML has it (a 1,000-job manifest in milliseconds, not a
    second), else PyYAML's own; both build plain data only."""
    import yaml

    return getattr(yaml, "CSafeLoader", yaml.SafeLoader)


def is_manifest(path: str) -> bool:
    lower = path.lower()
    if lower.endswith(".csv"):
        return True
    if not lower.endswith((".yaml", ".yml")):
        return False
    import yaml

    try:
        with open(path, encoding="utf-8") as handle:
            node = yaml.compose(handle, Loader=_loader())
    except (OSError, UnicodeDecodeError, yaml.YAMLError):
        return False
    # The top-level keys are enough: a composition YAML has links:, a manifest jobs:.
    if not isinstance(node, yaml.MappingNode):
        return False
    keys = {getattr(key, "value", None) for key, _ in node.value}
    return "jobs" in keys and "links" not in keys


def read_manifest(path: str) -> list[Row]:
    return _read_csv(path) if path.lower().endswith(".csv") else _read_yaml(path)


def _mapping(value: Any, what: str, where: str) -> dict[str, Any]:
    if value is None:
        return {}
    if not isinstance(value, Mapping):
        raise ConfigError(f"{where}: {what} must be a mapping, got {value!r}")
    return {str(k): v for k, v in value.items()}


def _row(data: Mapping[str, Any], defaults: Mapping[str, Any], base: str, where: str) -> Row:
    for key in data:
        if key not in ROW_KEYS:
            raise ConfigError(f"{where}: unknown job key {key!r}{closest(str(key), ROW_KEYS)}")
    if not data.get("input"):
        raise ConfigError(f"{where}: a job needs input: FILE")
    options = {
        **_mapping(defaults.get("options"), "defaults options", where),
        **_mapping(data.get("options"), "options", where),
    }
    args = {**_mapping(defaults.get("args"), "defaults args", where), **_mapping(data.get("args"), "args", where)}
    packages = {
        **_mapping(defaults.get("packages"), "defaults packages", where),
        **_mapping(data.get("packages"), "packages", where),
    }
    if args:
        options["xacro_args"] = {**_mapping(options.get("xacro_args"), "xacro_args", where), **args}
    if packages:
        given = {**_mapping(options.get("package_paths"), "package_paths", where), **packages}
        options["package_paths"] = {k: os.path.join(base, str(v)) for k, v in given.items()}
    sweep = data.get("sweep", defaults.get("sweep"))
    if sweep is not None and not isinstance(sweep, Mapping):
        raise ConfigError(f"{where}: sweep must be a mapping (grid, random, samples, seed)")
    target = data.get("target", defaults.get("target"))
    return Row(
        where=where,
        input=os.path.join(base, str(data["input"])),
        target=str(target) if target is not None else None,
        output=str(data["output"]) if data.get("output") else None,
        id=str(data["id"]) if data.get("id") else None,
        options=options,
        sweep=dict(sweep) if sweep is not None else None,
    )


def _read_yaml(path: str) -> list[Row]:
    import yaml

    try:
        with open(path, encoding="utf-8") as handle:
            text = handle.read()
        loader = _loader()(text)
        try:  # one parse: the nodes (for line numbers), then the data built from them
            node = loader.get_single_node()
            data = loader.construct_document(node) if node is not None else None
        finally:
            loader.dispose()
    except OSError as exc:
        raise ParseError(f"cannot read manifest: {exc.strerror}", loc=SourceLoc(path)) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        loc = SourceLoc(path, mark.line + 1, mark.column + 1) if mark is not None else SourceLoc(path)
        raise ParseError(f"manifest is not valid YAML: {getattr(exc, 'problem', exc)}", loc=loc) from None
    if not isinstance(data, dict) or not isinstance(data.get("jobs"), list):
        raise ConfigError(f"{path}: a manifest is a mapping with jobs: [ ... ] (and optional defaults:)")
    for key in data:
        if key not in ("jobs", "defaults"):
            raise ConfigError(f"{path}: unknown manifest key {key!r}{closest(str(key), ['jobs', 'defaults'])}")
    lines = _job_lines(node)
    defaults = _mapping(data.get("defaults"), "defaults", path)
    base = os.path.dirname(os.path.abspath(path))
    rows = []
    for index, item in enumerate(data["jobs"]):
        where = f"{path}:{lines[index]}" if index < len(lines) else path
        if not isinstance(item, Mapping):
            raise ConfigError(f"{where}: job {index + 1}: expected a mapping with input: FILE")
        rows.append(_row(item, defaults, base, where))
    return rows


def _job_lines(node: Any) -> list[int]:
    """1-based line of each entry of ``jobs:`` (for messages)."""
    import yaml

    if not isinstance(node, yaml.MappingNode):
        return []
    for key, value in node.value:
        if getattr(key, "value", None) == "jobs" and isinstance(value, yaml.SequenceNode):
            return [item.start_mark.line + 1 for item in value.value]
    return []


def _pairs(text: str, column: str, where: str) -> dict[str, str]:
    out = {}
    for item in text.replace(";", " ").split():
        name, sep, value = item.partition("=")
        name = name.removesuffix(":")
        if not sep or not name:
            raise ConfigError(f"{where}: column {column}: expected NAME=VALUE; ..., got {item!r}")
        out[name] = value
    return out


def _read_csv(path: str) -> list[Row]:
    import yaml

    base = os.path.dirname(os.path.abspath(path))
    rows = []
    try:
        with open(path, encoding="utf-8", newline="") as handle:
            reader = csv.DictReader(handle)
            if not reader.fieldnames or "input" not in reader.fieldnames:
                raise ConfigError(f"{path}:1: the first row names the columns, and one of them is input")
            for record in reader:
                where = f"{path}:{reader.line_num}"
                if None in record:
                    raise ConfigError(f"{where}: more cells than columns")
                data: dict[str, Any] = {}
                options: dict[str, Any] = {}
                for column, cell in record.items():
                    cell = (cell or "").strip()
                    if not cell:
                        continue
                    if column in ("input", "target", "output", "id"):
                        data[column] = cell
                    elif column in ("args", "packages"):
                        data[column] = _pairs(cell, column, where)
                    else:
                        try:
                            options[column] = yaml.safe_load(cell)
                        except yaml.YAMLError:
                            options[column] = cell
                if not data and not options:
                    continue  # a blank row
                data["options"] = options
                rows.append(_row(data, {}, base, where))
    except OSError as exc:
        raise ParseError(f"cannot read manifest: {exc.strerror}", loc=SourceLoc(path)) from None
    return rows
