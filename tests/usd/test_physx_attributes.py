"""Each PhysX joint attribute robodesc writes, proved in PhysX (ovphysx, on CPU): a pendulum or a
wheel whose motion changes when the attribute does, compared with the analytic motion.

The USD is robodesc's own (``emit_usd`` with a ``/PhysicsScene``); PhysX runs in its interpreter
(``robodesc.validation.physx_python``) through ``physx_joint_run.py``. Without it the tests skip.

The pendulum: a 1 kg point mass 0.5 m from a revolute joint about +Y (I = m l² + 1e-4 kg·m²),
gravity 9.81 m/s² along -Z, no drive gains (target type none).
"""

from __future__ import annotations

import json
import math
import subprocess
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from robodesc.emit.usd import UsdOptions, emit_usd
from robodesc.frontends.urdf import read_urdf_string
from robodesc.validation.physx_python import physx_python

PYTHON = physx_python()
pytestmark = pytest.mark.skipif(PYTHON is None, reason="PhysX (ovphysx) is not installed (tests/consumers/run.sh)")
RUNNER = Path(__file__).with_name("physx_joint_run.py")

G = 9.81
MASS, LENGTH = 1.0, 0.5
INERTIA = MASS * LENGTH**2 + 1e-4
DT = 0.002


def pendulum(extra: str = "", *, velocity: float = 100.0, com: str = "0 0 -0.5", axis: str = "0 1 0") -> str:
    """A URDF pendulum: the mass at ``com`` from the joint (hanging at q = 0 by default)."""
    return f"""<robot name="pendulum">
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="bob">
    <inertial><origin xyz="{com}"/><mass value="{MASS}"/>
      <inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="hinge" type="revolute">
    <parent link="base"/><child link="bob"/><axis xyz="{axis}"/>
    <limit lower="-3.1" upper="3.1" effort="100" velocity="{velocity}"/>
    {extra}
  </joint>
</robot>"""


def usd(tmp_path: Path, name: str, urdf: str, start: float, **options: Any) -> str:
    out = tmp_path / f"{name}.usda"
    robot = read_urdf_string(urdf)
    for joint in robot.joints:
        joint.armature = options.pop("armature", joint.armature)
    settings = {"target_type": "none", "physics_scene": True, "initial_positions": {"hinge": start}, **options}
    emit_usd(robot, str(out), UsdOptions(**settings))
    return str(out)


