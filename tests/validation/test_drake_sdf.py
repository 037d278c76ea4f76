"""validate_sdf against Drake with a hand-written SDF (the SDF emitter is written elsewhere)."""

from __future__ import annotations

import pytest

from robodesc.frontends.load import load_string
from robodesc.validation.drake_sdf import drake_available, validate_sdf
from robodesc.validation.report import Status

pytestmark = pytest.mark.skipif(not drake_available(), reason="pydrake is not installed")

URDF = """<robot name="two">
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="b"><inertial><origin xyz="0.1 0 0.05" rpy="0.3 0 0"/><mass value="2"/>
    <inertia ixx="0.01" iyy="0.015" izz="0.02" ixy="0.001" ixz="0" iyz="0"/></inertial></link>
  <link name="c"><inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="hinge" type="revolute"><origin xyz="0 0 0.3" rpy="0 0 0.5"/><parent link="a"/><child link="b"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1.2" effort="1" velocity="1"/></joint>
  <joint name="slide" type="prismatic"><origin xyz="0.2 0 0" rpy="0.1 0.2 0.3"/><parent link="b"/><child link="c"/>
    <axis xyz="0 0 1"/><limit lower="-0.1" upper="0.3" effort="1" velocity="1"/></joint>
</robot>"""

SDF = """<?xml version="1.0"?>
<sdf version="1.9"><model name="two">
  <link name="a"><inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz>
    <ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia></inertial></link>
  <joint name="hinge" type="revolute"><pose relative_to="a">0 0 0.3 0 0 0.5</pose><parent>a</parent><child>b</child>
    <axis><xyz>0 1 0</xyz><limit><lower>-1</lower><upper>1.2</upper></limit></axis></joint>
  <link name="b"><pose relative_to="hinge"/><inertial><pose>0.1 0 0.05 0.3 0 0</pose><mass>2</mass>
    <inertia><ixx>0.01</ixx><iyy>0.015</iyy><izz>0.02</izz><ixy>0.001</ixy><ixz>0</ixz><iyz>0</iyz></inertia></inertial></link>
  <joint name="slide" type="prismatic"><pose relative_to="b">0.2 0 0 0.1 0.2 0.3</pose><parent>b</parent><child>c</child>
    <axis><xyz>0 0 1</xyz><limit><lower>-0.1</lower><upper>0.3</upper></limit></axis></joint>
  <link name="c"><pose relative_to="slide"/><inertial><mass>0.5</mass><inertia><ixx>0.001</ixx><iyy>0.001</iyy>
    <izz>0.001</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia></inertial></link>
</model></sdf>"""


def failing(text: str, name: str) -> list[str]:
    robot = load_string(URDF).robot
    report = validate_sdf(robot, text)
    return [c.element for c in report.checks if c.name == name and c.status is Status.FAIL]


def test_faithful_sdf_passes() -> None:
    report = validate_sdf(load_string(URDF).robot, SDF)
    assert report.ok, report.to_text()
    assert report.max_errors["fk_position"] < 1e-12
    assert report.max_errors["inertia"] < 1e-12
    assert {c.name for c in report.checks} >= {
        "drake-parse",
        "bodies",
        "mass",
        "com",
        "inertia",
        "axis",
        "limits",
        "fk",
    }


def test_sdf_mass_error_names_the_link() -> None:
    assert failing(SDF.replace("<mass>2</mass>", "<mass>2.02</mass>"), "mass") == ["link 'b'"]


def test_sdf_axis_error_names_the_joint() -> None:
    bad = SDF.replace("<xyz>0 1 0</xyz>", "<xyz>1 0 0</xyz>")
    assert failing(bad, "axis") == ["joint 'hinge'"]
    assert failing(bad, "fk") == ["link 'b'"]


def test_sdf_limit_error_names_the_joint() -> None:
    assert failing(SDF.replace("<upper>0.3</upper>", "<upper>0.35</upper>"), "limits") == ["joint 'slide'"]


def test_sdf_drake_refusal_is_a_failing_check() -> None:
    bad = SDF.replace("<parent>b</parent>", "<parent>nope</parent>")
    assert failing(bad, "drake-parse") == ["document"]
