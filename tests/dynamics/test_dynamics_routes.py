"""Two stages of one robot compared scenario by scenario (``validation/dynamics/routes.py``): the
Isaac Sim 6 route's composed stage against robodesc's own USD, within docs/dynamics.md's thresholds."""

from __future__ import annotations

import math

from robodesc.validation.dynamics import Run, Thresholds
from robodesc.validation.dynamics.routes import behaviour_differences


def _runs(height: float = 0.35, knee: float = 0.80, mu: float = 0.5, slide: float = 0.6) -> list[Run]:
    return [
        Run("physx", "usd", "hold-fixed", drift=abs(knee - 0.8) + 0.006, final_q={"knee": knee, "hip": 0.4}),
        Run("physx", "usd", "drop", drift=0.01, height=height, tilt=0.001, mass=15.4, final_q={"knee": knee}),
        Run("physx", "usd", "slide", mu=mu, stick=1e-4, slide=slide),
    ]


def test_the_same_runs_behave_alike() -> None:
    assert behaviour_differences(_runs(), _runs()) == []


def test_differences_within_the_thresholds_are_the_same_behaviour() -> None:
    # The importer without the armature: the quadruped's drop settled 0.2 mm lower (measured 0.34923
    # against 0.34946 m), its hold 7e-5 rad apart.
    assert behaviour_differences(_runs(), _runs(height=0.3492, knee=0.80007)) == []


def test_the_drop_is_judged_by_where_the_base_settles() -> None:
    # Spirit without armature (importer_settings.json), 0.3 s: knees 0.025 rad apart mid-landing, the
    # base 2 mm lower; the drop's thresholds are on the base, as between engines.
    other = _runs(height=0.348)
    other[1].final_q = {"knee": 0.825}
    assert behaviour_differences(_runs(), other) == []


def test_a_lower_drop_and_a_sagging_joint_are_named_with_both_values() -> None:
    th = Thresholds()
    diffs = behaviour_differences(_runs(), _runs(height=0.35 - 2 * th.drop_height_agree, knee=0.9))
    assert "physx drop: height 0.2900 m (reference 0.3500, agree within 0.03)" in diffs
    assert "physx hold-fixed: joint 'knee' ends at 0.9000 (reference 0.8000, agree within 0.02)" in diffs
    # 0.106 rad from the target: the hold no longer holds within 0.05.
    assert "physx hold-fixed: drift 0.1060 (reference 0.0060; holds within 0.05)" in diffs


def test_a_lost_contact_material_shows_in_the_slide() -> None:
    # Stretch's caster: friction 0 in robodesc's USD, PhysX's default 0.5 where the binding is lost.
    ours = _runs(mu=0.0, slide=0.9)
    ours[2].stick = 0.5  # with no friction the block slides on both planes
    diffs = behaviour_differences(ours, _runs(mu=0.5))
    assert "physx slide: friction 0.5000 (reference 0.0000)" in diffs
    assert "physx slide: on the 'sticks' plane the block moves 0.0001 m (reference 0.5000)" in diffs


def test_a_run_that_fails_or_is_missing_is_a_difference() -> None:
    failed = _runs()
    failed[0] = Run("physx", "usd", "hold-fixed", ok=False, error="none of the robot's driven joints is in the file")
    diffs = behaviour_differences(_runs(), failed[:2])
    assert diffs == [
        "physx hold-fixed: failed: none of the robot's driven joints is in the file (reference ran)",
        "physx slide: not run",
    ]


def test_tilt_and_mass() -> None:
    other = _runs()
    other[1].tilt = math.radians(20.0)
    other[1].mass = 16.0
    diffs = behaviour_differences(_runs(), other)
    assert "physx drop: tilt 20.0000° (reference 0.0573°)" in diffs
    assert "physx drop: mass 16.0000 kg (reference 15.4000)" in diffs
