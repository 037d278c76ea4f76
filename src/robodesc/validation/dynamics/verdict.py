"""From runs to verdicts: engines against each other, each output against its source.

Exit 1 (a FAIL check) only where an output contradicts its source:
- an output run in an engine diverges from the source run in the same engine (same solver, same
  gains: any difference is in the file);
- a friction an engine reads from an output is not the source's (when the source gives one), or
  a block with it does not stick and slide as tan(angle) against the source's mu says;
- the drives of an output cannot hold the pose (fixed base) while the same gains hold it in another
  engine;
- an engine reads a total mass from an output that is not the source's (a row of its own, ``mass``:
  a lost or invented mass is named as such, never taken for a difference of contact models).
Everything else that differs between engines (drop height and tilt, a hold both engines fail) is a
WARN: engines solve contact and stiff drives differently, and the table says how. A drive that reaches
its effort limit in the hold or the drop is a WARN naming the engines where it does and does not: the
symptom of a robot that stands in one simulator and sags in another.
"""

from __future__ import annotations

import math
from itertools import combinations

from robodesc.validation.dynamics.result import READS_DIFFERENTLY, DynamicsReport, Run
from robodesc.validation.dynamics.scenarios import Setup, Thresholds
from robodesc.validation.report import Status

SOURCE = "source"
# A joint position (rad or m) or root height (m) beyond this is no motion a scenario can produce: the
# engine's state has blown up. A free wheel spinning at 100 rad/s for the 4 s drop turns 400 rad.
ABSURD = 1e4


def judge(report: DynamicsReport, setup: Setup, th: Thresholds) -> None:
    for r in report.runs:
        blown = blown_up(r)
        if r.ok and blown:
            # A run whose state is non-finite or absurd failed in its engine: its numbers say nothing
            # about the file's behaviour, so it is a ``run`` row, never a disagreement between engines.
            r.ok, r.error = False, blown
    outputs = [r for r in report.runs if r.file != SOURCE and r.ok]
    # An engine that refuses the source too (a non-physical inertia Drake will not factor): the
    # output carries the source's defect, as the structural checks report it, a warning.
    refused = {r.engine for r in report.runs if r.file == SOURCE and not r.ok}
    refused |= {c.element.split("/")[0] for c in report.checks if c.name == "load" and c.element.endswith("/" + SOURCE)}
    for c in report.checks:
        # An output the engine refuses as it refuses the source (an empty OBJ): the source's defect.
        # The output is run before the source, so its row is judged here, with both known.
        if c.name == "load" and c.status is Status.FAIL and c.element.split("/")[0] in refused:
            c.status = Status.WARN
            c.message += f" (the source fails in {c.element.split('/')[0]} too)"
    for r in report.runs:
        if not r.ok:
            # An engine reading what the source says its own way (READS_DIFFERENTLY) is not robodesc's fault.
            own = r.file != SOURCE and r.engine not in refused and not r.error.startswith(READS_DIFFERENTLY)
            why = "" if own else f" (the source fails in {r.engine} too)" if r.file != SOURCE else ""
            report.add("run", Status.FAIL if own else Status.WARN, _label(r), r.error + why)
    _against_source(report, setup, th)
    _masses(report, setup, th)
    _hold(report, [r for r in outputs if r.scenario == "hold-fixed"], th)
    _drop(report, [r for r in outputs if r.scenario == "drop"], th)
    _slide(report, [r for r in outputs if r.scenario == "slide"], setup, th)
    for scenario in ("hold-fixed", "drop"):
        _saturation(report, [r for r in outputs if r.scenario == scenario], th)
    _stand(report, [r for r in outputs if r.scenario == "stand"], th)


