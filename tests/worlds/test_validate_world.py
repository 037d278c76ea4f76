"""``validate`` with a world (validation/world_check.py): MuJoCo finds the ground of scene.xml where the
placement put it, usd-core composes the world stage with its terrain and the robot at the spawn;
a ground that is elsewhere fails the row."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from robodesc.api import check
from robodesc.cli import main
from robodesc.validation.report import Status, ValidationReport
from robodesc.validation.world_check import check_mjcf_ground
from tests.conftest import EXAMPLES

QUADRUPED = EXAMPLES / "quadruped.yaml"
STEPS = EXAMPLES / "worlds" / "steps.world"


def _row(report: ValidationReport | None, name: str) -> tuple[Status, str]:
    assert report is not None
    (row,) = [c for c in report.checks if c.name == name]
    return row.status, row.message


def test_validate_mjcf_finds_the_ground(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["validate", str(QUADRUPED), "-t", "mjcf", "--world", str(STEPS), "--spawn=-1,0", "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 0
    (row,) = [c for c in doc["validation"]["checks"] if c["name"] == "world-ground"]
    assert row["status"] == "pass" and row["error"] < 1e-6


def test_validate_usd_composes_the_world_stage() -> None:
    result = check(str(QUADRUPED), "usd", world=str(STEPS), spawn=(0.5, 0.0))
    status, message = _row(result.validation, "world-stage")
    assert status is Status.PASS, message
    assert "1 static triangle-mesh terrain" in message and "13 bodies" in message


def test_a_ground_elsewhere_fails(tmp_path: Path) -> None:
    """The same scene, told the step's top is 5 cm higher than it is: the row fails and says where."""
    result = check(str(QUADRUPED), "mjcf", world=str(STEPS))
    assert _row(result.validation, "world-ground")[0] is Status.PASS
    from robodesc.api import compile_to_mjcf

    compile_to_mjcf(str(QUADRUPED), str(tmp_path / "robot.xml"), world=str(STEPS))
    report = ValidationReport(robot="quadruped", target="mjcf", consumer="mujoco")
    check_mjcf_ground(str(tmp_path / "scene.xml"), [(0.0, 0.0, 0.05)], report)
    status, message = _row(report, "world-ground")
    assert status is Status.FAIL and "0.05 m from the placed terrain's" in message
