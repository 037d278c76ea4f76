"""Quad-SDK's Spirit and Go2 from their xacro, through the behaviour check's drop and slide
(``robodesc validate --dynamics``), with and without ``--preset gazebo_parity`` (issues 25, 28).

    python benchmarks/contact_drop.py [--robot spirit|go2 ...] [--json out.json] [--md out.md]

Engines: MuJoCo reading robodesc's MJCF, Drake reading its SDF, Newton (``SolverMuJoCo``, CPU)
reading its USD; each file compiled from the xacro with the same options (the checked target is
MJCF, the other two are compiled beside it). Each robot stands in Quad-SDK's stand pose, driven by
the same SI gains (100 / 2) in every engine:

- drop: dropped from 5 cm above its standing height onto a plane of its feet's friction, 1 s: the
  base height and tilt at the end, the time after which the height stays within 1 mm of its end
  (settle), and the worst joint's sag from the pose.
- slide: a 1 kg block of the friction the engine read from the robot's feet, on a plane tilted to
  tan = 0.7 mu (it must stick) and 1.3 mu (it must slide), 1 s each; the distance on the second
  gives the friction the engine applied: mu_applied = tan(theta) - 2 d / (g cos(theta) t^2).

Pairwise agreement for the drop: within 2 cm and 2 degrees (the issue's thresholds; the check's own
WARN is at 3 cm and 10 degrees). Newton runs in the consumer tier's venv (tests/consumers/run.sh
builds it). Results: benchmarks/results/contact_drop.md and .json.
"""

from __future__ import annotations

import argparse
import itertools
import math
import os
import sys
import time
from typing import Any

from results_io import publish

import robodesc

SHARED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "corpus", "quadsdk")
ROBOTS = {
    "spirit": (
        os.path.join(SHARED, "spirit_description/models/spirit/urdf/spirit.urdf.xacro"),
        {"0|2|4|6": 0.76, "1|3|5|7": 1.52},
    ),
    # Quad-SDK's Go2 names its joints as Spirit does (hip 0/2/4/6, knee 1/3/5/7; abduction 8-11).
    "go2": (
        os.path.join(SHARED, "go2_description/models/go2/urdf/go2.urdf.xacro"),
        {"0|2|4|6": 0.8, "1|3|5|7": -1.5},
    ),
}
ENGINES = ("mujoco", "drake", "newton")
PRESETS = (None, "gazebo_parity")
HEIGHT_AGREE = 0.02  # m: the issue's threshold
TILT_AGREE = 2.0  # degrees
G = 9.81


def applied_mu(mu: float, distance: float, duration: float) -> float:
    """The friction that gives a block starting at rest on tan(theta) = 1.3 mu this distance in
    ``duration``: d = (g sin - mu' g cos) t^2 / 2."""
    theta = math.atan(1.3 * mu)
    return math.tan(theta) - 2.0 * distance / (G * math.cos(theta) * duration**2)


def run(robot: str, preset: str | None) -> dict[str, Any]:
    path, pose = ROBOTS[robot]
    options: dict[str, Any] = {"fix_base": False, "stiffness": 100.0, "damping": 2.0}
    if preset:
        options["preset"] = preset
    started = time.perf_counter()
    result = robodesc.check(path, "mjcf", dynamics={"engines": ENGINES, "pose": pose}, **options)
    dyn = result.dynamics
    assert dyn is not None
    setup = dyn.info.get("setup", {})
    out: dict[str, Any] = {
        "robot": robot,
        "preset": preset or "-",
        "ok": dyn.ok,
        "seconds": round(time.perf_counter() - started, 1),
        "source_mu": setup.get("friction"),
        "feet": setup.get("feet"),
        "engines": {},
        "checks": [c.as_dict() for c in dyn.checks if c.status.value != "pass"],
    }
    for r in dyn.runs:
        if r.file == "source":
            continue
        row = out["engines"].setdefault(r.engine, {"file": r.file})
        if r.scenario == "drop":
            row["drop"] = {
                "ok": r.ok,
                "error": r.error,
                "height_m": r.height,
                "tilt_deg": None if r.tilt is None else math.degrees(r.tilt),
                "settle_s": r.settle,
                "sag_rad": r.drift,
                "sag_joint": r.worst_joint,
                "floor_mu": r.mu,
            }
        elif r.scenario == "slide":
            row["slide"] = {
                "ok": r.ok,
                "error": r.error,
                "mu": r.mu,
                "stick_m": r.stick,
                "slide_m": r.slide,
                "applied_mu": None if r.mu is None or r.slide is None else applied_mu(r.mu, r.slide, 1.0),
            }
    pairs = []
    for a, b in itertools.combinations([e for e in ENGINES if e in out["engines"]], 2):
        da, db = out["engines"][a].get("drop") or {}, out["engines"][b].get("drop") or {}
        if da.get("height_m") is None or db.get("height_m") is None:
            continue
        dh = abs(da["height_m"] - db["height_m"])
        dt = abs(da["tilt_deg"] - db["tilt_deg"])
        pairs.append(
            {"pair": f"{a}/{b}", "height_m": dh, "tilt_deg": dt, "agree": dh <= HEIGHT_AGREE and dt <= TILT_AGREE}
        )
    out["drop_agreement"] = pairs
    return out


