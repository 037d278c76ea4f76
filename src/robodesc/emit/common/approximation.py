"""How mesh colliders are approximated: one mode for every link, or ``{regex: mode}`` rules by link
name on top of it (``--collision-approximation convexHull --collision-approximation 'foot.*=convexDecomposition'``).
"""

from __future__ import annotations

from collections.abc import Mapping

from robodesc.emit.common.flags import flag
from robodesc.ir.diagnostics import ConfigError
from robodesc.ir.model import JointType, Robot
from robodesc.ir.rules import compile_table, first_match

# UsdPhysics' tokens, plus PhysX's "sdf" (a signed distance field of the triangle mesh). "none" is
# the triangle mesh itself.
APPROXIMATIONS = ("convexHull", "convexDecomposition", "boundingCube", "boundingSphere", "none", "sdf")
DEFAULT = "convexHull"
# The exact triangles: what PhysX takes only on static colliders (sdf also on GPU-simulated bodies).
TRIANGLE_MODES = ("none", "sdf")

FLAG = flag(
    f"how mesh colliders are approximated: {', '.join(APPROXIMATIONS)} (default convexHull; SDF: none, "
    "the mesh as given), or LINK_REGEX=MODE rules on top of it (repeatable, first match wins)",
    kind="rules",
    rule_value=lambda text: parse_mode(text),
    metavar="MODE|REGEX=MODE",
)

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


def asked(spec: Approximation) -> set[str]:
    """Every mode the option names."""
    return {spec} if isinstance(spec, str) else set(spec.values())


def static_links(robot: Robot, fix_base: bool) -> set[str]:
    """Links that never move: a root called ``world`` (URDF's name for the ground), or the root of a
    fixed-base robot, and every link welded to one of those by fixed joints."""
    try:
        root = robot.root
    except ValueError:
        return set()
    if root.name != "world" and not fix_base:
        return set()
    children = robot.child_joints()
    out = {root.name}
    todo = [root.name]
    while todo:
        for joint in children.get(todo.pop(), []):
            if joint.type is JointType.FIXED and joint.child not in out:
                out.add(joint.child)
                todo.append(joint.child)
    return out


# Snake-case spellings the command line accepts for UsdPhysics' tokens.
ALIASES = {
    "convex_hull": "convexHull",
    "convex_decomposition": "convexDecomposition",
    "bounding_cube": "boundingCube",
    "bounding_sphere": "boundingSphere",
}


def parse_mode(text: str) -> str:
    text = ALIASES.get(text, text)
    if text not in APPROXIMATIONS:
        raise ConfigError(f"--collision-approximation {text!r}: one of {', '.join(APPROXIMATIONS)}")
    return text
