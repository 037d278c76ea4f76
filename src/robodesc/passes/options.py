"""What the passes may do: one typed options object, and parsing of option names and values.

Unknown option names, strip kinds and policies raise :class:`ConfigError` naming the closest valid
one (``difflib``), so a typo never silently turns a pass off.
"""

from __future__ import annotations

import dataclasses
import difflib
import enum
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from robodesc.ir.diagnostics import ConfigError


class RepairPolicy(enum.Enum):
    """How :mod:`robodesc.passes.repair_inertia` repairs a link (see docs/passes.md)."""

    # Quad-SDK's rules exactly (0.001 kg, 1e-6 diagonal), plus invalid tensors with a positive mass
    # repaired from geometry (the gap Quad-SDK leaves open).
    QUAD_SDK = "quad_sdk"
    # Everything from geometry (mass from density when the mass is not usable); constants only
    # where a link has no geometry.
    GEOMETRY = "geometry"


# Strip kinds, in the order their findings are reported.
STRIP_KINDS: tuple[str, ...] = ("gazebo", "transmission", "ros2_control", "dont_collapse", "contact", "surface")


@dataclass(slots=True, frozen=True)
class RenameRule:
    """Rename ``kind`` ("joint" or "link") names equal to ``pattern`` (or matching it fully when
    ``regex``) to ``replacement`` (``\\1`` group references allowed when ``regex``)."""

    pattern: str
    replacement: str
    kind: str = "joint"
    regex: bool = False

    def apply(self, name: str) -> str | None:
        if not self.regex:
            return self.replacement if name == self.pattern else None
        m = re.fullmatch(self.pattern, name)
        return m.expand(self.replacement) if m else None


@dataclass(slots=True, frozen=True)
class ArmatureRule:
    """Joints whose name matches ``pattern`` (``re.search``) get ``value`` kg·m², or
    ``j_rotor * gear_ratio**2`` when given as motor parameters."""

    pattern: str
    value: float | None = None
    j_rotor: float | None = None
    gear_ratio: float | None = None

    def armature(self) -> float:
        if self.value is not None:
            return self.value
        if self.j_rotor is None or self.gear_ratio is None:
            raise ConfigError(f"armature rule {self.pattern!r} needs a value or both j_rotor and gear_ratio")
        return self.j_rotor * self.gear_ratio**2


@dataclass(slots=True)
class PassOptions:
    """Every knob of every pass. A pass whose switch is off (``False``, empty, ``None``) does nothing."""

    # rename: ordered rules, first match wins per name.
    rename: tuple[RenameRule, ...] = ()
    # rename also ``motor_<old>`` actuators and ``transmission_<old>`` transmissions (Quad-SDK did).
    rename_actuators: bool = True
    # strip_tags: a subset of STRIP_KINDS.
    strip: frozenset[str] = frozenset()
    sanitize_names: bool = False
    unique_materials: bool = False
    # geometric_inertia: fill inertials that have a mass but no tensor.
    fill_inertia: bool = False
    # repair_inertia: None = off.
    repair_inertia: RepairPolicy | None = None
    # repair_inertia: also give links without any <inertial> one (else only invalid ones are repaired).
    repair_missing: bool = True
    # massless: a moving fixed group without any mass gets its geometry's mass (a dead body otherwise).
    mass_from_colliders: bool = False
    # massless: every massless link gets a placeholder mass, taken from its fixed group's heaviest link
    # (USD: a UsdPhysics reader cannot be told "no mass").
    placeholder_masses: bool = False
    # kg/m³, used when a mass has to be derived from geometry.
    density: float = 1000.0
    # armature: ordered rules, first match wins. ``armature_by_robot`` maps a robot name to its table
    # and is used when ``armature`` is empty (how the quad_sdk preset knows Spirit's motors).
    armature: tuple[ArmatureRule, ...] = ()
    armature_by_robot: Mapping[str, tuple[ArmatureRule, ...]] = field(default_factory=dict)
    # default_armature: estimate armature from the effort limit where the source gives none
    # (passes/default_armature.py). None = not said (the presets that simulate say True), so that an
    # explicit False overrides a preset's True (merge_options keeps what differs from the default).
    default_armature: bool | None = None
    # None = not said (the mjcf preset says True: MuJoCo fuses static bodies as menagerie's models
    # have them), so that an explicit False (--no-merge-fixed) overrides a preset's True.
    merge_fixed: bool | None = None
    isaac_limits: bool = False
    # Isaac: dont_collapse on fixed joints whose child carries a sensor, frame or loop-joint end.
    keep_bodies: bool = False
    # Report joints whose zero position lies outside their limits (go2's knees).
    zero_pose_check: bool = True
    # explicit_damping: joint damping/friction the source leaves unsaid written as 0 (as ODE has them).
    explicit_damping: bool = False
    # copy_meshes (emit time): copy meshes/textures next to the output; convert suffixes the target
    # cannot read, e.g. {".dae": ".obj"}.
    copy_meshes: bool = False
    convert_meshes: Mapping[str, str] = field(default_factory=dict)


OPTION_NAMES: tuple[str, ...] = tuple(f.name for f in dataclasses.fields(PassOptions))


