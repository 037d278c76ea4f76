"""The MJCF default base (docs/mjcf.md, "Defaults and why"): a robot on three or more legs floats and
stands on them from its home keyframe in scene.xml; an arm stays welded; --fix-base still wins."""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pytest

from robodesc.api import compile_to_mjcf
from tests.conftest import EXAMPLES, GO2_XACRO, SPIRIT_XACRO
from tests.mjcf.helpers import stand_from_home


def _stand(scene: Path, seconds: float) -> tuple[float, float]:
    """The lowest up·z of the root from ``home`` and its final height."""
    worst, position = stand_from_home(scene, seconds)
    return worst, float(position[2])


@pytest.mark.parametrize("source", [SPIRIT_XACRO, GO2_XACRO], ids=["spirit", "go2"])
def test_quadruped_floats_and_stands_from_home(source: Path, tmp_path: Path) -> None:
    if not source.exists():
        pytest.skip("corpus not present")
    out = tmp_path / "robot.xml"
    result = compile_to_mjcf(str(source), str(out))
    assert any(f.code == "base-floating" for f in result.findings)
    model = mujoco.MjModel.from_xml_path(str(out))
    assert model.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE
    home = model.key_qpos[0]
    assert np.count_nonzero(home[7:]) >= 8  # hips and knees bent: the stance, not the zero pose
    upright, height = _stand(tmp_path / "scene.xml", 2.0)
    assert upright >= 0.99
    assert height > 0.1  # on its feet, not on its belly


def test_arm_stays_welded(tmp_path: Path) -> None:
    out = tmp_path / "robot.xml"
    result = compile_to_mjcf(
        str(EXAMPLES / "urdf/gripper_arm.urdf"), str(out), package_paths={"robodesc_examples": str(EXAMPLES / "urdf")}
    )
    assert not any(f.code == "base-floating" for f in result.findings)
    model = mujoco.MjModel.from_xml_path(str(out))
    assert mujoco.mjtJoint.mjJNT_FREE not in list(model.jnt_type)


def test_fix_base_given_welds_a_quadruped(tmp_path: Path) -> None:
    if not SPIRIT_XACRO.exists():
        pytest.skip("corpus not present")
    out = tmp_path / "robot.xml"
    compile_to_mjcf(str(SPIRIT_XACRO), str(out), fix_base=True)
    model = mujoco.MjModel.from_xml_path(str(out))
    assert mujoco.mjtJoint.mjJNT_FREE not in list(model.jnt_type)
