"""The YAML format's units, templates and anchors, and the Python builder."""

from __future__ import annotations

import math

import pytest

from robodesc.frontends.compose.builder import Part, RobotBuilder, pose
from robodesc.frontends.compose.shapes import box, cylinder, sphere
from robodesc.frontends.compose.units import deg, mm
from robodesc.frontends.compose.yaml_format import load_yaml_text
from robodesc.ir.diagnostics import BrokenReferenceError, Findings, ParseError
from robodesc.ir.model import JointType
from robodesc.ir.transforms import forward_kinematics

PENDULUM = """
robot: pendulum
{units}
links:
  base: {{geometry: {{box: [0.1, 0.1, 0.1]}}, mass: 1}}
  bob: {{geometry: {{sphere: 0.05}}, mass: 0.2, pose: {{xyz: [0, 0, -0.5], rpy: [0, {pitch}, 0]}}}}
joints:
  swing:
    type: revolute
    parent: base
    child: bob
    axis: y
    limits: {{lower: {lo}, upper: {hi}, velocity: {vel}}}
"""


def test_units_are_stated_once_and_converted() -> None:
    in_deg = load_yaml_text(PENDULUM.format(units="units: {angle: deg}", pitch=90, lo=-45, hi=45, vel=180), "p.yaml")
    findings = Findings()
    in_rad = load_yaml_text(
        PENDULUM.format(units="", pitch=math.pi / 2, lo=-math.pi / 4, hi=math.pi / 4, vel=math.pi),
        "p.yaml",
        None,
        findings,
    )
    for robot in (in_deg, in_rad):
        swing = robot.joint("swing")
        assert swing.limit is not None
        assert swing.limit.lower == pytest.approx(-math.pi / 4) and swing.limit.velocity == pytest.approx(math.pi)
        assert swing.origin is not None and swing.origin.rpy[1] == pytest.approx(math.pi / 2)
    assert [f.code for f in findings] == ["default-units"]


def test_templates_overrides_and_anchors() -> None:
    robot = load_yaml_text(
        """
robot: hexapod_fragment
units: {angle: deg}
x-common: &common {mass: 0.1, color: red}
links:
  body: {geometry: {box: [0.3, 0.2, 0.05]}, mass: 2}
templates:
  leg:
    links:
      coxa: {<<: *common, geometry: {cylinder: {radius: 0.01, length: 0.05}}}
      tibia: {<<: *common, geometry: {box: [0.02, 0.02, 0.1]}, pose: [0, 0, -0.05]}
    joints:
      hip: {type: revolute, parent: body, child: coxa, axis: z, limits: {lower: -30, upper: 30}}
      knee: {type: revolute, parent: coxa, child: tibia, axis: x, limits: {lower: -60, upper: 60}}
use:
  - {template: leg, prefix: a_, overrides: {links: {coxa: {pose: [0.1, 0.1, 0]}}}}
  - template: leg
    suffix: _b
    overrides:
      links: {coxa: {pose: [-0.1, 0.1, 0], mass: 0.3}}
      joints: {knee: {limits: {upper: 10}}}
""",
        "hex.yaml",
    )
    assert [link.name for link in robot.links] == ["body", "a_coxa", "a_tibia", "coxa_b", "tibia_b"]
    assert robot.link("coxa_b").inertial.mass == 0.3  # type: ignore[union-attr]
    assert robot.link("a_tibia").inertial.mass == 0.1  # type: ignore[union-attr]
    knee_b = robot.joint("knee_b")
    assert knee_b.parent == "coxa_b" and knee_b.limit is not None
    assert knee_b.limit.upper == pytest.approx(math.radians(10)) and knee_b.limit.lower == pytest.approx(
        -math.radians(60)
    )
    assert robot.joint("a_hip").parent == "body"
    fk = forward_kinematics(robot)
    assert fk["tibia_b"][:3, 3] == pytest.approx([-0.1, 0.1, -0.05])


def test_builder_in_a_few_lines() -> None:
    b = RobotBuilder("arm")
    b.link("base", box(0.2, 0.2, 0.1), mass=5.0, color="#333")
    b.link("upper", cylinder(0.03, 0.4), mass=1.0, pose=(0, 0, 0.25), frame="world")
    b.link("hand", Part(sphere(0.04), origin=(0, 0, 0.02), density=1000.0), pose=(0, 0, 0.45), frame="world")
    b.link("slider", box(0.02, 0.02, 0.02), mass=0.1)
    b.joint("shoulder", "revolute", "base", "upper", axis="z", limits=deg(-90, 90), effort=10, velocity=2)
    b.joint("wrist", "hinge", "upper", "hand", axis=(0, 1, 0), lower=-45, upper=45, unit="deg", armature=0.01)
    b.joint("slide", "slider", "hand", "slider", axis="x", limits=mm(0, 50), origin=pose(xyz=(0, 0, 0.05)))
    b.frame("tcp", "hand", (0, 0, 0.06))
    b.sensor("wrist_ft", "force_torque", "hand")
    b.actuator("shoulder", interface="hardware_interface/EffortJointInterface", reduction=100)
    robot = b.build()
    assert robot.joint("shoulder").origin.xyz == (0.0, 0.0, 0.25)  # type: ignore[union-attr]
    assert robot.joint("wrist").origin.xyz == (0.0, 0.0, 0.2)  # type: ignore[union-attr]
    assert robot.joint("wrist").type is JointType.REVOLUTE and robot.joint("wrist").armature == 0.01
    assert robot.joint("wrist").limit.upper == pytest.approx(math.pi / 4)  # type: ignore[union-attr]
    assert robot.joint("slide").limit.upper == pytest.approx(0.05)  # type: ignore[union-attr]
    hand = robot.link("hand").inertial
    assert hand is not None and hand.mass == pytest.approx(1000 * 4 / 3 * math.pi * 0.04**3)
    assert hand.origin is not None and hand.origin.xyz == (0.0, 0.0, 0.02)
    assert robot.transmissions[0].actuators[0].mechanical_reduction == 100


def test_builder_reports_mistakes_with_their_place() -> None:
    b = RobotBuilder("x")
    b.link("a", box(1, 1, 1), mass=1)
    with pytest.raises(ParseError, match="duplicate link name 'a'"):
        b.link("a", box(1, 1, 1), mass=1)
    with pytest.raises(ParseError, match="invalid inertia tensor"):
        b.link("b", box(1, 1, 1), mass=1, inertia=(1, 1, 5))
    b.link("c", box(1, 1, 1), mass=1)
    b.joint("j", "revolute", "a", "c", axis="z", limits=deg(-1, 1), mimic="ghost")
    with pytest.raises(BrokenReferenceError, match="mimics joint 'ghost', which is not defined"):
        b.build()


def test_unknown_key_at_top_level_is_suggested() -> None:
    with pytest.raises(ParseError, match=r"^r\.yaml:2:1: top level: unknown key 'lnks'; did you mean 'links'\?"):
        load_yaml_text("robot: r\nlnks: {}\n", "r.yaml")