def _f(value: float | None, fmt: str) -> str:
    return "–" if value is None else format(value, fmt)


def markdown(results: list[dict[str, Any]]) -> str:
    lines = [
        "# Spirit and Go2 dropped and slid in MuJoCo (MJCF), Drake (SDF) and Newton (USD)",
        "",
        "`python benchmarks/contact_drop.py --robot spirit --robot go2 --json benchmarks/results/contact_drop.json"
        " --md benchmarks/results/contact_drop.md` (what each column means: the script's docstring). Drop: 1 s"
        " from 5 cm, stand pose, gains 100 / 2; settle: time after which the base stays within 1 mm of its end;"
        " sag: the worst joint's distance from the pose at the end. Slide: block of the feet's friction on"
        " tan θ = 0.7 μ (stick) and 1.3 μ (slide); applied μ from the distance slid.",
        "",
    ]
    for robot in dict.fromkeys(r["robot"] for r in results):
        rows = [r for r in results if r["robot"] == robot]
        src = rows[0]["source_mu"]
        lines += [
            f"## {robot} (source μ of its feet: {'not given' if src is None else src}; feet: {', '.join(rows[0]['feet'] or [])})",
            "",
            "| engine (file) | preset | height m | tilt ° | settle s | sag rad | μ read | stick m | slide m | applied μ |",
            "|---|---|---|---|---|---|---|---|---|---|",
        ]
        for engine in ENGINES:
            for r in rows:
                e = r["engines"].get(engine)
                if e is None:
                    continue
                d, s = e.get("drop") or {}, e.get("slide") or {}
                lines.append(
                    f"| {engine} ({e['file']}) | {r['preset']} | {_f(d.get('height_m'), '.4f')} | "
                    f"{_f(d.get('tilt_deg'), '.2f')} | {_f(d.get('settle_s'), '.2f')} | {_f(d.get('sag_rad'), '.3f')} | "
                    f"{_f(s.get('mu'), '.3g')} | {_f(s.get('stick_m'), '.4f')} | {_f(s.get('slide_m'), '.3f')} | "
                    f"{_f(s.get('applied_mu'), '.3f')} |"
                )
        lines += ["", "| preset | pair | Δ height m | Δ tilt ° | within 2 cm and 2° |", "|---|---|---|---|---|"]
        for r in rows:
            for p in r["drop_agreement"]:
                lines.append(
                    f"| {r['preset']} | {p['pair']} | {p['height_m']:.4f} | {p['tilt_deg']:.2f} | {'yes' if p['agree'] else 'NO'} |"
                )
        for r in rows:
            for c in r["checks"]:
                lines.append(f"\n- {r['preset']}: {c['status'].upper()} {c['name']} {c['element']}: {c['message']}")
        lines.append("")
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--robot", action="append", choices=sorted(ROBOTS))
    parser.add_argument("--json")
    parser.add_argument("--md")
    args = parser.parse_args()
    results = [run(robot, preset) for robot in (args.robot or ["spirit"]) for preset in PRESETS]
    publish(markdown(results), results, args.json, args.md)
    return 0


if __name__ == "__main__":
    sys.exit(main())
