"""Validation never blames robodesc for what it carried faithfully (issue 26): a planar joint (MuJoCo
expands it into three joints), a composition link of mass 0, a world joint with parent and child
swapped. Each compiles with default validation, exit 0."""

from __future__ import annotations

from pathlib import Path

import pytest

import robodesc
from robodesc.cli import main

HERE = Path(__file__).parent / "source_defects"


@pytest.mark.parametrize("name", ["planar.urdf", "world_swapped.urdf", "mass_zero.yaml"])
def test_default_validation_passes(name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out.urdf"
    assert main(["compile", str(HERE / name), "-o", str(out)]) == 0, capsys.readouterr().err
    assert out.exists()
    assert "robodesc's fault" not in capsys.readouterr().err


def test_planar_joint_is_compared_as_mujocos_three_joints(tmp_path: Path) -> None:
    result = robodesc.compile_to_urdf(str(HERE / "planar.urdf"), tmp_path / "p.urdf")
    report = result.validation
    assert report is not None and report.ok
    assert not [c for c in report.checks if "the robot does not" in c.message]


def test_planar_joint_with_a_wrong_normal_fails(tmp_path: Path) -> None:
    from robodesc.validation.mujoco_urdf import validate_urdf_text

    robot = robodesc.load(str(HERE / "planar.urdf"))
    text = robodesc.compile_to_urdf(robot, validate=False).text
    assert text is not None and 'xyz="0 0 1"' in text
    report = validate_urdf_text(robot, text.replace('<axis xyz="0 0 1"/>', '<axis xyz="1 0 0"/>'))
    assert any(c.name == "axis" for c in report.failures)


def test_mass_zero_link_gets_a_zero_inertia(tmp_path: Path) -> None:
    robodesc.compile_to_urdf(str(HERE / "mass_zero.yaml"), tmp_path / "m.urdf", validate=False)
    text = (tmp_path / "m.urdf").read_text()
    assert '<mass value="0"/>' in text
    assert '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>' in text


def test_world_joint_swapped_is_a_source_defect_warning(tmp_path: Path) -> None:
    result = robodesc.compile_to_urdf(str(HERE / "world_swapped.urdf"), tmp_path / "w.urdf")
    report = result.validation
    assert report is not None and report.ok
    assert any(c.name == "parents" and "swapped" in c.message for c in report.checks)
