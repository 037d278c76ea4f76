"""Golden URDF output for representative inputs (regenerate with ``pytest --update-golden``)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

import robodesc
from robodesc.emit.common.paths import PathMode
from robodesc.emit.urdf import UrdfOptions, emit_urdf
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions, MissingMesh
from tests.conftest import EXAMPLES, GO2_XACRO, SPIRIT_XACRO, Golden


def _example_copy(tmp_path: Path) -> Path:
    """The example package copied beside the output, so relative mesh paths do not depend on where
    the checkout lives."""
    shutil.copytree(EXAMPLES / "urdf", tmp_path / "robodesc_examples")
    return tmp_path / "robodesc_examples" / "gripper_arm.urdf"


def test_gripper_arm(golden: Golden, tmp_path: Path) -> None:
    out = tmp_path / "out" / "gripper_arm.urdf"
    result = robodesc.compile_to_urdf(_example_copy(tmp_path), out)
    golden.check("gripper_arm.urdf", out.read_text())
    assert result.text == out.read_text()


def test_gripper_arm_package_paths(golden: Golden, tmp_path: Path) -> None:
    robot = load_path(str(_example_copy(tmp_path))).robot
    text = emit_urdf(robot, UrdfOptions(path_mode=PathMode.PACKAGE, out_dir=str(tmp_path / "out")))
    golden.check("gripper_arm.package.urdf", text)


@pytest.mark.parametrize("xacro", [SPIRIT_XACRO, GO2_XACRO], ids=["spirit", "go2"])
def test_quadsdk_xacro(xacro: Path, golden: Golden, tmp_path: Path) -> None:
    out = tmp_path / "robot.urdf"
    robodesc.compile_to_urdf(xacro, out, missing_mesh="warn", invalid_inertia="warn")
    text = out.read_text()
    golden.check(f"{xacro.name.split('.')[0]}.urdf", _portable(text, out.parent))


def _portable(text: str, out_dir: Path) -> str:
    """Rewrite relative mesh paths (which depend on the test's tmp folder) relative to the corpus."""
    import os
    import re

    corpus = (Path(__file__).resolve().parents[3] / "shared" / "corpus").resolve()

    def fix(match: re.Match[str]) -> str:
        if "://" in match.group(1):  # a missing mesh keeps its URI
            return match.group(0)
        path = (out_dir / match.group(1)).resolve()
        return f'filename="$CORPUS/{os.path.relpath(path, corpus)}"'

    return re.sub(r'(?<=<mesh )filename="([^"]+)"', fix, text)


def test_missing_mesh_policies_on_go2() -> None:
    for policy, kept in (("warn", True), ("drop", False), ("primitive", False)):
        loaded = load_path(str(GO2_XACRO), LoadOptions(missing_mesh=MissingMesh(policy)))
        body = loaded.robot.link("body")
        assert (len(body.visuals) == 1 and type(body.visuals[0].geometry).__name__ == "Mesh") == kept
        assert any(
            f.code == "missing-mesh" and "body.dae" in f.message and f.element == "link 'body'" for f in loaded.findings
        )


def test_golden_numbers_compare_at_the_stated_tolerance() -> None:
    from tests.conftest import GOLDEN_REL_TOL, same_within_rounding

    # The 15th digit differs between OpenBLAS kernels; a changed value or word does not pass.
    assert GOLDEN_REL_TOL == 1e-12
    assert same_within_rounding('ixx="3.3500412129993215e-08"', 'ixx="3.3500412129993426e-08"')
    assert not same_within_rounding('ixx="3.35e-08"', 'ixx="3.36e-08"')
    assert not same_within_rounding('ixx="1"', 'iyy="1"')
