"""Valid, unique SDF names for the frames of one model.

SDF (1.8 and later) puts links, joints and frames of a model in one namespace, reserves ``world``,
``__model__`` and names wrapped in ``__``, and uses ``::`` as its scope separator. URDF allows a link
and a joint to share a name and allows all of these. Names are fixed deterministically (links keep
theirs first, then joints, loop joints and frames, in IR order) and every change is a finding.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from robodesc.ir.diagnostics import Findings, SourceLoc

STAGE = "emit:sdf"

_SUFFIX = {
    "model": "_model",
    "link": "_link",
    "joint": "_joint",
    "loop_joint": "_joint",
    "fix_base": "_joint",
    "frame": "_frame",
    "visual": "_visual",
    "collision": "_collision",
    "sensor": "_sensor",
}


def reserved_reason(name: str) -> str | None:
    if name == "":
        return "an empty name"
    if name in ("world", "__model__"):
        return f"{name!r} is reserved"
    if name.startswith("__") or name.endswith("__"):
        return "names starting or ending with '__' are reserved"
    if "::" in name:
        return "'::' is the scope separator"
    return None


def _clean(name: str, kind: str) -> str:
    out = name.replace("::", "_")
    if out.startswith("__") or out.endswith("__"):
        out = out.strip("_")
    if out in ("", "world", "__model__"):
        out = f"{out or 'unnamed'}{_SUFFIX[kind]}"
    return out


@dataclass(slots=True)
class Namespace:
    """One SDF scope: names handed out so far, and what each IR name became."""

    used: set[str] = field(default_factory=set)
    # kind -> IR name -> SDF name (first occurrence wins when the IR repeats a name)
    by_kind: dict[str, dict[str, str]] = field(default_factory=dict)

    def claim(
        self,
        kind: str,
        name: str,
        findings: Findings,
        *,
        loc: SourceLoc | None = None,
        label: str | None = None,
    ) -> str:
        reason = reserved_reason(name)
        candidate = _clean(name, kind) if reason else name
        if candidate in self.used:
            reason = reason or "SDF needs unique names among a model's links, joints and frames"
            base = candidate + _SUFFIX[kind] if not candidate.endswith(_SUFFIX[kind]) else candidate
            candidate = base
            n = 1
            while candidate in self.used:
                n += 1
                candidate = f"{base}_{n}"
        self.used.add(candidate)
        self.by_kind.setdefault(kind, {}).setdefault(name, candidate)
        if candidate != name:
            findings.warn(
                "sdf-rename",
                f"renamed to {candidate!r}: {reason}",
                element=f"{label or kind} {name!r}",
                loc=loc,
                stage=STAGE,
            )
        return candidate

    def get(self, kind: str, name: str) -> str:
        return self.by_kind.get(kind, {}).get(name, name)
