"""USD read back through usd-core's physics parser: faithful outputs pass, corrupted ones fail by name."""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from pathlib import Path

import pytest
from helpers import ROOT, SPIRIT_XACRO

import robodesc
from robodesc.ir.model import Robot
from robodesc.validation.mujoco_usd import validate_usd
from robodesc.validation.report import Status, ValidationReport
from robodesc.validation.usd_physics import validate_usd_physics

GRIPPER = ROOT / "examples/urdf/gripper_arm.urdf"


@pytest.fixture(scope="module")
def gripper(tmp_path_factory: pytest.TempPathFactory) -> tuple[Robot, str]:
    out = tmp_path_factory.mktemp("usd") / "r.usda"
    result = robodesc.compile_to_usd(GRIPPER, out, validate=False)
    return result.robot, out.read_text(encoding="utf-8")


def _check(robot: Robot, text: str, tmp_path: Path) -> ValidationReport:
    path = tmp_path / "r.usda"
    path.write_text(text, encoding="utf-8")
    return validate_usd_physics(robot, str(path))


def _failing(report: ValidationReport, name: str, element: str) -> str:
    rows = [c for c in report.failures if c.name == name and c.element == element]
    assert rows, f"no failing {name!r} row for {element}: {[(c.name, c.element) for c in report.failures]}"
    return rows[0].message


def _block(text: str, header: str) -> tuple[int, int]:
    """Start and end offsets of the prim whose ``def`` line contains ``header`` (braces matched)."""
    start = text.index(header)
    start = text.rindex("\n", 0, start) + 1
    depth, i = 0, text.index("{", start)
    while True:
        if text[i] == "{":
            depth += 1
        elif text[i] == "}":
            depth -= 1
            if depth == 0:
                return start, i + 1
        i += 1


def _edit_in(text: str, header: str, pattern: str, replace: str | Callable[[re.Match[str]], str]) -> str:
    """Apply ``re.sub(pattern, replace)`` once inside one prim's block."""
    start, end = _block(text, header)
    block, n = re.subn(pattern, replace, text[start:end], count=1)
    assert n == 1, (header, pattern)
    return text[:start] + block + text[end:]


def _all_pass(report: ValidationReport) -> None:
    assert report.ok, report.to_text()
    names = {c.name for c in report.checks if c.status is Status.PASS}
    assert {"bodies", "mass", "com", "inertia", "joints", "joint-type", "axis", "limits", "articulation", "fk"} <= names


def test_gripper_arm_passes(gripper: tuple[Robot, str], tmp_path: Path) -> None:
    robot, text = gripper
    report = _check(robot, text, tmp_path)
    _all_pass(report)
    assert report.consumer == "usd-physics"
    # float32 storage: errors sit at float32 rounding, far below the bounds.
    assert report.max_errors["mass"] < 1e-7
    assert report.max_errors["fk_position"] < 1e-6
    assert report.max_errors["limit"] < 1e-7


def test_spirit_passes(tmp_path: Path) -> None:
    if not SPIRIT_XACRO.exists():
        pytest.skip("shared corpus not installed")
    out = tmp_path / "spirit.usda"
    result = robodesc.compile_to_usd(SPIRIT_XACRO, out, validate=False, invalid_inertia="repair")
    report = validate_usd_physics(result.robot, str(out))
    _all_pass(report)
    assert next(c for c in report.checks if c.name == "bodies").element == f"{len(result.robot.links)} links"


def test_validate_usd_always_has_usd_physics_rows(gripper: tuple[Robot, str], tmp_path: Path) -> None:
    robot, text = gripper
    path = tmp_path / "r.usda"
    path.write_text(text, encoding="utf-8")
    report = validate_usd(robot, str(path))
    assert report.ok
    assert report.by_name("fk")[0].status is Status.PASS
    # mujoco-usd cannot be installed next to usd-core here: its row is a skip, not the whole report.
    mj = report.by_name("mujoco-usd")
    assert not mj or mj[0].status is Status.SKIP


def test_mass_off_by_one_percent(gripper: tuple[Robot, str], tmp_path: Path) -> None:
    robot, text = gripper
    bad = _edit_in(
        text, 'def Xform "upper_arm"', r"physics:mass = ([-0-9.e]+)", lambda m: f"physics:mass = {float(m[1]) * 1.01}"
    )
    report = _check(robot, bad, tmp_path)
    assert "USD mass 1.212" in _failing(report, "mass", "link 'upper_arm'")
    # The robot's total is off by the same 12 g: a row of its own.
    assert "USD (authored physics:mass): total" in _failing(report, "total mass", "robot 'gripper_arm'")
    assert [c.element for c in report.failures] == ["link 'upper_arm'", "robot 'gripper_arm'"]


def test_revolute_limit_in_radians(gripper: tuple[Robot, str], tmp_path: Path) -> None:
    robot, text = gripper

    def to_radians(m: re.Match[str]) -> str:
        return f"physics:{m[1]}Limit = {math.radians(float(m[2]))}"

    bad = text
    for which in ("lower", "upper"):
        bad = _edit_in(bad, 'PhysicsRevoluteJoint "elbow"', rf"physics:({which})Limit = ([-0-9.e]+)", to_radians)
    report = _check(robot, bad, tmp_path)
    message = _failing(report, "limits", "joint 'elbow'")
    assert "deg" in message and "126.05" in message
    assert {c.name for c in report.failures} == {"limits"}


def test_swapped_axis_token(gripper: tuple[Robot, str], tmp_path: Path) -> None:
    robot, text = gripper
    bad = _edit_in(text, 'PhysicsRevoluteJoint "shoulder_pitch"', r'physics:axis = "Y"', 'physics:axis = "Z"')
    report = _check(robot, bad, tmp_path)
    assert "USD axis Z" in _failing(report, "axis", "joint 'shoulder_pitch'")
    # The joint moves its subtree: FK names the first link below it.
    _failing(report, "fk", "link 'upper_arm'")


def test_deleted_body(gripper: tuple[Robot, str], tmp_path: Path) -> None:
    robot, text = gripper
    start, end = _block(text, 'def Xform "tool"')
    report = _check(robot, text[:start] + text[end:], tmp_path)
    _failing(report, "bodies", "link 'tool'")


def test_unreadable_file(tmp_path: Path) -> None:
    robot = robodesc.compile_to_usd(GRIPPER, tmp_path / "ok.usda", validate=False).robot
    report = validate_usd_physics(robot, str(tmp_path / "missing.usda"))
    assert not report.ok and report.failures[0].name == "usd-open"
