"""URDF -> SDF (robodesc's SDF target) -> IR -> URDF equals the original: masses, inertias, COMs,
joint types and limits, FK at random joint values. On the bundled fixtures, Quad-SDK's Spirit and Go2,
and robodesc's SDF goldens read back against the robots they were written from."""

from __future__ import annotations

from pathlib import Path

import pytest

import robodesc
from robodesc.frontends.load import load_path
from robodesc.ir.model import Robot
from tests.conftest import GO2_XACRO, SPIRIT_XACRO
from tests.sdf import fixtures as fx
from tests.sdf_in.compare import differences

SOURCES = {
    "arm": fx.DATA / "arm.urdf",
    "gripper": fx.DATA / "gripper.urdf",
    "sensor_bot": fx.DATA / "sensor_bot.urdf",
    "spirit": SPIRIT_XACRO,
    "go2": GO2_XACRO,
}


@pytest.mark.parametrize("name", sorted(SOURCES))
def test_urdf_sdf_ir_urdf(name: str, tmp_path: Path) -> None:
    source = SOURCES[name]
    if not source.exists():
        pytest.skip(f"{source} is not in the shared corpus")
    original = load_path(str(source)).robot
    sdf = tmp_path / "robot.sdf"
    robodesc.compile_to(str(source), "sdf", str(sdf))
    read = load_path(str(sdf)).robot
    problems, fk = differences(original, read)
    assert problems == [] and fk < 1e-9
    back = tmp_path / "back.urdf"
    robodesc.compile_to(str(sdf), "urdf", str(back))
    problems, fk = differences(original, load_path(str(back)).robot)
    assert problems == [] and fk < 1e-9


def _golden(name: str, tmp_path: Path) -> Path:
    """A golden's SDF without the findings report the golden test appends after it."""
    text = (fx.GOLDEN / name).read_text()
    path = tmp_path / name
    path.write_text(text[: text.index("</sdf>") + len("</sdf>")] + "\n")
    return path


GOLDENS = {
    "arm_fixed.sdf": fx.arm,
    "arm_model_frame.sdf": fx.arm,
    "gripper_1_10.sdf": fx.gripper,
    "gripper_1_11.sdf": fx.gripper,
    "sensor_bot.sdf": fx.sensor_bot,
    "sensor_bot_classic.sdf": fx.sensor_bot,
}


@pytest.mark.parametrize("name", sorted(GOLDENS))
def test_golden_reads_back(name: str, tmp_path: Path) -> None:
    original: Robot = GOLDENS[name]()
    read = load_path(str(_golden(name, tmp_path))).robot
    problems, fk = differences(original, read)
    assert problems == [] and fk < 1e-9
    if name.startswith(("arm", "gripper")):
        assert read.fixed_base is True  # the golden's world_joint
    if name.startswith("sensor_bot"):
        assert sorted(s.name for s in read.sensors) == sorted(s.name for s in original.sensors)
        assert {s.name: s.type for s in read.sensors} == {s.name: s.type for s in original.sensors}


def test_spirit_golden_reads_back(tmp_path: Path) -> None:
    if not SPIRIT_XACRO.exists():
        pytest.skip("Spirit is not in the shared corpus")
    read = load_path(str(_golden("spirit.sdf", tmp_path))).robot
    problems, fk = differences(fx.spirit(), read)
    assert problems == [] and fk < 1e-9
    toes = [c.contact for link in read.links for c in link.collisions if link.name.startswith("toe")]
    assert toes and all(c is not None and c.mu is not None for c in toes)
