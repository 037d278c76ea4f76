"""The plain-float maths (robodesc.ir.rigid, robodesc.ir.principal) against numpy."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from robodesc.ir.geometry import Inertia
from robodesc.ir.principal import inertia_problem, symmetric_eigen
from robodesc.ir.rigid import (
    Frame,
    axis_angle_rotation,
    matmul,
    quat_rotation,
    rotation_quat,
    rotation_rpy,
    rpy_rotation,
)

USD_DATA = Path(__file__).resolve().parents[1] / "usd" / "data"


def _random_tensors(count: int) -> list[np.ndarray]:
    rng = np.random.default_rng(7)
    out = []
    for k in range(count):
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        kind = k % 4
        if kind == 0:  # moments over ten decades
            d = 10.0 ** rng.uniform(-8, 2, 3)
        elif kind == 1:  # two equal moments (a cylinder)
            d = np.array([1.0, 1.0, 2.0]) * rng.uniform(0.1, 10)
        elif kind == 2:  # nearly diagonal: off-diagonal terms at rounding level
            q = np.eye(3) + rng.normal(size=(3, 3)) * 1e-13
            d = rng.uniform(0.1, 1.0, 3)
        else:
            d = rng.uniform(0.0, 1.0, 3)
        m = q @ np.diag(d) @ q.T
        out.append((m + m.T) / 2)
    return out


@pytest.mark.parametrize("m", _random_tensors(400))
def test_symmetric_eigen_matches_lapack_and_recomposes(m: np.ndarray) -> None:
    values, axes = symmetric_eigen(tuple(tuple(float(x) for x in row) for row in m))
    scale = float(np.max(np.abs(m)))
    np.testing.assert_allclose(values, np.linalg.eigvalsh(m), rtol=0, atol=4e-15 * scale)
    r = np.array(axes)
    np.testing.assert_allclose(r.T @ r, np.eye(3), atol=2e-15)
    assert np.linalg.det(r) == pytest.approx(1.0, abs=1e-14)
    np.testing.assert_allclose(r @ np.diag(values) @ r.T, m, rtol=0, atol=4e-15 * scale)
    assert list(values) == sorted(values)


def test_symmetric_eigen_signs_give_the_rotation_closest_to_identity() -> None:
    # Any rotation with these columns (up to sign) is valid; the convention picks the largest trace.
    values, axes = symmetric_eigen(((1.0, 1e-9, 0.0), (1e-9, 2.0, 0.0), (0.0, 0.0, 3.0)))
    assert values == pytest.approx((1.0, 2.0, 3.0))
    np.testing.assert_allclose(np.array(axes), np.eye(3), atol=1e-8)
    diag = symmetric_eigen(((3.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 2.0)))
    assert diag[0] == (1.0, 2.0, 3.0)
    assert np.linalg.det(np.array(diag[1])) == 1.0


def test_inertia_problem_cases() -> None:
    assert inertia_problem(Inertia(1.0, 1.0, 1.0)) is None
    assert inertia_problem(Inertia(0.0, 0.0, 0.0)) == "inertia tensor is zero"
    assert inertia_problem(Inertia(math.nan, 1.0, 1.0)) == "inertia has a non-finite value"
    assert "not positive definite" in (inertia_problem(Inertia(1.0, 1.0, -1.0)) or "")
    assert "triangle inequality" in (inertia_problem(Inertia(1.0, 1.0, 3.0)) or "")
    # A thin rod: I1 + I2 = I3 to the printed digits is accepted.
    assert inertia_problem(Inertia(0.5, 0.5, 1.0)) is None
    # Off-diagonal: a rotated box is fine, a tensor with a negative principal moment is not.
    assert inertia_problem(Inertia(2.0, 2.0, 3.0, ixy=0.5)) is None
    assert inertia_problem(Inertia(1.0, 1.0, 1.0, ixy=1.5)) is not None


def test_rotations_match_closed_forms() -> None:
    rng = np.random.default_rng(3)
    for _ in range(200):
        rpy = tuple(float(x) for x in rng.uniform(-3, 3, 3))
        r = np.array(rpy_rotation(rpy))  # type: ignore[arg-type]
        rx = np.array(axis_angle_rotation((1.0, 0.0, 0.0), rpy[0]))
        ry = np.array(axis_angle_rotation((0.0, 1.0, 0.0), rpy[1]))
        rz = np.array(axis_angle_rotation((0.0, 0.0, 1.0), rpy[2]))
        np.testing.assert_allclose(r, rz @ ry @ rx, atol=1e-15)
        np.testing.assert_allclose(np.array(rpy_rotation(rotation_rpy(r.tolist()))), r, atol=1e-12)
        q = rotation_quat(r.tolist())
        assert q[0] >= 0 and math.isclose(math.hypot(*q), 1.0, rel_tol=1e-15)
        np.testing.assert_allclose(np.array(quat_rotation(q)), r, atol=1e-15)
        np.testing.assert_allclose(np.array(matmul(r.tolist(), r.T.tolist())), np.eye(3), atol=1e-15)


def test_frame_composition_is_the_matrix_product() -> None:
    a = Frame(rpy_rotation((0.1, -0.4, 2.0)), (1.0, 2.0, 3.0))
    b = Frame(rpy_rotation((-1.0, 0.3, 0.2)), (-0.5, 0.25, 4.0))
    np.testing.assert_allclose(np.array((a @ b).matrix()), np.array(a.matrix()) @ np.array(b.matrix()), atol=1e-15)


@pytest.mark.parametrize("name", ["gripper", "sensors", "fourbar"])
def test_robot_of_primitives_compiles_to_usd_without_numpy(tmp_path: Path, name: str) -> None:
    """numpy's import costs more than converting a small robot: the path from URDF to USD must not
    need it unless a mesh or a computed inertia does."""
    code = (
        "import sys\n"
        "from robodesc.cli import main\n"
        f"code = main(['compile', {str(USD_DATA / f'{name}.urdf')!r}, '-t', 'usd', '--layered',"
        f" '--physics-scene', '--no-validate', '-q', '-o', {str(tmp_path / 'robot.usda')!r}])\n"
        "assert code == 0, code\n"
        "print('numpy' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
