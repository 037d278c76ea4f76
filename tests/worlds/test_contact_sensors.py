"""Contact sensors on the feet (--contact-sensors): decided once, written by every target, and each
proven by a simulation in which the sensors read the robot's weight when it stands."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import mujoco
import pytest
from lxml import etree

from robodesc.api import compile_for_isaac_sim, compile_to_mjcf, compile_to_sdf, compile_to_usd
from robodesc.cli import main
from robodesc.validation.physx_python import physx_python
from tests.conftest import EXAMPLES, SPIRIT_XACRO
from tests.worlds.physx_scripts import CONTACT

QUADRUPED = EXAMPLES / "quadruped.yaml"
FEET = ["FL_calf", "FR_calf", "RL_calf", "RR_calf"]  # the example quadruped's lowest link per leg
G = 9.81


_PLANE = """<sdf version="1.6"><world name="plane"><model name="ground"><static>true</static>
<pose>0 0 -0.05 0 0 0</pose><link name="l"><collision name="c"><geometry><box><size>10 10 0.1</size></box>
</geometry></collision></link></model></world></sdf>"""


def _weight(result) -> float:  # type: ignore[no-untyped-def]
    return sum(link.inertial.mass for link in result.robot.links if link.inertial and link.inertial.mass) * G


@pytest.mark.parametrize("source", [QUADRUPED, SPIRIT_XACRO], ids=["quadruped", "spirit"])
def test_mujoco_touch_sensors_read_the_weight(source: Path, tmp_path: Path) -> None:
    if not source.exists():
        pytest.skip("corpus not present")
    out = tmp_path / "robot.xml"
    result = compile_to_mjcf(str(source), str(out), contact_sensors=True)
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    touch = [i for i in range(model.nsensor) if model.sensor_type[i] == mujoco.mjtSensor.mjSENS_TOUCH]
    assert len(touch) == 4
    total = 0.0
    for step in range(2000):
        mujoco.mj_step(model, data)
        if step >= 1750:
            total += sum(float(data.sensordata[model.sensor_adr[i]]) for i in touch)
    assert total / 250 == pytest.approx(_weight(result), rel=0.01)


@pytest.mark.skipif(physx_python() is None, reason="no PhysX interpreter (tests/consumers/run.sh builds one)")
def test_physx_contact_reports_read_the_weight(tmp_path: Path) -> None:
    plane = tmp_path / "plane.world"
    plane.write_text(_PLANE)
    out = tmp_path / "quadruped.usda"
    result = compile_to_usd(str(QUADRUPED), str(out), contact_sensors=True, world=str(plane), fix_base=False)
    python = physx_python()
    assert python is not None
    paths = [f"/World/{result.robot.name}/{foot}" for foot in FEET]
    done = subprocess.run(
        [python, "-c", CONTACT, str(tmp_path / "quadruped_world.usda"), json.dumps(paths)],
        capture_output=True, text=True, timeout=600, check=False, env={**os.environ},
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    forces = json.loads(done.stdout.strip().splitlines()[-1])["forces"]
    assert sum(f[2] for f in forces) == pytest.approx(_weight(result), rel=0.02)
    assert all(f[2] > 0.1 * _weight(result) for f in forces)  # every foot carries its share


def test_sdf_names_the_foot_collisions(tmp_path: Path) -> None:
    out = tmp_path / "quadruped.sdf"
    compile_to_sdf(str(QUADRUPED), str(out), contact_sensors=True)
    root = etree.parse(str(out)).getroot()
    sensors = root.findall(".//sensor[@type='contact']")
    assert sorted(s.getparent().get("name") for s in sensors) == FEET
    for sensor in sensors:
        link = sensor.getparent()
        named = {c.text for c in sensor.findall("contact/collision")}
        assert named and named <= {c.get("name") for c in link.findall("collision")}


def test_isaac_lab_module_lists_the_sensors(tmp_path: Path) -> None:
    out = tmp_path / "quadruped_isaac"
    compile_for_isaac_sim(str(QUADRUPED), str(out), contact_sensors=True)
    text = (out / "quadruped_isaaclab.py").read_text()
    assert "ContactSensorCfg" in text and "'contact_sensors': ['FL_calf', 'FR_calf', 'RL_calf', 'RR_calf']" in text
    usd = (out / "quadruped.usda").read_text()
    assert usd.count('"PhysxContactReportAPI"') + usd.count(', "PhysxContactReportAPI"') >= 1


def test_a_regex_and_its_refusals(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "robot.xml"
    assert main(["compile", str(QUADRUPED), "-t", "mjcf", "-o", str(out), "--contact-sensors", "F._calf", "-q"]) == 0
    assert out.read_text().count("<touch ") == 2
    for bad, said in (("(", "not a regular expression"), ("nothing_here", "matches no link")):
        code = main(["compile", str(QUADRUPED), "-t", "mjcf", "-o", str(tmp_path / "x.xml"), "--contact-sensors", bad])
        assert code == 2 and said in capsys.readouterr().err
    arm = EXAMPLES / "urdf" / "gripper_arm.urdf"
    result = compile_to_mjcf(str(arm), str(tmp_path / "arm.xml"), contact_sensors=True)
    assert any(f.code == "contact-sensors-no-feet" for f in result.findings)
