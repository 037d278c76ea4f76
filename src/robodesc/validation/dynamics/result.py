"""What the dynamics check measured: one :class:`Run` per engine, file and scenario, and the
verdicts drawn from them (:class:`~robodesc.validation.report.Check` rows, as every validation)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from robodesc.ir.model import Robot
from robodesc.validation.report import Check, Status

# A dropped robot has settled once its root height stays within this of where it ends.
SETTLE_BAND = 0.001  # m
# How an engine's refusal starts when the file says what the source says and the engine reads that
# differently: a warning, not robodesc's fault.
READS_DIFFERENTLY = "reads the source differently:"


def settle_time(heights: list[tuple[float, float]], band: float = SETTLE_BAND) -> float | None:
    """The first sample time after which every (time, root height) sample stays within ``band`` of
    the last one; None without samples."""
    if not heights:
        return None
    final = heights[-1][1]
    settled = heights[-1][0]
    for t, z in reversed(heights):
        if abs(z - final) > band:
            break
        settled = t
    return settled


@dataclass(slots=True)
class Run:
    """One scenario in one engine. Quantities are None when the scenario does not measure them."""

    engine: str  # "mujoco", "drake", "newton", "physx"
    file: str  # what the engine read: "urdf", "sdf", "usd", "mjcf", or "source" (the input itself)
    scenario: str  # "hold-fixed", "drop", "slide"
    ok: bool = True  # the run finished with a finite state
    error: str = ""
    drift: float | None = None  # max |q - q_home| at the end, rad or m
    worst_joint: str = ""
    height: float | None = None  # root height at the end, m
    tilt: float | None = None  # angle between the root's z and the world's, rad
    settle: float | None = None  # drop: time after which the root height stays within SETTLE_BAND of its end, s
    mu: float | None = None  # friction the engine gave the robot's colliders
    stick: float | None = None  # slide: distance moved on the "sticks" plane, m
    slide: float | None = None  # slide: distance moved on the "slides" plane, m
    mass: float | None = None  # the robot's total mass as the engine read it, kg (the floor excluded)
    seconds: float = 0.0
    final_q: dict[str, float] = field(default_factory=dict)
    # Each driven joint's largest |drive effort| over the run's steps (N·m or N), and that peak as a
    # share of the joint's effort limit (1 = saturated; joints without a limit are left out).
    peak_effort: dict[str, float] = field(default_factory=dict)
    saturation: dict[str, float] = field(default_factory=dict)
    # (time, {joint: q}) samples, for comparing an output with its source in one engine.
    trajectory: list[tuple[float, dict[str, float]]] = field(default_factory=list)
    # (time, (x, y, z, qw, qx, qy, qz)) of the root link in the world, SI, at the trajectory's
    # samples: filled by the drop only when ``Setup.record`` asks (``validate --video``).
    root: list[tuple[float, tuple[float, ...]]] = field(default_factory=list)
    # stand (on a world): each foot link's pose (x, y, z, qw, qx, qy, qz) at the start and the end,
    # what the runner read; the rest is measured from them against the ground (run.py).
    feet_start: dict[str, list[float]] = field(default_factory=dict)
    feet_end: dict[str, list[float]] = field(default_factory=dict)
    feet_height: dict[str, float] = field(default_factory=dict)  # root height over the ground under each foot, m
    sole_gap: float | None = None  # the largest |sole - ground under it| at the end, m
    slip: float | None = None  # the largest horizontal travel of a sole, m
    contact_sum: float | None = None  # the feet's contact sensors, summed (N, the normal force)
    weight: float | None = None  # the robot's weight as the engine read its mass, N
    # Each joint's armature as the engine read it from the file (MuJoCo on an MJCF), kg·m²: the source
    # run in the same engine is given the armature the file adds (run.py, _source_setup).
    armature: dict[str, float] = field(default_factory=dict)

    def as_dict(self) -> dict[str, Any]:
        keys = ("engine", "file", "scenario", "ok", "error", "drift", "worst_joint", "height", "tilt", "mu")
        out: dict[str, Any] = {k: getattr(self, k) for k in keys}
        out.update(stick=self.stick, slide=self.slide, settle=self.settle, seconds=round(self.seconds, 3))
        if self.mass is not None:
            out["mass"] = round(self.mass, 4)
        if self.scenario == "stand":
            out.update(
                feet_height={k: round(v, 4) for k, v in self.feet_height.items()},
                sole_gap=self.sole_gap,
                slip=self.slip,
                contact_sum=self.contact_sum,
                weight=self.weight,
            )
        if self.peak_effort:
            out["peak_effort"] = {k: round(v, 4) for k, v in self.peak_effort.items()}
            out["saturation"] = {k: round(v, 4) for k, v in self.saturation.items()}
            out["worst_saturation"] = self.worst_saturation()
        return out

    def set_peaks(self, peaks: Mapping[str, float], limits: Mapping[str, float]) -> None:
        """Record the peak efforts and their shares of ``limits`` (joint -> effort limit > 0)."""
        self.peak_effort = {k: float(v) for k, v in peaks.items()}
        self.saturation = {k: float(v) / limits[k] for k, v in peaks.items() if limits.get(k, 0.0) > 0.0}

    def worst_saturation(self) -> tuple[str, float] | None:
        """(joint, share) of the most saturated joint, None when no joint has a limit."""
        if not self.saturation:
            return None
        joint = max(self.saturation, key=lambda k: self.saturation[k])
        return joint, round(self.saturation[joint], 4)


@dataclass(slots=True)
class DynamicsReport:
    robot: str
    runs: list[Run] = field(default_factory=list)
    checks: list[Check] = field(default_factory=list)
    info: dict[str, Any] = field(default_factory=dict)
    # The IR the runs' joints are named after (the source's), for drawing the runs
    # (robodesc.view.video); not part of the report's text or JSON.
    model: Robot | None = field(default=None, repr=False, compare=False)

    @property
    def ok(self) -> bool:
        return not any(c.status is Status.FAIL for c in self.checks)

    def add(self, name: str, status: Status, element: str, message: str, **kw: float | None) -> None:
        self.checks.append(Check(name, status, element, message, kw.get("error"), kw.get("tolerance")))

    def agreement(self) -> dict[str, str]:
        """Per scenario: "agree", "differ" or "n/a" (fewer than two engines ran it), for the corpus
        report's column."""
        out: dict[str, str] = {}
        # The stand only when there was a world: the corpus report's columns stay the three.
        stand = ("stand",) if any(r.scenario == "stand" for r in self.runs) else ()
        for scenario in ("hold-fixed", "drop", "slide", *stand):
            names = [c for c in self.checks if c.name == f"agree:{scenario}"]
            if not names:
                out[scenario] = "n/a"
            else:
                out[scenario] = "differ" if any(c.status is not Status.PASS for c in names) else "agree"
        return out

    def as_dict(self) -> dict[str, Any]:
        return {
            "robot": self.robot,
            "ok": self.ok,
            "runs": [r.as_dict() for r in self.runs],
            "checks": [c.as_dict() for c in self.checks],
            "agreement": self.agreement(),
            "info": self.info,
        }

    def to_text(self) -> str:
        lines = [f"dynamics of {self.robot!r} ({self.info.get('pose_note', 'home pose')}):"]
        head = f"  {'engine':<8} {'file':<7} {'scenario':<11} {'drift':>9} {'height':>8} {'tilt':>7} {'mu':>6} {'moved stick/slide':>18} {'peak/effort':>20} {'s':>6}"
        lines.append(head)
        for r in self.runs:
            if not r.ok:
                lines.append(f"  {r.engine:<8} {r.file:<7} {r.scenario:<11} failed: {r.error}")
                continue
            moved = "" if r.stick is None else f"{_num(r.stick, 3)}/{_num(r.slide, 3)}"
            if r.scenario == "stand":
                moved = f"slip {_num(r.slip, 3)}"
            tilt = None if r.tilt is None else math.degrees(r.tilt)
            lines.append(
                f"  {r.engine:<8} {r.file:<7} {r.scenario:<11} {_num(r.drift, 4):>9} {_num(r.height, 3):>8} "
                f"{_num(tilt, 1):>7} {_num(r.mu, 3):>6} {moved:>18} {_saturation(r):>20} {r.seconds:>6.2f}"
            )
        stands = [r for r in self.runs if r.scenario == "stand" and r.ok and r.feet_height]
        if stands:
            lines.append(
                "  on the world: root height over the ground under each foot (m), sole gap, contact sensors / weight"
            )
        for r in stands:
            feet = " ".join(f"{k} {v:.3f}" for k, v in r.feet_height.items())
            sensed = "" if r.contact_sum is None else f"; sensors {r.contact_sum:.1f} N / weight {_num(r.weight, 1)} N"
            lines.append(f"  {r.engine:<8} {r.file:<7} {feet}; sole gap {_num(r.sole_gap, 3)}{sensed}")
        for c in sorted(self.checks, key=lambda c: c.status is Status.PASS):
            lines.append(f"  {c.status.value.upper():<4} {c.name} {c.element}: {c.message}")
        verdict = "passed" if self.ok else "FAILED (an output behaves unlike its source)"
        lines.append(f"dynamics {verdict}")
        return "\n".join(lines)