def run(tmp_path: Path, cases: list[tuple[str, float]]) -> list[dict[str, Any]]:
    """Step each (usd, seconds) in PhysX; positions in rad, velocities in rad/s."""
    spec = tmp_path / "cases.json"
    out = tmp_path / "out.json"
    spec.write_text(json.dumps([{"usd": path, "dt": DT, "steps": round(seconds / DT)} for path, seconds in cases]))
    assert PYTHON is not None
    done = subprocess.run([PYTHON, str(RUNNER), str(spec), str(out)], capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr[-3000:]
    results: list[dict[str, Any]] = json.loads(out.read_text())["cases"]
    for case in results:
        case["q"] = np.radians(case["q"])
        case["qd"] = np.radians(case["qd"])
        case["t"] = np.asarray(case["t"])
    return results


def retarget(path: str, joint: str, degrees: float) -> None:
    """Move a drive's target away from the joint's start (robodesc targets the start pose)."""
    from pxr import Usd

    stage = Usd.Stage.Open(path)
    stage.GetPrimAtPath(joint).GetAttribute("drive:angular:physics:targetPosition").Set(degrees)
    stage.Save()


def period(case: dict[str, Any]) -> float:
    """Mean time between successive downward zero crossings of the position."""
    q, t = case["q"], case["t"]
    crossings = [t[i] - DT * q[i] / (q[i] - q[i - 1]) for i in range(1, len(q)) if q[i - 1] > 0 >= q[i]]
    assert len(crossings) >= 2, "the pendulum did not swing"
    return float(np.mean(np.diff(crossings)))


def test_armature_slows_the_swing_as_theory_predicts(tmp_path: Path) -> None:
    # Small swings (0.1 rad): T = 2π sqrt((I + armature) / (m g l)); 0.5 kg·m² triples I.
    cases = [usd(tmp_path, "plain", pendulum(), 0.1), usd(tmp_path, "armature", pendulum(), 0.1, armature=0.5)]
    plain, heavy = run(tmp_path, [(cases[0], 4.0), (cases[1], 6.0)])
    assert heavy["parsed"]["jointArmature"] == pytest.approx([0.5])
    for case, armature in ((plain, 0.0), (heavy, 0.5)):
        expected = 2 * math.pi * math.sqrt((INERTIA + armature) / (MASS * G * LENGTH))
        assert period(case) == pytest.approx(expected, rel=0.01)
    assert period(heavy) / period(plain) == pytest.approx(math.sqrt((INERTIA + 0.5) / INERTIA), rel=0.01)


def test_max_joint_velocity_caps_speed_at_the_written_value(tmp_path: Path) -> None:
    # Released from horizontal, the free pendulum reaches sqrt(2 m g l / I) = 6.26 rad/s at the
    # bottom; a URDF velocity of 1 rad/s (written as 57.3 deg/s) holds it to 1 rad/s.
    free = usd(tmp_path, "free", pendulum(velocity=100.0), math.pi / 2)
    capped = usd(tmp_path, "capped", pendulum(velocity=1.0), math.pi / 2)
    free_run, capped_run = run(tmp_path, [(free, 0.6), (capped, 0.6)])
    assert capped_run["parsed"]["jointMaxVelocity"] == pytest.approx([math.degrees(1.0)], rel=1e-6)
    assert np.abs(free_run["qd"]).max() == pytest.approx(math.sqrt(2 * MASS * G * LENGTH / INERTIA), rel=0.02)
    assert np.abs(capped_run["qd"]).max() == pytest.approx(1.0, rel=0.01)


def test_friction_effort_holds_below_and_slows_above(tmp_path: Path) -> None:
    # Horizontal, gravity's torque is m g l = 4.905 N·m. A friction effort of 6 N·m holds the arm;
    # one of 3 N·m lets it fall with (m g l - 3) / I instead of m g l / I.
    torque = MASS * G * LENGTH
    paths = [
        usd(tmp_path, f"friction{f:g}", pendulum(f'<dynamics friction="{f}"/>' if f else ""), math.pi / 2)
        for f in (0.0, 3.0, 6.0)
    ]
    free, slowed, held = run(tmp_path, [(p, 0.5) for p in paths])
    assert held["parsed"]["jointStaticFriction"] == pytest.approx([6.0])
    assert held["parsed"]["jointDynamicFriction"] == pytest.approx([6.0])
    assert abs(held["q"][-1] - math.pi / 2) < 1e-3
    # 0.1 s after release the arm has turned ½ α t² (cos of the angle it turned stays above 0.999).
    at = round(0.1 / DT) - 1
    for case, friction in ((free, 0.0), (slowed, 3.0)):
        expected = 0.5 * (torque - friction) / INERTIA * 0.1**2
        assert math.pi / 2 - case["q"][at] == pytest.approx(expected, rel=0.01)


def test_performance_envelope_reduces_torque_with_speed(tmp_path: Path) -> None:
    # A wheel about the vertical (no gravity torque): I = 0.1 kg·m², a stiff position drive far from
    # its target saturates at effort 1 N·m. Alone, ω = τ t / I; with the motor envelope from the
    # URDF's effort and velocity (2 rad/s), dω/dt = (τ - τ ω / ω_max) / I: ω = ω_max (1 - e^(-t τ / (ω_max I))).
    urdf = """<robot name="wheel">
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="wheel"><inertial><mass value="1"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="hinge" type="revolute">
    <parent link="base"/><child link="wheel"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="2"/>
  </joint>
</robot>"""
    common = {"target_type": "position", "stiffness": 1000.0, "damping": 0.0}
    plain = usd(tmp_path, "plain", urdf, 2.5, **common)
    motor = usd(tmp_path, "motor", urdf, 2.5, motor_envelope=True, **common)
    for path in (plain, motor):
        retarget(path, "/wheel/joints/hinge", 0.0)
    plain_run, motor_run = run(tmp_path, [(plain, 0.2), (motor, 0.2)])
    parsed = motor_run["parsed"]
    assert parsed["jointMaxActuatorVelocity"] == pytest.approx([math.degrees(2.0)], rel=1e-6)
    at = round(0.1 / DT) - 1
    t = plain_run["t"][at]
    assert abs(plain_run["qd"][at]) == pytest.approx(1.0 * t / 0.1, rel=0.02)
    expected = 2.0 * (1 - math.exp(-t * 1.0 / (2.0 * 0.1)))
    assert abs(motor_run["qd"][at]) == pytest.approx(expected, rel=0.02)
