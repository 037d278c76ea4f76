"""What the passes changed, link by link: before and after, for the page's repairs panel.

Read from the two robots themselves (the verified source and the compiled IR), not from the
findings' wording, so a repair is shown even when its finding is grouped or silent. Three kinds,
the ones users ask about: a link's mass or inertia changed (repaired, filled from geometry or
merged with a child); visuals or colliders dropped (a missing mesh); links merged away through
fixed joints. Renamed links are followed through the passes' ``renamed`` findings.
"""

from __future__ import annotations

from typing import Any

from robodesc.ir.diagnostics import Finding
from robodesc.ir.geometry import Inertial, Mesh
from robodesc.ir.model import Link, Robot
from robodesc.view.scene import inertia_box, renames

Json = dict[str, Any]


def _inertia_text(inertial: Inertial | None) -> str:
    if inertial is None or inertial.mass is None:
        return "no inertial"
    text = f"mass {inertial.mass:.6g} kg"
    if inertial.origin is not None:
        text += ", com (" + ", ".join(f"{v:.4g}" for v in inertial.origin.xyz) + ")"
    i = inertial.inertia
    if i is not None:
        text += f", ixx iyy izz {i.ixx:.4g} {i.iyy:.4g} {i.izz:.4g}"
        # Products of inertia that are rounding noise (1e-36 after a rotation) are not shown.
        scale = max(abs(i.ixx), abs(i.iyy), abs(i.izz), 1e-300)
        if max(abs(i.ixy), abs(i.ixz), abs(i.iyz)) > 1e-9 * scale:
            text += f", ixy ixz iyz {i.ixy:.3g} {i.ixz:.3g} {i.iyz:.3g}"
    return text


def _same_inertial(a: Inertial | None, b: Inertial | None) -> bool:
    if a is None or b is None:
        return a is b
    pose_a = (a.origin.xyz, a.origin.rpy) if a.origin is not None else None
    pose_b = (b.origin.xyz, b.origin.rpy) if b.origin is not None else None
    tensor_a = a.inertia.as_tuple() if a.inertia is not None else None
    tensor_b = b.inertia.as_tuple() if b.inertia is not None else None
    return a.mass == b.mass and pose_a == pose_b and tensor_a == tensor_b


def _shapes_text(link: Link) -> str:
    def one(geometry: object) -> str:
        return f"mesh {geometry.uri}" if isinstance(geometry, Mesh) else type(geometry).__name__.lower()

    vis = ", ".join(one(v.geometry) for v in link.visuals) or "none"
    col = ", ".join(one(c.geometry) for c in link.collisions) or "none"
    return f"visuals: {vis}; colliders: {col}"


def _merged_into(before: Robot, name: str, kept: set[str]) -> str | None:
    parents = before.parent_joint()
    while name in parents:
        name = parents[name].parent
        if name in kept:
            return name
    return None


def find_repairs(before: Robot, after: Robot, findings: list[Finding]) -> list[Json]:
    """One entry per changed link: ``kind`` (inertia | dropped | merged), ``link`` (its name in
    the compiled robot), ``before``/``after`` texts and, for inertia, both equivalent boxes."""
    renamed = renames(findings)
    now = after.link_map()
    out: list[Json] = []
    merged: dict[str, list[str]] = {}
    kept = {link.name for link in before.links if renamed.get(link.name, link.name) in now}
    for link in before.links:
        name = renamed.get(link.name, link.name)
        new = now.get(name)
        if new is None:
            into = _merged_into(before, link.name, kept)
            if into is not None:
                merged.setdefault(renamed.get(into, into), []).append(link.name)
            continue
        if _shapes_text(link) != _shapes_text(new):
            out.append(
                {
                    "kind": "dropped",
                    "link": name,
                    "before": _shapes_text(link),
                    "after": _shapes_text(new),
                }
            )
    # Inertia after merges too: a merged parent carries its children's mass, which is a repair of
    # its own worth seeing (the body Isaac simulates).
    for link in before.links:
        name = renamed.get(link.name, link.name)
        new = now.get(name)
        if new is None or _same_inertial(link.inertial, new.inertial):
            continue
        out.append(
            {
                "kind": "inertia",
                "link": name,
                "before": _inertia_text(link.inertial),
                "after": _inertia_text(new.inertial),
                "before_box": inertia_box(link.inertial),
                "after_box": inertia_box(new.inertial),
                "merged": merged.get(name, []),
            }
        )
    for into, names in merged.items():
        out.append(
            {
                "kind": "merged",
                "link": into,
                "before": f"{len(names)} link(s) of their own: " + ", ".join(names),
                "after": f"part of {into!r} (kept as fixed frames)",
            }
        )
    order = {"inertia": 0, "dropped": 1, "merged": 2}
    out.sort(key=lambda r: (order[r["kind"]], r["link"]))
    return out
