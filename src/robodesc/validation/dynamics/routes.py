"""Two stages of one robot in one engine, compared scenario by scenario: does the second behave as
the first within the documented thresholds (:class:`~.scenarios.Thresholds`, docs/dynamics.md)?

The Isaac Sim 6 route (docs/isaac.md) uses it: robodesc's own USD is the reference, and the
importer's USD, with robodesc's physics layer over it or with ``importer_settings.json`` alone, is
run through the same hold, drop and slide. The engine and the scenario setup are the same on both
sides, so the engine-to-engine thresholds are generous here; they are the ones
``validate --dynamics`` already documents, so "the same behaviour" means one thing.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from robodesc.validation.dynamics.result import Run
from robodesc.validation.dynamics.scenarios import Thresholds


def behaviour_differences(reference: Sequence[Run], other: Sequence[Run], th: Thresholds | None = None) -> list[str]:
    """Each way ``other``'s runs differ from ``reference``'s (matched by engine and scenario) beyond
    ``th``, as a sentence naming the scenario, the joint or quantity and both values; empty when
    they behave alike."""
    th = th or Thresholds()
    theirs = {(r.engine, r.scenario): r for r in other}
    out: list[str] = []
    for ours in reference:
        key = (ours.engine, ours.scenario)
        where = f"{ours.engine} {ours.scenario}"
        got = theirs.get(key)
        if got is None:
            out.append(f"{where}: not run")
            continue
        if ours.ok != got.ok:
            out.append(f"{where}: {'failed: ' + got.error if ours.ok else 'ran'} (reference {ours.error or 'ran'})")
            continue
        if not ours.ok:
            continue
        # As validate --dynamics judges engines: the hold by each joint's end, the drop by where
        # the base settles (its joints follow the landing, which the drop's thresholds allow for).
        if ours.scenario == "hold-fixed":
            out.extend(_final_pose(where, ours, got, th))
        if ours.scenario == "drop":
            out.extend(_drop(where, ours, got, th))
        if ours.scenario == "slide":
            out.extend(_slide(where, ours, got, th))
    return out


def _final_pose(where: str, ours: Run, got: Run, th: Thresholds) -> list[str]:
    out = []
    for joint, q in sorted(ours.final_q.items()):
        theirs = got.final_q.get(joint)
        if theirs is None:
            out.append(f"{where}: joint {joint!r} not driven")
        elif abs(theirs - q) > th.hold_agree:
            out.append(
                f"{where}: joint {joint!r} ends at {theirs:.4f} (reference {q:.4f}, agree within {th.hold_agree})"
            )
    holds = [r.drift is not None and r.drift <= th.hold_drift for r in (ours, got)]
    if holds[0] != holds[1]:
        out.append(f"{where}: drift {_n(got.drift)} (reference {_n(ours.drift)}; holds within {th.hold_drift})")
    return out


def _drop(where: str, ours: Run, got: Run, th: Thresholds) -> list[str]:
    out = []
    if _apart(ours.height, got.height, th.drop_height_agree):
        out.append(
            f"{where}: height {_n(got.height)} m (reference {_n(ours.height)}, agree within {th.drop_height_agree})"
        )
    if _apart(ours.tilt, got.tilt, th.drop_tilt_agree):
        tilt = [None if t is None else math.degrees(t) for t in (got.tilt, ours.tilt)]
        out.append(f"{where}: tilt {_n(tilt[0])}° (reference {_n(tilt[1])}°)")
    if ours.mass is not None and got.mass is not None and not math.isclose(got.mass, ours.mass, rel_tol=th.mass_rel):
        out.append(f"{where}: mass {got.mass:.4f} kg (reference {ours.mass:.4f})")
    return out


def _slide(where: str, ours: Run, got: Run, th: Thresholds) -> list[str]:
    out = []
    if ours.mu is not None and (got.mu is None or not math.isclose(got.mu, ours.mu, rel_tol=th.friction_rel)):
        out.append(f"{where}: friction {_n(got.mu)} (reference {_n(ours.mu)})")
    for label, attr in (("sticks", "stick"), ("slides", "slide")):
        moved = [getattr(r, attr) for r in (ours, got)]
        if None in moved:
            continue
        outcome = [(m <= th.stick_max) if attr == "stick" else (m >= th.slide_min) for m in moved]
        if outcome[0] != outcome[1]:
            out.append(f"{where}: on the '{label}' plane the block moves {moved[1]:.4f} m (reference {moved[0]:.4f})")
    return out


def _apart(a: float | None, b: float | None, tolerance: float) -> bool:
    if a is None or b is None:
        return a is not b
    return abs(a - b) > tolerance


def _n(value: float | None) -> str:
    return "-" if value is None else f"{value:.4f}"
