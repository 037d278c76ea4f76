"""USD stores joint frames in float32: the FK tolerance follows the rounding of the numbers written
along each link's path (issue 26: a 20,000-link chain drifted 1e-5 m at its tip and was blamed on
robodesc)."""

from __future__ import annotations

from robodesc.ir.geometry import Pose
from robodesc.ir.model import Joint, JointType, Limit, Link, Robot
from robodesc.validation.options import ValidateOptions
from robodesc.validation.usd_physics import FLOAT32_FK_TOL, float32_fk_tolerances


def _chain(n: int, xyz: tuple[float, float, float], rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> Robot:
    links = [Link(name=f"l{i}") for i in range(n)]
    joints = [
        Joint(
            name=f"j{i}",
            type=JointType.REVOLUTE,
            parent=f"l{i - 1}",
            child=f"l{i}",
            origin=Pose(xyz=xyz, rpy=rpy),
            axis=(0.0, 0.0, 1.0),
            limit=Limit(lower=-1.0, upper=1.0, effort=1.0, velocity=1.0),
        )
        for i in range(1, n)
    ]
    return Robot(name="chain", links=links, joints=joints)


def _opts() -> ValidateOptions:
    return ValidateOptions(position_tol=FLOAT32_FK_TOL, rotation_tol=FLOAT32_FK_TOL)


def test_exact_numbers_keep_the_fixed_tolerance() -> None:
    assert float32_fk_tolerances(_chain(1000, (0.0, 0.0, 0.125)), _opts()) == {}


def test_long_chain_tolerance_grows_with_the_rounding_written() -> None:
    tol = float32_fk_tolerances(_chain(20_000, (0.0, 0.0, 0.1)), _opts())
    # 0.1 is 1.49e-9 off in float32: 19,999 joints add up to ~3e-5 m at the tip, doubled.
    tip_p, tip_r = tol["l19999"]
    assert 5e-5 < tip_p - FLOAT32_FK_TOL < 7e-5
    assert tip_r == FLOAT32_FK_TOL
    # Near the root the tolerance is still the fixed one, so a corruption there is still caught.
    assert tol["l10"][0] < FLOAT32_FK_TOL + 1e-7


def test_rotations_count_with_their_lever_arm() -> None:
    tol = float32_fk_tolerances(_chain(100, (0.0, 0.0, 0.1), rpy=(0.3, 0.0, 0.0)), _opts())
    assert tol["l99"][1] > tol["l50"][1] > FLOAT32_FK_TOL
    assert tol["l99"][0] > tol["l50"][0]
