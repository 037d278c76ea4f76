"""Fields of compliant cords from a YAML file (``--cords FILE``), checked field by field.

```yaml
cords:
  - name: underbrush      # prim, body and model names start with it
    count: 20             # cords in the field
    length: 0.6           # m, anchor to tip
    segments: 6           # capsules per cord (joints: one per segment, the first at the anchor)
    radius: 0.008         # m
    stiffness: 0.2        # N·m/rad at every joint (bending)
    damping: 0.005        # N·m·s/rad at every joint
    anchor_height: [0.7, 0.9]   # m, each anchor's height drawn in this range
    area: [-1, -1, 1, 1]        # x0, y0, x1, y1 (m): where the anchors are drawn
    seed: 0               # the draw's seed: the same field every time
    mass: 0.03            # kg per cord (default: the capsules' volume at 1000 kg/m³)
```

Read with ``yaml.safe_load`` (no tags, no code) and a size limit; every number must be finite and in
its range, else the message names the field and the file."""

from __future__ import annotations

import math
from typing import Any

from robodesc.ir.diagnostics import ConfigError, ParseError, SourceLoc
from robodesc.ir.world import CordField

MAX_BYTES = 1 << 20
MAX_CORDS = 10_000
MAX_SEGMENTS = 200


def read_cords(path: str) -> list[CordField]:
    import yaml

    try:
        with open(path, "rb") as handle:
            raw = handle.read(MAX_BYTES + 1)
    except OSError as exc:
        raise ParseError(f"cannot read: {exc.strerror}", loc=SourceLoc(path)) from None
    if len(raw) > MAX_BYTES:
        raise ParseError(f"a cords file is at most {MAX_BYTES // 1024} KiB", loc=SourceLoc(path))
    try:
        data = yaml.safe_load(raw)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        line = mark.line + 1 if mark is not None else None
        raise ParseError(f"not YAML: {getattr(exc, 'problem', exc)}", loc=SourceLoc(path, line)) from None
    items = data.get("cords") if isinstance(data, dict) else None
    if not isinstance(items, list) or not items:
        raise ParseError("expected a mapping with a non-empty list 'cords:'", loc=SourceLoc(path))
    fields = [_field(path, i, item) for i, item in enumerate(items)]
    names = [f.name for f in fields]
    if len(set(names)) != len(names):
        raise ConfigError(f"{path}: two cord fields share a name ({', '.join(names)})")
    return fields


def _field(path: str, index: int, item: Any) -> CordField:
    where = f"{path}: cords[{index}]"
    if not isinstance(item, dict):
        raise ConfigError(f"{where}: expected a mapping")
    known = {
        "name",
        "count",
        "length",
        "segments",
        "radius",
        "stiffness",
        "damping",
        "anchor_height",
        "area",
        "seed",
        "mass",
    }
    unknown = sorted(set(item) - known)
    if unknown:
        raise ConfigError(
            f"{where}: unknown field(s) {', '.join(map(str, unknown))} (known: {', '.join(sorted(known))})"
        )
    name = str(item.get("name", f"cords{index}"))
    if not name.replace("_", "").isalnum() or name[0].isdigit():
        raise ConfigError(f"{where}: name {name!r} must be letters, digits and _ (not starting with a digit)")
    height = _pair(where, item, "anchor_height", (0.5, 1.0))
    area = item.get("area", [-1.0, -1.0, 1.0, 1.0])
    if not (isinstance(area, list) and len(area) == 4):
        raise ConfigError(f"{where}: area must be [x0, y0, x1, y1]")
    box = tuple(_number(where, "area", v) for v in area)
    if not (box[0] <= box[2] and box[1] <= box[3]):
        raise ConfigError(f"{where}: area {list(box)} must have x0 <= x1 and y0 <= y1")
    return CordField(
        name=name,
        count=_int(where, item, "count", 10, 1, MAX_CORDS),
        length=_positive(where, item, "length", 0.5),
        segments=_int(where, item, "segments", 5, 1, MAX_SEGMENTS),
        radius=_positive(where, item, "radius", 0.01),
        stiffness=_non_negative(where, item, "stiffness", 0.1),
        damping=_non_negative(where, item, "damping", 0.01),
        anchor_height=(height[0], height[1]),
        area=(box[0], box[1], box[2], box[3]),
        seed=_int(where, item, "seed", 0, 0, 2**32 - 1),
        mass=_positive(where, item, "mass", None),
        src=SourceLoc(path),
    )


def _number(where: str, key: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ConfigError(f"{where}: {key} must be a finite number, got {value!r}")
    return float(value)


def _positive(where: str, item: dict[str, Any], key: str, default: float | None) -> Any:
    if key not in item:
        return default
    value = _number(where, key, item[key])
    if not value > 0:
        raise ConfigError(f"{where}: {key} must be positive, got {value:g}")
    return value


def _non_negative(where: str, item: dict[str, Any], key: str, default: float) -> float:
    value = _number(where, key, item.get(key, default))
    if value < 0:
        raise ConfigError(f"{where}: {key} must not be negative, got {value:g}")
    return value


def _int(where: str, item: dict[str, Any], key: str, default: int, low: int, high: int) -> int:
    value = item.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise ConfigError(f"{where}: {key} must be a whole number from {low} to {high}, got {value!r}")
    return value


def _pair(where: str, item: dict[str, Any], key: str, default: tuple[float, float]) -> tuple[float, float]:
    value = item.get(key, list(default))
    if isinstance(value, int | float) and not isinstance(value, bool):
        value = [value, value]
    if not (isinstance(value, list) and len(value) == 2):
        raise ConfigError(f"{where}: {key} must be [low, high] or one number")
    low, high = (_number(where, key, v) for v in value)
    if low > high:
        raise ConfigError(f"{where}: {key} [{low:g}, {high:g}] must have low <= high")
    return low, high
