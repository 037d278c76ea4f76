"""Outputs are written only inside the output path, never through a link that leaves it; and a mesh
reached through a symlinked folder outside the robot's roots is read into no output (issue 26)."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

import robodesc
from robodesc.cli import main
from tests.conftest import EXAMPLES

ARM = EXAMPLES / "urdf" / "gripper_arm.urdf"


def test_copy_meshes_never_writes_through_a_meshes_symlink(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out, victim = tmp_path / "out", tmp_path / "victim"
    out.mkdir()
    victim.mkdir()
    (victim / "finger.stl").write_text("precious")
    os.symlink(victim, out / "meshes")
    assert main(["compile", str(ARM), "--copy-meshes", "-o", str(out / "arm.urdf")]) == 2
    assert "symlink" in capsys.readouterr().err
    assert sorted(os.listdir(victim)) == ["finger.stl"]
    assert (victim / "finger.stl").read_text() == "precious"
    assert not (out / "arm.urdf").exists()


def _robot_behind_a_symlinked_folder(tmp_path: Path) -> Path:
    robot, elsewhere = tmp_path / "robot", tmp_path / "elsewhere"
    robot.mkdir()
    elsewhere.mkdir()
    shutil.copy(EXAMPLES / "urdf" / "meshes" / "finger.stl", elsewhere / "finger.stl")
    os.symlink(elsewhere, robot / "meshes")
    text = ARM.read_text().replace("package://robodesc_examples/meshes", "meshes")
    assert "meshes/finger.stl" in text
    (robot / "arm.urdf").write_text(text)
    return robot / "arm.urdf"


def test_usd_and_copy_meshes_apply_one_rule_to_a_symlinked_mesh_folder(tmp_path: Path) -> None:
    src = _robot_behind_a_symlinked_folder(tmp_path)
    usd = robodesc.compile_to_usd(str(src), tmp_path / "arm.usda")
    assert "usd-mesh-not-read" in {f.code for f in usd.findings}
    assert "def Mesh" not in (tmp_path / "arm.usda").read_text()  # the finger meshes were not embedded
    plain = robodesc.compile_to_usd(str(ARM), tmp_path / "plain.usda", validate=False)
    assert "usd-mesh-not-read" not in {f.code for f in plain.findings}
    assert "def Mesh" in (tmp_path / "plain.usda").read_text()
    copied = robodesc.compile_to_urdf(str(src), tmp_path / "c" / "arm.urdf", copy_meshes=True)
    assert "mesh-not-copied" in {f.code for f in copied.findings}
    assert not (tmp_path / "c" / "meshes").exists()
