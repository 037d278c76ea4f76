"""The pure-Python part of newton_check.py's MJCF mode (the tier runs it inside Newton's environment;
these run in robodesc's own): how joints, masses and mimic couplings of the two imports are paired."""

from __future__ import annotations

from tests.consumers.newton_check import STUB_MASS, Report, compare_mimic, joints_by_child, mass_pairs

BODIES = ["r/worldbody/base", "r/worldbody/base/arm", "r/worldbody/base/arm/tool"]


def test_joints_are_paired_by_the_body_they_move() -> None:
    """A weld has no name in MJCF (Newton calls it ``<body>_joint``): keyed by child body, the URDF's
    ``tool_mount`` and the MJCF's ``tool_joint`` are the same joint."""
    urdf = joints_by_child(["r/fixed_base", "r/shoulder", "r/tool_mount"], [0, 1, 2], [-1, 0, 1], [3, 1, 3], BODIES)
    mjcf = joints_by_child(["r/base_joint", "r/shoulder", "r/tool_joint"], [0, 1, 2], [-1, 0, 1], [3, 1, 3], BODIES)
    assert set(urdf) == set(mjcf) == {"base", "arm", "tool"}
    assert urdf["tool"][1:] == mjcf["tool"][1:] == (3, "arm")
    assert urdf["base"][2] == mjcf["base"][2] == ""  # the base joint's parent is the world
    assert urdf["arm"][0] == mjcf["arm"][0] == "shoulder"


def test_token_mass_is_said_not_compared() -> None:
    """robodesc's 1e-3 kg on a massless moving body (MuJoCo refuses mass 0 there) is listed, not a
    failed comparison; any other difference is compared."""
    pairs, stubs = mass_pairs({"a": 0.0, "b": 1.5, "c": 0.0}, {"a": STUB_MASS, "b": 1.5, "c": 0.0})
    assert stubs == ["a"]
    assert pairs == [("b", 1.5, 1.5), ("c", 0.0, 0.0)]
    pairs, stubs = mass_pairs({"a": 0.0}, {"a": 0.002})
    assert not stubs and pairs == [("a", 0.0, 0.002)]
    rep = Report(side="mjcf")
    rep.compare("mass", pairs, 1e-6, 1e-9)
    assert not rep.checks[0]["ok"] and "mjcf 0.002" in rep.checks[0]["where"]


def test_mimic_compared_by_follower() -> None:
    names = ["base", "left", "right"]
    urdf = {"right": ("left", 0.0, 1.0)}
    assert compare_mimic(urdf, {"right": ("left", 0.0, 1.0)}) == []
    assert compare_mimic(urdf, {"right": ("left", 0.0, -1.0)}) == ["right"]
    assert compare_mimic(urdf, {}) == ["right"]
    from tests.consumers.newton_check import mimic_table

    assert mimic_table(names, [(2, 1, 0.01, 2.0)]) == {"right": ("left", 0.01, 2.0)}
