"""Every URDF robodesc writes for ROS loads in urdfdom, through Pinocchio (which parses URDF with
urdfdom): ``--ros2`` and the Isaac folder for every input, ``-t urdf`` for compositions; the
examples, the compositions of ``tests/compose``, the fuzz seeds and a pybullet-style file with
capsules and a spherical joint. The test tier runs ``check_urdf`` itself on more (run.sh)."""

from __future__ import annotations

import re
from pathlib import Path

import pinocchio as pin
import pytest

import robodesc
from robodesc.emit.urdf.writer import UrdfOptions, emit_urdf
from tests.conftest import EXAMPLES, ROOT

FIXTURES = Path(__file__).parent / "fixtures"
PYBULLET = FIXTURES / "pybullet_ball.urdf"
COMPOSITIONS = sorted(
    [p for p in EXAMPLES.glob("*.*") if p.suffix in (".yaml", ".holo", ".py")]
    + list((ROOT / "tests" / "compose" / "holo").glob("*.holo"))
    + [p for p in (ROOT / "tests" / "fuzz" / "seeds").glob("*.*") if p.suffix in (".yaml", ".holo")]
)
URDFS = [EXAMPLES / "urdf" / "gripper_arm.urdf", ROOT / "tests" / "fuzz" / "seeds" / "arm.urdf", PYBULLET]


def _ids(paths: list[Path]) -> list[str]:
    return [str(p.relative_to(ROOT)) for p in paths]


def _loads(urdf: Path) -> pin.Model:
    try:
        return pin.buildModelFromXML(urdf.read_text(encoding="utf-8"))
    except (ValueError, RuntimeError) as exc:  # urdfdom's refusal
        raise AssertionError(f"urdfdom (Pinocchio) refuses {urdf.name}: {exc}") from None


@pytest.mark.parametrize("source", COMPOSITIONS + URDFS, ids=_ids(COMPOSITIONS + URDFS))
def test_ros2_urdf_loads_in_urdfdom(source: Path, tmp_path: Path) -> None:
    result = robodesc.compile_for_ros2(str(source), tmp_path / "ros2", validate=False)
    (urdf,) = (tmp_path / "ros2").glob("*.urdf")
    model = _loads(urdf)
    assert model.nq >= sum(j.type.dof for j in result.robot.joints if j.type.value != "floating")


@pytest.mark.parametrize("source", COMPOSITIONS, ids=_ids(COMPOSITIONS))
def test_composition_urdf_loads_in_urdfdom(source: Path, tmp_path: Path) -> None:
    robodesc.compile_to_urdf(str(source), tmp_path / "out.urdf", validate=False)
    _loads(tmp_path / "out.urdf")


@pytest.mark.parametrize("source", [EXAMPLES / "isaac_arm.yaml", PYBULLET], ids=["isaac_arm", "pybullet_ball"])
def test_isaac_urdf_loads_in_urdfdom(source: Path, tmp_path: Path) -> None:
    result = robodesc.compile_for_isaac_sim(str(source), tmp_path / "isaac", validate=False)
    _loads(Path(result.files["urdf"]))


def test_missing_effort_gets_documented_defaults_with_a_warning(tmp_path: Path) -> None:
    # tests/fuzz/seeds/arm.holo: a hinge with limits and no effort or velocity (issue 26).
    src = ROOT / "tests" / "fuzz" / "seeds" / "arm.holo"
    result = robodesc.compile_to_urdf(str(src), tmp_path / "a.urdf", validate=False)
    warned = [f for f in result.findings if f.code == "urdf-limit-defaults"]
    assert warned and "Arm_joint" in warned[0].message
    text = (tmp_path / "a.urdf").read_text()
    assert 'effort="1000"' in text and 'velocity="100"' in text
    # Overridable: UrdfOptions.default_effort / default_velocity (and the same fields of Ros2Options).
    text = emit_urdf(result.robot, UrdfOptions(default_effort=5.0, default_velocity=2.0))
    assert 'effort="5"' in text and 'velocity="2"' in text
    robodesc.compile_for_ros2(str(src), tmp_path / "ros2", validate=False, default_effort=7.0, default_velocity=3.0)
    (urdf,) = (tmp_path / "ros2").glob("*.urdf")
    assert 'effort="7"' in urdf.read_text() and 'velocity="3"' in urdf.read_text()


