"""The same SDF in Drake (libsdformat's frame rules) and in robodesc's IR of it: every body's mass,
centre of mass and inertia about it, in the root's frame, at random joint values."""

from __future__ import annotations

from pathlib import Path

import pytest

from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions
from tests.conftest import SPIRIT_XACRO
from tests.sdf_in.drake_check import compare_in_drake
from tests.sdf_in.test_round_trip import GOLDENS, _golden

pytest.importorskip("pydrake")
DATA = Path(__file__).parent / "data"
MODELS = DATA / "models"


def test_feature_model_in_drake(tmp_path: Path) -> None:
    robot = load_path(str(DATA / "feature_bot.sdf"), LoadOptions(model_path=(str(MODELS),))).robot
    # Drake resolves model:// through ROS packages only: give it the included file itself.
    finger = (MODELS / "finger_part" / "model.sdf").resolve()
    text = (DATA / "feature_bot.sdf").read_text().replace("model://finger_part", str(finger))
    copy = tmp_path / "feature_bot.sdf"
    copy.write_text(text)
    result = compare_in_drake(str(copy), robot)
    assert result.problems == []
    # Every body but the universal joint's cross (robodesc's own): 8 links.
    assert result.bodies == 8
    assert result.max_com_error < 1e-12 and result.max_inertia_error < 1e-12


@pytest.mark.parametrize("name", [*sorted(GOLDENS), "spirit.sdf"])
def test_goldens_in_drake(name: str, tmp_path: Path) -> None:
    if name == "spirit.sdf" and not SPIRIT_XACRO.exists():
        pytest.skip("Spirit is not in the shared corpus")
    path = _golden(name, tmp_path)
    robot = load_path(str(path)).robot
    result = compare_in_drake(str(path), robot)
    assert result.problems == [] and result.bodies == len(robot.links)
    assert result.max_com_error < 1e-12


def test_bundled_example_in_drake() -> None:
    example = Path(__file__).resolve().parents[2] / "examples" / "sdf" / "pan_tilt"
    robot = load_path(str(example)).robot
    assert robot.fixed_base is True and {j.name: j.drive.stiffness for j in robot.joints if j.drive} == {
        "pan": 4.0,
        "tilt": 3.0,
    }
    result = compare_in_drake(str(example / "model.sdf"), robot)
    assert result.problems == [] and result.bodies == 3 and result.max_com_error < 1e-12
