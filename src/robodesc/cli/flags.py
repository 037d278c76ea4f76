"""Target flags, made from the targets' options dataclasses (``robodesc.emit.common.flags``).

Several targets may declare the same field (``fix_base``, ``stiffness``): it becomes one flag whose
help names every target that takes it, and its value goes to whichever target runs."""

from __future__ import annotations

import argparse
import dataclasses
import enum
import functools
import typing
from collections.abc import Callable
from typing import Any

from robodesc.emit.common.flags import Flag, declared_flags, flag_name
from robodesc.ir.diagnostics import ConfigError
from robodesc.targets import TARGETS, target_spec


def _declarations() -> dict[str, tuple[dataclasses.Field[Any], Flag, type[Any], list[str]]]:
    """flag name -> (field, declaration, options class, targets that take it), in table order."""
    found: dict[str, tuple[dataclasses.Field[Any], Flag, type[Any], list[str]]] = {}
    for name in TARGETS:
        spec = target_spec(name)
        if spec.options is None:
            continue
        for field, decl in declared_flags(spec.options):
            key = flag_name(field)
            if key in found:
                if found[key][0].name != field.name:
                    raise ConfigError(f"{key} names option {field.name!r} of {name} and {found[key][0].name!r}")
                found[key][3].append(name)
            else:
                found[key] = (field, decl, spec.options, [name])
    return found


def target_lines() -> str:
    """One line per target for --help."""
    lines = []
    for name in TARGETS:
        spec = target_spec(name)
        suffix = "a folder" if spec.folder else "/".join(spec.suffixes)
        lines.append(f"  {name:<7} {spec.summary} ({suffix})")
    return "\n".join(lines)


def add_target_flags(parser: argparse.ArgumentParser) -> None:
    groups: dict[str, argparse._ArgumentGroup] = {}
    for key, (field, decl, cls, targets) in _declarations().items():
        title = target_spec(targets[0]).options_title or f"{targets[0]} (-t {targets[0]})"
        group = groups.get(title) or groups.setdefault(title, parser.add_argument_group(title))
        takes = f" [{', '.join(targets)}]"
        kwargs: dict[str, Any] = {"dest": f"target__{field.name}", "default": None, "help": decl.help + takes}
        if decl.kind == "switch":
            kwargs["action"] = argparse.BooleanOptionalAction
        elif decl.kind == "on":
            kwargs["action"] = "store_const"
            kwargs["const"] = True if decl.const is None else decl.const
        elif decl.kind in ("rules", "vector"):
            kwargs["action"] = "append" if decl.kind == "rules" else "store"
            kwargs["metavar"] = decl.metavar or ("VALUE|REGEX=VALUE" if decl.kind == "rules" else "X,Y,Z")
        else:
            choices = decl.choices or _enum_choices(cls, field)
            if choices:
                kwargs["choices"] = list(choices)
            if decl.type is not None:
                kwargs["type"] = decl.type
            if decl.metavar or not choices:
                kwargs["metavar"] = decl.metavar or field.name.upper()
        group.add_argument(key, **kwargs)


def _enum_choices(cls: type[Any], field: dataclasses.Field[Any]) -> tuple[str, ...] | None:
    hint = typing.get_type_hints(cls).get(field.name)
    for candidate in (*typing.get_args(hint), hint):
        if isinstance(candidate, type) and issubclass(candidate, enum.Enum):
            return tuple(str(e.value) for e in candidate)
    return None


def target_options(args: argparse.Namespace) -> dict[str, Any]:
    """Only the target flags the user set, by option name, so every options class keeps its own
    defaults; rules and vectors parsed."""
    given: dict[str, Any] = {}
    for key, (field, decl, _, _) in _declarations().items():
        value = getattr(args, f"target__{field.name}", None)
        if value is None:
            continue
        if decl.kind == "rules":
            value = _rules(value, key, decl.rules_only, decl.rule_value or functools.partial(_number, flag=key))
        elif decl.kind == "vector":
            value = _vector(value, key, decl.size)
        given[field.name] = value
    return given


def gain_rules(values: list[str], flag: str) -> Any:
    """A gain flag's value (``validate --dynamics --stiffness``): one number, or REGEX=VALUE rules."""
    return _rules(values, flag, False, functools.partial(_number, flag=flag))


def _rules(values: list[str], flag: str, rules_only: bool, parse: Callable[[str], Any]) -> Any:
    """``--stiffness 100``, or ``--stiffness 'knee.*=50' --stiffness '.*=20'``: rules in order, first
    full match wins; a bare value among rules applies to every name the rules leave (it goes last)."""
    if len(values) == 1 and "=" not in values[0]:
        value = parse(values[0])
        return {".*": value} if rules_only else value
    table: dict[str, Any] = {}
    fallback = None
    for item in values:
        pattern, sep, text = item.rpartition("=")
        if not sep:
            fallback = parse(item)
            continue
        if not pattern:
            raise ConfigError(f"{flag} {item!r}: expected a value or REGEX=VALUE")
        table[pattern] = parse(text)
    if fallback is not None:
        table.setdefault(".*", fallback)
    return table


def _vector(text: str, flag: str, size: int) -> tuple[float, ...]:
    parts = text.split(",")
    if len(parts) != size:
        raise ConfigError(f"{flag} {text!r}: expected {size} comma-separated numbers")
    return tuple(_number(p, flag) for p in parts)


def _number(text: str, flag: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise ConfigError(f"{flag} {text!r}: expected a number") from None
