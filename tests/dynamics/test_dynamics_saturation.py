"""Saturation (#38): each drive's peak effort in the hold and drop, as a share of its effort limit,
per engine. A horizontal arm whose hold effort is known in closed form, m g l, checks the numbers;
the verdict rows are checked on hand-made runs. Nothing here is timed."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

import robodesc
from robodesc.validation.dynamics import Run
from robodesc.validation.dynamics.result import DynamicsReport
from robodesc.validation.dynamics.scenarios import Thresholds
from robodesc.validation.dynamics.verdict import _drop as judge_drop
from robodesc.validation.dynamics.verdict import _saturation
from robodesc.validation.report import Status

from ..conftest import ROOT

G = 9.81
MASS, ARM_LENGTH = 1.0, 0.5  # kg, m: a point-like bob at the end of a massless arm
HOLD = MASS * G * ARM_LENGTH  # N·m the drive holds at the horizontal


def _pendulum(tmp_path: Path, effort: float) -> Path:
    """A hinge about y at the base, the arm along x (horizontal at q = 0), its mass at the end."""
    urdf = tmp_path / "pendulum.urdf"
    urdf.write_text(
        f"""<robot name="pendulum">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="arm">
    <inertial><origin xyz="{ARM_LENGTH} 0 0"/><mass value="{MASS}"/>
      <inertia ixx="1e-5" iyy="1e-5" izz="1e-5" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="{effort}" velocity="10"/></joint>
