"""How mesh colliders are approximated: one mode for every link, or ``{regex: mode}`` rules by link
name on top of it (``--collision-approximation convexHull --collision-approximation 'foot.*=convexDecomposition'``).
"""

from __future__ import annotations

from collections.abc import Mapping

from robodesc.ir.diagnostics import ConfigError
from robodesc.ir.rules import compile_table, first_match

APPROXIMATIONS = ("convexHull", "convexDecomposition", "boundingCube", "boundingSphere", "none")
DEFAULT = "convexHull"

# One mode, or ordered rules (first full match of the link name wins; ".*" is the fallback).
Approximation = str | Mapping[str, str]


def mode_for(spec: Approximation, link: str) -> str:
    """The mode for ``link``'s mesh colliders."""
    if isinstance(spec, str):
        return spec
    found = first_match(compile_table(spec, "collision_approximation"), link)
    return found if found is not None else DEFAULT


def global_mode(spec: Approximation) -> str:
    """The mode that applies to links no rule names (importer settings have one value)."""
    return spec if isinstance(spec, str) else spec.get(".*", DEFAULT)


def check(spec: Approximation, allowed: tuple[str, ...] = APPROXIMATIONS) -> None:
    modes = [spec] if isinstance(spec, str) else list(spec.values())
    compile_table({} if isinstance(spec, str) else spec, "collision_approximation")
    for mode in modes:
        if mode not in allowed:
            raise ConfigError(f"collision_approximation must be one of {', '.join(allowed)}; got {mode!r}")


def parse_mode(text: str) -> str:
    if text not in APPROXIMATIONS:
        raise ConfigError(f"--collision-approximation {text!r}: one of {', '.join(APPROXIMATIONS)}")
    return text