def test_pybullet_ros2_splits_capsules_and_ball_joints(tmp_path: Path) -> None:
    result = robodesc.compile_for_ros2(str(PYBULLET), tmp_path / "ros2")
    codes = {f.code for f in result.findings}
    assert {"urdf-capsule-split", "urdf-spherical-split"} <= codes
    (urdf,) = (tmp_path / "ros2").glob("*.urdf")
    text = urdf.read_text()
    assert "<capsule" not in text and 'type="spherical"' not in text
    model = _loads(urdf)
    assert {"chest_x", "chest_y", "chest_z", "elbow"} <= set(model.names)
    controllers = (tmp_path / "ros2" / "controllers.yaml").read_text()
    assert "chest_x" in controllers and "elbow" in controllers
    # Validation (MuJoCo) passed against the three revolute joints.
    assert result.validation is not None and result.validation.ok


def test_pybullet_round_trip_keeps_extensions_and_says_ros_will_not_load_it(tmp_path: Path) -> None:
    result = robodesc.compile_to_urdf(str(PYBULLET), tmp_path / "out.urdf")
    warned = [f for f in result.findings if f.code == "urdf-not-ros"]
    assert warned and "urdfdom" in warned[0].message
    text = (tmp_path / "out.urdf").read_text()
    assert "<capsule" in text and 'type="spherical"' in text
    with pytest.raises((ValueError, RuntimeError)):
        pin.buildModelFromXML(text)


def test_mjcf_input_urdf_is_written_for_ros(tmp_path: Path) -> None:
    # An MJCF model's URDF is a new file, not a round trip of a pybullet URDF: urdfdom must load it
    # (menagerie go1's 24 capsules made urdfdom drop every collision of 9 links). The fixture has
    # capsules, a ball joint and a <connect> loop (a <loop_joint type="spherical">, which the URDF
    # check once mistook for the ball joint itself and compared the unsplit robot).
    source = ROOT / "tests" / "mjcf_in" / "data" / "features.xml"
    result = robodesc.compile_to_urdf(str(source), tmp_path / "out.urdf")
    assert result.validation is not None and result.validation.ok, result.validation.to_text()
    text = (tmp_path / "out.urdf").read_text(encoding="utf-8")
    assert "<capsule" not in text
    assert 'type="spherical"' in text  # the loop joint stays, written as <loop_joint>
    model = _loads(tmp_path / "out.urdf")
    assert {"ball_x", "ball_y", "ball_z"} <= set(model.names)
    codes = {f.code for f in result.findings}
    assert {"urdf-capsule-split", "urdf-spherical-split"} <= codes and "urdf-not-ros" not in codes


def test_urdf_named_xml_is_still_a_round_trip(tmp_path: Path) -> None:
    # A URDF saved as .xml keeps its capsules (pybullet reads them), as a .urdf does.
    urdf = tmp_path / "capsule.xml"
    urdf.write_text(PYBULLET.read_text(encoding="utf-8"), encoding="utf-8")
    result = robodesc.compile_to_urdf(str(urdf), tmp_path / "out.urdf", validate=False)
    assert "<capsule" in (tmp_path / "out.urdf").read_text(encoding="utf-8")
    assert "urdf-not-ros" in {f.code for f in result.findings}


def test_continuous_joint_limit_gets_the_missing_velocity(tmp_path: Path) -> None:
    # An unlimited MJCF hinge driven by a servo with a forcerange (menagerie Gen3's joint_1) is a
    # continuous joint whose <limit> has an effort only: urdfdom refused the whole file ("limit has
    # no velocity"). The missing number gets the documented default, with the warning.
    mjcf = tmp_path / "wheel.xml"
    mjcf.write_text(
        """<mujoco model="wheel">
  <worldbody>
    <body name="base">
      <geom type="box" size="0.1 0.1 0.1" mass="1"/>
      <body name="rotor" pos="0 0 0.2">
        <joint name="spin" axis="0 0 1"/>
        <geom type="cylinder" size="0.05 0.01" mass="0.2"/>
      </body>
    </body>
  </worldbody>
  <actuator><position name="spin" joint="spin" kp="10" forcerange="-7 7"/></actuator>
</mujoco>
""",
        encoding="utf-8",
    )
    result = robodesc.compile_to_urdf(str(mjcf), tmp_path / "out.urdf")
    assert result.validation is not None and result.validation.ok
    text = (tmp_path / "out.urdf").read_text(encoding="utf-8")
    assert re.search(r'type="continuous">(?:(?!</joint>).)*<limit effort="7" velocity="100"/>', text, re.DOTALL)
    model = _loads(tmp_path / "out.urdf")
    assert model.effortLimit[model.joints[model.getJointId("spin")].idx_v] == pytest.approx(7.0)
    warned = [f for f in result.findings if f.code == "urdf-limit-defaults"]
    assert warned and "spin" in warned[0].message