</robot>"""
    )
    return urdf


# Stiff and overdamped: the arm sags by m g l / kp = 4.9 mrad without ringing, so the drive's peak is
# the static m g l up to the deceleration of the sag (I q'' of order 1e-3 of m g l).
KP, KD = 1000.0, 200.0
GAINS = {"stiffness": KP, "damping": KD, "pose": {"hinge": 0.0}}


def test_the_hold_effort_of_a_horizontal_arm_is_m_g_l_in_mujoco_and_drake(tmp_path: Path) -> None:
    urdf = _pendulum(tmp_path, effort=2 * HOLD)
    dyn = robodesc.check(str(urdf), "urdf", dynamics={"engines": ("mujoco", "drake"), **GAINS}).dynamics
    assert dyn is not None
    holds = [r for r in dyn.runs if r.scenario == "hold-fixed" and r.file != "source"]
    assert {r.engine for r in holds} >= {"mujoco"}
    for run in holds:
        assert run.peak_effort["hinge"] == pytest.approx(HOLD, rel=0.02), run.engine
        assert run.saturation["hinge"] == pytest.approx(0.5, rel=0.02), run.engine
        assert run.worst_saturation() == ("hinge", pytest.approx(0.5, rel=0.02))
    assert not [c for c in dyn.checks if c.name == "saturation"]
    assert "0.50 hinge" in dyn.to_text()
    doc = dyn.as_dict()["runs"][0]
    assert doc["peak_effort"]["hinge"] == pytest.approx(HOLD, rel=0.02)
    assert doc["saturation"]["hinge"] == pytest.approx(0.5, rel=0.02)


def test_a_drive_whose_limit_is_below_m_g_l_saturates_and_sags(tmp_path: Path) -> None:
    """Effort limit half of m g l: the drive gives its limit and no more, the arm falls away from
    the pose, and the report says the drive saturates."""
    urdf = _pendulum(tmp_path, effort=HOLD / 2)
    dyn = robodesc.check(str(urdf), "urdf", dynamics={"engines": ("mujoco",), **GAINS}).dynamics
    assert dyn is not None
    hold = next(r for r in dyn.runs if r.scenario == "hold-fixed" and r.file == "urdf")
    # MuJoCo's URDF reader turns effort into the joint's actuator force range: the drive is clamped.
    assert hold.saturation["hinge"] == pytest.approx(1.0, abs=0.01)
    assert (hold.drift or 0.0) > 0.5
    rows = [c for c in dyn.checks if c.name == "saturation"]
    assert rows and all(c.status is Status.WARN for c in rows)
    assert "'hinge' peaks at" in rows[0].message


def _run(engine: str, share: float) -> Run:
    run = Run(engine, "usd" if engine == "physx" else "urdf", "drop")
    run.set_peaks({"knee": 20.0 * share, "hip": 1.0}, {"knee": 20.0, "hip": 20.0})
    return run


def test_saturation_rows_name_the_engine_that_saturates_and_the_others_share() -> None:
    report = DynamicsReport("r", runs=[_run("mujoco", 0.6), _run("physx", 1.0)])
    _saturation(report, report.runs, Thresholds())
    (row,) = [c for c in report.checks if c.name == "saturation"]
    assert row.status is Status.WARN and row.element == "physx/usd/drop"
    assert "1 drive(s) reach their effort limit (knee)" in row.message and "mujoco/urdf 0.60" in row.message
    assert row.error == pytest.approx(1.0)


def test_a_joint_without_an_effort_limit_has_a_peak_and_no_share() -> None:
    run = Run("mujoco", "urdf", "hold-fixed")
    run.set_peaks({"knee": 3.0, "wheel": 2.0}, {"knee": 6.0})
    assert run.saturation == {"knee": 0.5} and run.peak_effort["wheel"] == 2.0
    assert run.worst_saturation() == ("knee", 0.5)


def test_validate_takes_the_controllers_gains(tmp_path: Path) -> None:
    """``--stiffness`` on ``validate --dynamics``: a weaker drive sags more, by m g l / kp."""
    urdf = _pendulum(tmp_path, effort=2 * HOLD)
    drifts = {}
    for kp in ("1000", "250"):
        cmd = [sys.executable, "-m", "robodesc", "validate", str(urdf), "-t", "urdf", "--dynamics"]
        cmd += ["--engines", "mujoco", "--stiffness", f"hin.*={kp}", "--damping", "200", "--json"]
        done = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
        assert done.returncode == 0, done.stdout + done.stderr
        runs = json.loads(done.stdout)["dynamics"]["runs"]
        drifts[kp] = next(r["drift"] for r in runs if r["scenario"] == "hold-fixed" and r["file"] == "urdf")
    # Overdamped (kd 200): the sag follows the first-order lag towards m g l / kp, time constant kd / kp
    # (0.2 s and 0.8 s), for the run's 1 s.
    for kp, drift in drifts.items():
        k = float(kp)
        assert drift == pytest.approx(HOLD / k * (1.0 - math.exp(-k / 200.0)), rel=0.03), kp


def test_gains_without_dynamics_are_refused(tmp_path: Path) -> None:
    urdf = _pendulum(tmp_path, effort=2 * HOLD)
    cmd = [sys.executable, "-m", "robodesc", "validate", str(urdf), "-t", "urdf", "--stiffness", "60"]
    done = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    assert done.returncode != 0 and "add --dynamics" in done.stderr


def _drop(engine: str, height: float, mass: float) -> Run:
    run = Run(engine, "usd" if engine == "physx" else "urdf", "drop", height=height, tilt=0.0)
    run.mass = mass
    return run


def test_drops_that_settle_apart_with_different_masses_say_so() -> None:
    """ANYmal C: PhysX reads 99.5 kg where the URDF says 52.1 (issue 38): the row says mass, not contact."""
    report = DynamicsReport("r", runs=[_drop("mujoco", 0.4249, 52.13), _drop("physx", 0.4617, 99.51)])
    judge_drop(report, report.runs, Thresholds())
    (row,) = [c for c in report.checks if c.name == "agree:drop"]
    assert row.status is Status.WARN and "different masses" in row.message and "99.51 kg" in row.message
    report = DynamicsReport("r", runs=[_drop("mujoco", 0.40, 52.13), _drop("physx", 0.46, 52.14)])
    judge_drop(report, report.runs, Thresholds())
    (row,) = [c for c in report.checks if c.name == "agree:drop"]
    assert "contact models differ" in row.message
