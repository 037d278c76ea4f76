"""Command-line flags declared where the option lives: on the options dataclass's field.

A target's new option is one field::

    actuator: str = field(default="position", metadata=flag("actuator kind", choices=ACTUATORS, name="--mjcf-actuator"))

The CLI builds its flags from these declarations (the flag defaults to ``--field-name``); the API
takes the field by name. Several targets may declare the same field (``stiffness`` for USD and
MJCF): the CLI makes one flag of it and hands the value to whichever target runs.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

# How a flag's text becomes the option's value.
#  "value": as argparse gives it (with ``type``/``choices``);
#  "switch": a boolean, --x / --no-x;
#  "on": can only be switched on (--x): True, or ``const``;
#  "rules": one number for every joint, or repeated REGEX=NUMBER rules (first full match wins);
#  "vector": comma-separated numbers (X,Y,Z).
KINDS = ("value", "switch", "on", "rules", "vector")


@dataclass(frozen=True, slots=True)
class Flag:
    help: str
    name: str | None = None  # default: "--" + the field name with '-' for '_'
    kind: str = "value"
    type: Callable[[str], Any] | None = None
    choices: tuple[str, ...] | None = None
    metavar: str | None = None
    # For "rules": a bare number means this one rule (``{".*": value}``) rather than a number.
    rules_only: bool = False
    # For "rules": what a rule's value is (default: a number), e.g. one of ``choices``.
    rule_value: Callable[[str], Any] | None = None
    # For "vector": how many numbers.
    size: int = 3
    # For "on": the value the flag sets (default True), e.g. an enum value: --gazebo-classic sets
    # flavour to "classic".
    const: Any = None


def flag(help: str, **kwargs: Any) -> dict[str, Flag]:
    """Field metadata that declares the field's command-line flag."""
    spec = Flag(help=help, **kwargs)
    if spec.kind not in KINDS:
        raise ValueError(f"flag kind {spec.kind!r}: one of {KINDS}")
    return {"flag": spec}


def flag_name(field: dataclasses.Field[Any]) -> str:
    spec: Flag = field.metadata["flag"]
    return spec.name or "--" + field.name.replace("_", "-")


def declared_flags(cls: type[Any]) -> Iterator[tuple[dataclasses.Field[Any], Flag]]:
    """The fields of an options dataclass that declare a flag, in declaration order."""
    for f in dataclasses.fields(cls):
        spec = f.metadata.get("flag")
        if isinstance(spec, Flag):
            yield f, spec


# ---- options several targets take: one declaration, so the flag and its help are the same --------
FIX_BASE = flag(
    "weld the root link to the world, or float it with --no-fix-base (default, the same in every target: a "
    "robot on three or more legs floats so it stands on them, anything else is welded; a composition's "
    "own choice wins over the legs; the summary line says which applied and why)",
    kind="switch",
)
DRIVE_TYPE = flag("joint drive type (default force)", choices=("force", "acceleration"))
TARGET_TYPE = flag(
    "drive target (default position; none = passive joints, gains 0)", choices=("none", "position", "velocity")
)
STIFFNESS = flag(
    "drive stiffness in SI (N·m/rad, N/m), one number or rules (repeatable, first match wins); each target "
    "writes it in its own units (USD per degree)",
    kind="rules",
)
DAMPING = flag("drive damping in SI (N·m·s/rad, N·s/m), like --stiffness", kind="rules")
SELF_COLLISION = flag("collide the robot's links with each other", kind="on")
INIT_POS = flag("spawn position of the base (m)", kind="vector", metavar="X,Y,Z")
INIT_JOINT_POS = flag(
    "initial joint positions (rad or m; REGEX=VALUE, repeatable, first match wins)",
    kind="rules",
    rules_only=True,
    metavar="REGEX=VALUE",
)
FRICTION_COMBINE = flag(
    "how two colliders' friction coefficients combine: average (PhysX's default), min (ODE's, so "
    "Gazebo's), multiply, max; docs/contact.md",
    choices=("average", "min", "multiply", "max"),
)
DEFAULT_FRICTION = flag(
    "friction coefficient of colliders the source gives none for, where a physics material is written "
    "(default 0.5, PhysX's default material; --preset gazebo_parity: 1, ODE's)",
    type=float,
    metavar="MU",
)