def blown_up(r: Run) -> str:
    """Why the run's state is non-finite or absurd (the first sample that is), or "" when it is not."""
    samples: list[tuple[float | None, dict[str, float]]] = [*r.trajectory, (None, r.final_q)]
    for t, q in samples:
        for name, value in q.items():
            if not math.isfinite(value) or abs(value) > ABSURD:
                when = "at the end" if t is None else f"at {t:.3g} s"
                return f"the state blew up: joint {name!r} reached {value:.3g} {when} (the engine's run failed)"
    for what, measured in (("drift", r.drift), ("root height", r.height)):
        if measured is not None and (not math.isfinite(measured) or abs(measured) > ABSURD):
            return f"the state blew up: {what} {measured:.3g} (the engine's run failed)"
    return ""


def _label(r: Run) -> str:
    return f"{r.engine}/{r.file}/{r.scenario}"


def _against_source(report: DynamicsReport, setup: Setup, th: Thresholds) -> None:
    sources = {(r.engine, r.scenario): r for r in report.runs if r.file == SOURCE and r.ok}
    coupled = set(setup.mimics) | set(setup.mimics.values())
    for r in report.runs:
        src = sources.get((r.engine, r.scenario))
        if r.file == SOURCE or src is None or not r.ok or not r.trajectory:
            continue
        worst, where, joint = 0.0, "", ""
        for (t, qa), (_, qb) in zip(src.trajectory, r.trajectory, strict=False):
            for name, value in qa.items():
                if name in qb and abs(value - qb[name]) > worst:
                    worst, where, joint = abs(value - qb[name]), f"{name} at {t:.2f} s", name
        status = Status.PASS if worst <= th.source_traj else Status.FAIL
        why = ""
        if status is Status.FAIL and (joint in coupled or (coupled and r.file == "sdf")):
            # SDF before 1.11 has no <mimic>: the follower moves freely and its inertia loads the
            # chain differently (talos' wrist, 1.4e-3 rad). The compile warned (sdf-mimic-dropped).
            status = Status.WARN
            why = "; the output does not couple the mimic joints as the source does (the compile warned)"
        report.add(
            f"source:{r.scenario}",
            status,
            f"{r.engine}/{r.file}",
            f"joint trajectory against the source in {r.engine}: largest difference {worst:.3g}"
            + (f" ({where})" if where else "")
            + why,
            error=worst,
            tolerance=th.source_traj,
        )


def _hold(report: DynamicsReport, runs: list[Run], th: Thresholds) -> None:
    holds = {id(r): (r.drift or 0.0) <= th.hold_drift for r in runs}
    # Engines whose own reading of the source was run and matched by the output: there, a sag is
    # the source's behaviour in that engine, not the output's fault.
    as_source = {
        c.element.split("/")[0] for c in report.checks if c.name == "source:hold-fixed" and c.status is Status.PASS
    }
    for a, b in combinations(runs, 2):
        common = [n for n in a.final_q if n in b.final_q]
        if not common:
            continue  # nothing to compare: the run without joints is a failing row of its own
        diff = max((abs(a.final_q[n] - b.final_q[n]) for n in common), default=0.0)
        agree = diff <= th.hold_agree
        who = f"{a.engine}/{a.file} vs {b.engine}/{b.file}"
        if agree:
            report.add(
                "agree:hold-fixed",
                Status.PASS,
                who,
                f"final joints within {diff:.3g}",
                error=diff,
                tolerance=th.hold_agree,
            )
            continue
        # One holds, the other does not: the same gains hold the pose elsewhere, so the failing
        # output's drives (units, gains, limits) are not the source's.
        lost = [r for r in (a, b) if not holds[id(r)]]
        status = Status.FAIL if len(lost) == 1 and lost[0].engine not in as_source else Status.WARN
        if len(lost) != 1:
            why = "both drift; they settle apart (stiff drives and solvers differ)"
        else:
            why = f"{lost[0].engine}/{lost[0].file} drifts {lost[0].drift:.3g} at {lost[0].worst_joint!r} where the same gains hold"
            if lost[0].engine in as_source:
                why += f"; the source itself does so in {lost[0].engine}: the engines differ, not the file"
        report.add(
            "agree:hold-fixed",
            status,
            who,
            f"final joints differ by {diff:.3g}: {why}",
            error=diff,
            tolerance=th.hold_agree,
        )