def _saturation(run: Run) -> str:
    """The most saturated joint: its peak effort as a share of its limit, and its name."""
    worst = run.worst_saturation()
    return "" if worst is None else f"{worst[1]:.2f} {worst[0][:15]}"


def run_from_json(engine: str, kind: str, raw: Mapping[str, Any], limits: Mapping[str, float]) -> Run:
    """A :class:`Run` from a worker's JSON answer (the Newton and PhysX workers speak the same)."""
    run = Run(engine, kind, str(raw["scenario"]), ok=bool(raw.get("ok")), error=str(raw.get("error", "")))
    for key in ("drift", "height", "tilt", "mu", "stick", "slide", "mass", "contact_sum"):
        value = raw.get(key)
        setattr(run, key, None if value is None else float(value))
    run.worst_joint = str(raw.get("worst_joint", ""))
    run.seconds = float(raw.get("seconds", 0.0))
    run.final_q = {str(k): float(v) for k, v in (raw.get("final_q") or {}).items()}
    run.trajectory = [(float(t), {str(k): float(v) for k, v in q.items()}) for t, q in raw.get("trajectory", [])]
    run.root = [(float(t), tuple(float(c) for c in pose)) for t, pose in raw.get("root", [])]
    for key in ("feet_start", "feet_end"):
        setattr(run, key, {str(k): [float(v) for v in pose] for k, pose in (raw.get(key) or {}).items()})
    if raw.get("heights"):
        run.settle = settle_time([(float(t), float(z)) for t, z in raw["heights"]])
    if raw.get("peak_effort"):
        run.set_peaks({str(k): float(v) for k, v in raw["peak_effort"].items()}, limits)
    return run


def _num(value: float | None, digits: int) -> str:
    return "-" if value is None else f"{value:.{digits}f}"
