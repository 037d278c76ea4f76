"""What the IR cannot hold, named: one warning per element, with its ``file:line`` and what the
outputs lose. Nothing of the model is dropped without one (docs/mjcf-input.md lists them)."""

from __future__ import annotations

from robodesc.frontends.mjcf.context import Reading
from robodesc.frontends.mjcf.source import tag

_ALL = "URDF, SDF, USD and MJCF outputs leave it out"
# Elements (by tag and, for a section's children, their section) and what each output loses.
_LOST = {
    ("tendon", "fixed"): f"a fixed tendon (a linear coupling of joints, and what acts on it) has no IR form: {_ALL}",
    ("tendon", "spatial"): f"a spatial tendon (a cable through sites) has no IR form: {_ALL}",
}
# Sections read by other modules or with nothing robot-specific, that need no warning.
_OPTIONS = {"option", "size", "visual", "statistic", "custom"}


def warn_unheld(r: Reading) -> None:
    said_options: set[str] = set()
    for el in r.source.root.iter():
        if not isinstance(el.tag, str):
            continue
        parent = el.getparent()
        key = (tag(parent) if parent is not None else "", tag(el))
        lost = _LOST.get(key)
        if lost is not None:
            label = el.get("name") or ""
            r.warn("mjcf-not-held", lost, f"{key[1]}{' ' + repr(label) if label else ''}", r.source.loc(el))
        elif key[0] == "mujoco" and key[1] in _OPTIONS and key[1] not in said_options and len(el.attrib) + len(el):
            said_options.add(key[1])
            r.info(
                "mjcf-simulation-options",
                f"<{key[1]}> sets MuJoCo's simulation (timestep, solver, cone ...), not the robot: the MJCF output "
                "writes robodesc's own (--mjcf-integrator), other targets their engines' defaults",
                key[1],
                r.source.loc(el),
            )