def _mass_off(mass: float | None, want: float | None, th: Thresholds) -> bool:
    return mass is not None and want is not None and abs(mass - want) > th.mass_rel * max(abs(want), 1e-9)


def _masses(report: DynamicsReport, setup: Setup, th: Thresholds) -> None:
    """Each engine's total mass against the source's: FAIL for an output, unless the engine reads
    the source itself just as far off (then it is the engine's reading, a warning)."""
    if setup.mass is None:
        return
    seen: set[tuple[str, str]] = set()
    source_off = {r.engine for r in report.runs if r.file == SOURCE and r.ok and _mass_off(r.mass, setup.mass, th)}
    for r in report.runs:
        if not r.ok or r.mass is None or (r.engine, r.file) in seen:
            continue
        seen.add((r.engine, r.file))
        rel = abs(r.mass - setup.mass) / max(abs(setup.mass), 1e-9)
        if not _mass_off(r.mass, setup.mass, th):
            status = Status.PASS
        else:
            status = Status.WARN if r.file == SOURCE or r.engine in source_off else Status.FAIL
        report.add(
            "mass",
            status,
            f"{r.engine}/{r.file}",
            f"reads {r.mass:.6g} kg; the source's links weigh {setup.mass:.6g} kg",
            error=rel,
            tolerance=th.mass_rel,
        )


def _drop(report: DynamicsReport, runs: list[Run], th: Thresholds) -> None:
    for a, b in combinations(runs, 2):
        dh = abs((a.height or 0.0) - (b.height or 0.0))
        dt = abs((a.tilt or 0.0) - (b.tilt or 0.0))
        ok = dh <= th.drop_height_agree and dt <= th.drop_tilt_agree
        if ok:
            why = ""
        elif a.mass is not None and b.mass is not None and _mass_off(a.mass, b.mass, th):
            why = f" (they read different masses, {a.mass:.4g} and {b.mass:.4g} kg: see the mass rows)"
        else:
            why = " (contact models differ; a fall from a pose the robot cannot keep is chaotic)"
        report.add(
            "agree:drop",
            Status.PASS if ok else Status.WARN,
            f"{a.engine}/{a.file} vs {b.engine}/{b.file}",
            f"settled heights differ by {dh:.3g} m, tilts by {math.degrees(dt):.3g} deg" + why,
            error=max(dh / th.drop_height_agree, dt / th.drop_tilt_agree),
            tolerance=1.0,
        )


def _saturation(report: DynamicsReport, runs: list[Run], th: Thresholds) -> None:
    """A WARN per run whose drives reach their effort limit, naming the runs where they do not."""
    for r in runs:
        worst = r.worst_saturation()
        if worst is None or worst[1] < th.saturated:
            continue
        joint, share = worst
        saturated = sorted(n for n, v in r.saturation.items() if v >= th.saturated)
        within = [
            f"{o.engine}/{o.file} {o.saturation.get(joint, 0.0):.2f}"
            for o in runs
            if o is not r and joint in o.saturation
        ]
        report.add(
            "saturation",
            Status.WARN,
            f"{_label(r)}",
            f"{len(saturated)} drive(s) reach their effort limit ({', '.join(saturated[:6])}"
            + (", ..." if len(saturated) > 6 else "")
            + f"); {joint!r} peaks at {r.peak_effort[joint]:.4g}, {share:.2f} of its limit"
            + (f"; elsewhere: {', '.join(within)}" if within else ""),
            error=share,
            tolerance=th.saturated,
        )


# Files an engine reads as URDF (the output, and the source it is compared with).
URDF_FILES = frozenset({"urdf", "source"})


