"""usd-core's physics parser recurses once per joint: a 50,000-link chain overflowed the main
thread's stack (SIGSEGV, issue 26). It runs on a thread with a stack for the tree's depth, and past
the largest one validation says so instead of crashing."""

from __future__ import annotations

from pathlib import Path

import pytest

import robodesc
import robodesc.validation.usd_physics as usd_physics
from robodesc.validation.report import Status

ARM = Path(__file__).resolve().parents[2] / "examples" / "urdf" / "gripper_arm.urdf"


def test_stack_grows_with_depth() -> None:
    assert usd_physics.parser_stack_size(10) == usd_physics.PARSER_MIN_STACK
    # 50,000 joints: the 8 MiB main-thread stack was not enough, 1 GiB was; 4 KiB per joint leaves room.
    size = usd_physics.parser_stack_size(50_000)
    assert size is not None and size >= 50_000 * 4096
    assert usd_physics.parser_stack_size(10**8) is None


def test_parse_on_its_own_thread_matches(tmp_path: Path) -> None:
    result = robodesc.compile_to_usd(str(ARM), tmp_path / "arm.usda")
    assert result.validation is not None and result.validation.ok


def test_too_deep_is_said_not_crashed(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(usd_physics, "PARSER_MAX_STACK", 1)
    result = robodesc.compile_to_usd(str(ARM), tmp_path / "arm.usda")
    report = result.validation
    assert report is not None and report.ok
    rows = [c for c in report.checks if c.name == "usd-open"]
    assert rows and rows[0].status is Status.WARN and "joints deep" in rows[0].message
