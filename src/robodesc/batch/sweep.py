"""Variant sweeps over xacro arguments: a grid (every combination) and seeded random samples.

    grid:   {leg_length: [0.30, 0.35, 0.40], payload: [0, 1]}     # 6 variants
    random: {mass: {uniform: [1.0, 2.0]}, tool: {choice: [a, b]}, teeth: {randint: [10, 20]}}
    samples: 50                                                      # random points (per grid point)
    seed: 7

The same seed gives the same variants on every machine (Python's Mersenne Twister, values written
with 6 significant digits).
"""

from __future__ import annotations

import itertools
import random
from collections.abc import Mapping
from typing import Any

from robodesc.ir.diagnostics import ConfigError


def _text(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)


def _pair(spec: Any, name: str, kind: str, where: str) -> tuple[float, float]:
    if not (isinstance(spec, list | tuple) and len(spec) == 2 and all(isinstance(v, int | float) for v in spec)):
        raise ConfigError(f"{where}: sweep random {name}: {kind} takes [LOW, HIGH], got {spec!r}")
    low, high = float(spec[0]), float(spec[1])
    if low > high:
        raise ConfigError(f"{where}: sweep random {name}: {kind} [{spec[0]}, {spec[1]}] has LOW > HIGH")
    return low, high


def _draw(rng: random.Random, name: str, spec: Any, where: str) -> str:
    if isinstance(spec, list):  # a bare list is a choice
        spec = {"choice": spec}
    if not isinstance(spec, Mapping) or len(spec) != 1:
        raise ConfigError(f"{where}: sweep random {name}: expected {{uniform|choice|randint: ...}}, got {spec!r}")
    kind, value = next(iter(spec.items()))
    if kind == "uniform":
        low, high = _pair(value, name, kind, where)
        return _text(rng.uniform(low, high))
    if kind == "randint":
        low, high = _pair(value, name, kind, where)
        return _text(rng.randint(int(low), int(high)))
    if kind == "choice":
        if not isinstance(value, list) or not value:
            raise ConfigError(f"{where}: sweep random {name}: choice takes a non-empty list")
        return _text(rng.choice(value))
    raise ConfigError(f"{where}: sweep random {name}: unknown distribution {kind!r} (uniform, choice, randint)")


def expand(spec: Mapping[str, Any], where: str) -> list[dict[str, str]]:
    """The xacro argument sets a sweep stands for, in a fixed order."""
    unknown = set(spec) - {"grid", "random", "samples", "seed"}
    if unknown:
        raise ConfigError(f"{where}: unknown sweep key {sorted(unknown)[0]!r} (grid, random, samples, seed)")
    grid = spec.get("grid") or {}
    randoms = spec.get("random") or {}
    if not isinstance(grid, Mapping) or not isinstance(randoms, Mapping):
        raise ConfigError(f"{where}: sweep grid and random are mappings of argument names")
    for name, values in grid.items():
        if not isinstance(values, list) or not values:
            raise ConfigError(f"{where}: sweep grid {name}: expected a non-empty list of values, got {values!r}")
    samples = spec.get("samples", 1 if not randoms else None)
    if randoms and (not isinstance(samples, int) or samples < 1):
        raise ConfigError(f"{where}: a random sweep needs samples: N (a positive integer)")
    seed = spec.get("seed", 0)
    if not isinstance(seed, int):
        raise ConfigError(f"{where}: sweep seed must be an integer, got {seed!r}")
    names = list(grid)
    points = [dict(zip(names, (_text(v) for v in combo), strict=True)) for combo in itertools.product(*grid.values())]
    if not randoms:
        return points
    rng = random.Random(seed)
    out = []
    for point in points:
        for _ in range(int(samples or 1)):
            out.append({**point, **{name: _draw(rng, name, dist, where) for name, dist in randoms.items()}})
    return out


def from_cli(items: list[str], samples: int | None, seed: int) -> dict[str, Any] | None:
    """``--sweep NAME=V1,V2`` (grid) and ``--sweep NAME=LOW..HIGH`` (uniform, with ``--samples``)."""
    if not items:
        return None
    grid: dict[str, list[str]] = {}
    randoms: dict[str, Any] = {}
    for item in items:
        name, sep, values = item.partition("=")
        name = name.removesuffix(":")
        if not sep or not name or not values:
            raise ConfigError(f"--sweep {item!r}: expected NAME=V1,V2,... or NAME=LOW..HIGH")
        low, dots, high = values.partition("..")
        if dots:
            try:
                randoms[name] = {"uniform": [float(low), float(high)]}
            except ValueError:
                raise ConfigError(f"--sweep {item!r}: LOW..HIGH must be numbers") from None
        else:
            grid[name] = values.split(",")
    if randoms and samples is None:
        raise ConfigError("--sweep NAME=LOW..HIGH draws random values: give --samples N (and --seed)")
    spec: dict[str, Any] = {"grid": grid, "random": randoms, "seed": seed}
    if samples is not None:
        spec["samples"] = samples
    return spec
