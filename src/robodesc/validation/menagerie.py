"""mujoco_menagerie's model test (``test/model_test.py``), as a validation check.

Menagerie's CI compiles every ``scene*.xml``, then steps it until ``data.time`` reaches 1 s at the
model's own timestep, setting each actuator's control from a Halton sequence spread over its
``ctrlrange`` (or [-1, 1] where the control is unlimited) before every step. Any non-zero
``mjData.warning`` counter fails the model. This module repeats that loop step for step, so a
model that passes here passes there, and also fails on a NaN or infinite state: MuJoCo resets the
state after a bad acceleration and only its warning counter remembers it, which a reader of the
final state alone would miss.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import mujoco
import numpy as np

from robodesc.validation.mujoco_load import captured_warnings
from robodesc.validation.report import Status, ValidationReport

MAX_SIM_TIME = 1.0  # s, menagerie's _MAX_SIM_TIME
NOISE_SCALE = 1.0  # menagerie's _NOISE_SCALE


@dataclass(slots=True)
class MenagerieResult:
    steps: int = 0
    # mjtWarning name -> count, for every counter that is not zero at the end.
    warnings: dict[str, int] = field(default_factory=dict)
    # Simulated time at which qpos/qvel/ctrl first held a NaN or an infinity (None: never).
    nonfinite_at: float | None = None
    # What MuJoCo printed (e.g. "Nan, Inf or huge value in QACC at DOF 3"), which names the DOF.
    messages: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.warnings and self.nonfinite_at is None


# A control range wider than this (rad, m or N·m) is read as no range.
UNBOUNDED = 1e6


def pseudorandom_ctrl(model: Any, data: Any, i: int, noise: float = NOISE_SCALE) -> None:
    """Menagerie's ``_pseudorandom_ctrlnoise``: step ``i``'s control, deterministic across runs."""
    for j in range(model.nu):
        lo, hi = (float(x) for x in model.actuator_ctrlrange[j])
        if model.actuator_ctrllimited[j] and hi - lo <= UNBOUNDED:
            center, radius = 0.5 * (hi + lo), 0.5 * (hi - lo)
        else:
            # Unlimited, or a range no motor has (a URDF's ±1e16 for "no limit", iris' rotors): the
            # noise of an unlimited control. Menagerie's models have no such ranges.
            center, radius = 0.0, 1.0
        data.ctrl[j] = center + radius * noise * (2 * mujoco.mju_Halton(i, j + 2) - 1)


def run_menagerie_test(model: Any, duration: float = MAX_SIM_TIME) -> MenagerieResult:
    """Step ``model`` for ``duration`` s of simulated time under menagerie's control noise."""
    data = mujoco.MjData(model)
    result = MenagerieResult()
    # MuJoCo resets the state, time included, after a bad acceleration: menagerie's loop on time
    # alone would then never end. Capping the steps at what a healthy run takes keeps its verdict.
    max_steps = math.ceil(duration / float(model.opt.timestep)) + 1
    # Captured rather than left to MuJoCo, which would print them and append to MUJOCO_LOG.TXT
    # in the working directory.
    with captured_warnings(result.messages):
        while data.time < duration and result.steps < max_steps:
            pseudorandom_ctrl(model, data, result.steps)
            mujoco.mj_step(model, data)
            result.steps += 1
            if result.nonfinite_at is None and not _finite(data):
                result.nonfinite_at = float(data.time)
    for index, counter in enumerate(data.warning):
        if int(counter.number):
            result.warnings[mujoco.mjtWarning(index).name] = int(counter.number)
    return result


def _finite(data: Any) -> bool:
    return bool(np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel)) and np.all(np.isfinite(data.ctrl)))


def add_menagerie_check(model: Any, element: str, report: ValidationReport) -> MenagerieResult:
    """Run the test and add one ``menagerie`` row (pass, or fail listing every warning)."""
    result = run_menagerie_test(model)
    timestep = float(model.opt.timestep)
    if result.ok:
        report.add(
            "menagerie",
            Status.PASS,
            element,
            f"stepped {result.steps} × {timestep:g} s under pseudorandom control of {model.nu} actuators "
            "across ctrlrange: no MuJoCo warning, no NaN",
        )
        return result
    problems = [f"{name}: count={count}" for name, count in sorted(result.warnings.items())]
    if result.nonfinite_at is not None:
        problems.append(f"state not finite at t = {result.nonfinite_at:.4g} s")
    if result.messages:
        problems.append("first: " + result.messages[0])
    report.add(
        "menagerie",
        Status.FAIL,
        element,
        f"mujoco_menagerie's model test fails after {result.steps} steps of {timestep:g} s: " + "; ".join(problems),
    )
    return result