def _slide(report: DynamicsReport, runs: list[Run], setup: Setup, th: Thresholds) -> None:
    for r in runs:
        src = setup.friction
        if r.mu is not None and src is not None and abs(r.mu - src) > th.friction_rel * max(abs(src), 1e-9):
            if r.file in URDF_FILES:
                # URDF has no friction element: MuJoCo's and Drake's URDF parsers read no <gazebo>
                # block, whatever robodesc writes (the other formats carry it: docs/contact.md).
                report.add(
                    "friction",
                    Status.WARN,
                    f"{r.engine}/{r.file}",
                    f"reads mu {r.mu:.4g} (its default): URDF cannot give it the source's {src:.4g}",
                )
            else:
                report.add(
                    "friction", Status.FAIL, f"{r.engine}/{r.file}", f"reads mu {r.mu:.4g}; the source gives {src:.4g}"
                )
        sticks = (r.stick or 0.0) <= th.stick_max
        slides = (r.slide or 0.0) >= th.slide_min
        status = Status.PASS if sticks and slides else Status.FAIL
        basis = "the source's" if src is not None else f"{r.engine}'s default (the source gives none)"
        report.add(
            "slide",
            status,
            f"{r.engine}/{r.file}",
            f"mu {r.mu:.3g} ({basis}): moved {r.stick:.3g} m at tan = 0.7 mu, {r.slide:.3g} m at 1.3 mu",
        )
    for a, b in combinations(runs, 2):
        same = a.mu is not None and b.mu is not None and abs(a.mu - b.mu) <= th.friction_rel * max(a.mu, b.mu, 1e-9)
        report.add(
            "agree:slide",
            Status.PASS if same else Status.WARN,
            f"{a.engine}/{a.file} vs {b.engine}/{b.file}",
            f"mu {a.mu} and {b.mu}" + ("" if same else ": the engines' defaults differ where the source gives none"),
        )


# The feet's contact sensors read the robot's weight within this (relative) when it stands.
CONTACT_REL = 0.05
# A sole this far from the ground under it at the end is not standing on it.
SOLE_GAP = 0.02  # m


def _stand(report: DynamicsReport, runs: list[Run], th: Thresholds) -> None:
    """The stand on a world: upright on its soles in each engine, the engines agreeing on the
    height over the ground and the tilt, and the contact sensors reading the weight. All WARN: the
    terrain and each engine's contact model decide them, not what the output says of the robot."""
    for r in runs:
        tilt = math.degrees(r.tilt or 0.0)
        upright = r.tilt is not None and r.tilt <= th.upright_tilt
        on_ground = r.sole_gap is not None and r.sole_gap <= SOLE_GAP
        heights = ", ".join(f"{k} {v:.3f}" for k, v in r.feet_height.items())
        message = f"tilt {tilt:.1f}°, slip {_m(r.slip)}, soles within {_m(r.sole_gap)} of the ground; over each foot {heights}"
        report.add("stand", Status.PASS if upright and on_ground else Status.WARN, _label(r), message)
        if r.contact_sum is not None and r.weight:
            off = abs(r.contact_sum - r.weight) / r.weight
            report.add(
                "contact",
                Status.PASS if off <= CONTACT_REL else Status.WARN,
                _label(r),
                f"the feet's contact sensors sum to {r.contact_sum:.2f} N against the weight {r.weight:.2f} N ({off:.1%})",
                error=off,
                tolerance=CONTACT_REL,
            )
    for a, b in combinations(runs, 2):
        if not (a.feet_height and b.feet_height) or a.tilt is None or b.tilt is None:
            continue
        ha = sum(a.feet_height.values()) / len(a.feet_height)
        hb = sum(b.feet_height.values()) / len(b.feet_height)
        dh, dt = abs(ha - hb), abs(a.tilt - b.tilt)
        agree = dh <= th.drop_height_agree and dt <= th.drop_tilt_agree
        report.add(
            "agree:stand",
            Status.PASS if agree else Status.WARN,
            f"{_label(a)} vs {_label(b)}",
            f"height over the ground {ha:.3f} / {hb:.3f} m, tilt {math.degrees(a.tilt):.1f}° / {math.degrees(b.tilt):.1f}°"
            + ("" if agree else " (contact models differ, or one engine reads the terrain differently)"),
            error=dh,
            tolerance=th.drop_height_agree,
        )


def _m(value: float | None) -> str:
    return "-" if value is None else f"{value:.3f} m"