def closest(name: str, choices: Iterable[str]) -> str:
    """`` (did you mean 'x'?)`` or an empty string."""
    match = difflib.get_close_matches(name, list(choices), n=1, cutoff=0.5)
    return f" (did you mean {match[0]!r}?)" if match else ""


def check_option_name(name: str) -> str:
    key = name.replace("-", "_")
    if key not in OPTION_NAMES:
        raise ConfigError(f"unknown pass option {name!r}{closest(key, OPTION_NAMES)}", element="pass options")
    return key


def parse_strip(spec: str | Iterable[str]) -> frozenset[str]:
    """``"gazebo,transmission"`` or an iterable of kinds; ``"all"`` means every kind."""
    items = [s.strip() for s in spec.split(",")] if isinstance(spec, str) else [str(s).strip() for s in spec]
    out: set[str] = set()
    for item in items:
        if not item:
            continue
        if item == "all":
            out.update(STRIP_KINDS)
        elif item not in STRIP_KINDS:
            raise ConfigError(
                f"unknown strip kind {item!r}{closest(item, (*STRIP_KINDS, 'all'))}; kinds are {', '.join(STRIP_KINDS)}",
                element="option 'strip'",
            )
        else:
            out.add(item)
    return frozenset(out)


def parse_repair_policy(spec: str | RepairPolicy | None) -> RepairPolicy | None:
    if spec is None or isinstance(spec, RepairPolicy):
        return spec
    if spec in ("", "off", "none"):
        return None
    values = [p.value for p in RepairPolicy]
    if spec not in values:
        raise ConfigError(
            f"unknown inertia repair policy {spec!r}{closest(spec, values)}; policies are {', '.join(values)}",
            element="option 'repair_inertia'",
        )
    return RepairPolicy(spec)


def parse_rename(spec: str, kind: str = "joint") -> RenameRule:
    """``OLD=NEW`` (exact) or ``re:PATTERN=REPLACEMENT`` (full-match regex); ``link:`` prefix renames links."""
    text = spec
    if text.startswith("link:"):
        kind, text = "link", text[len("link:") :]
    elif text.startswith("joint:"):
        kind, text = "joint", text[len("joint:") :]
    regex = text.startswith("re:")
    if regex:
        text = text[3:]
    old, sep, new = text.rpartition("=")
    if not sep or not old or not new:
        raise ConfigError(f"rename rule {spec!r} is not OLD=NEW (or re:PATTERN=REPLACEMENT)", element="option 'rename'")
    if regex:
        try:
            re.compile(old)
        except re.error as exc:
            raise ConfigError(f"rename rule {spec!r}: bad regex: {exc}", element="option 'rename'") from None
    return RenameRule(old, new, kind, regex)


def parse_armature(spec: str) -> ArmatureRule:
    """``REGEX=VALUE`` (kg·m²) or ``REGEX=J_ROTOR*N^2`` e.g. ``^j_knee_=1.231e-4*12^2``."""
    pattern, sep, value = spec.rpartition("=")
    if not sep or not pattern:
        raise ConfigError(f"armature rule {spec!r} is not REGEX=VALUE", element="option 'armature'")
    try:
        re.compile(pattern)
    except re.error as exc:
        raise ConfigError(f"armature rule {spec!r}: bad regex: {exc}", element="option 'armature'") from None
    m = re.fullmatch(r"\s*([^*]+)\*\s*([^^]+)\^2\s*", value)
    try:
        if m:
            return ArmatureRule(pattern, j_rotor=float(m.group(1)), gear_ratio=float(m.group(2)))
        return ArmatureRule(pattern, value=float(value))
    except ValueError:
        raise ConfigError(f"armature rule {spec!r}: {value!r} is not a number", element="option 'armature'") from None


def _coerce(name: str, value: object) -> object:
    if name == "strip" and isinstance(value, str | list | tuple | set | frozenset):
        return parse_strip(value if isinstance(value, str) else [str(v) for v in value])
    if name == "repair_inertia" and (value is None or isinstance(value, str | RepairPolicy)):
        return parse_repair_policy(value)
    if name == "rename" and isinstance(value, list | tuple):
        return tuple(v if isinstance(v, RenameRule) else parse_rename(str(v)) for v in value)
    if name == "armature" and isinstance(value, list | tuple):
        return tuple(v if isinstance(v, ArmatureRule) else parse_armature(str(v)) for v in value)
    return value


def options_from_mapping(values: Mapping[str, object], base: PassOptions | None = None) -> PassOptions:
    """Options from ``{name: value}`` (CLI/config spelling; ``-`` or ``_``), on top of ``base``."""
    changes: dict[str, Any] = {check_option_name(k): _coerce(check_option_name(k), v) for k, v in values.items()}
    return dataclasses.replace(base or PassOptions(), **changes)


def merge_options(base: PassOptions, override: PassOptions) -> PassOptions:
    """``base`` with every field of ``override`` that differs from the default (a preset plus CLI flags)."""
    default = PassOptions()
    changes: dict[str, Any] = {
        f.name: getattr(override, f.name)
        for f in dataclasses.fields(PassOptions)
        if getattr(override, f.name) != getattr(default, f.name)
    }
    return dataclasses.replace(base, **changes)
