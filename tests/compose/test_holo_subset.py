"""The .holo subset: templates, groups, the three joint notations, both axis notations, props."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robodesc.frontends.holo.lower import HoloResult, load_holo_text
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import BrokenReferenceError, ParseError
from robodesc.ir.geometry import Box, Capsule, Cylinder, Sphere
from robodesc.ir.model import JointType
from robodesc.ir.transforms import forward_kinematics, pose_matrix


def load(text: str) -> HoloResult:
    return load_holo_text(text, "t.holo", LoadOptions())


def codes(result: HoloResult) -> list[str]:
    return [f.code for f in result.findings]


ROBOT = """
// a gantry written with every joint notation
composition 'Gantry' {
  environment { gravity: [0, 0, -9.81]; skybox: "sunset" }
  template "Rail" {
    geometry: "box"
    scale: [1.0, 0.05, 0.05]
    color: "#f00"
    @physics { type: "dynamic", mass: 2 }
  }
  /* the fixed base */
  object "Base" {
    @physics { type: "static" mass: 20 }
    geometry: "box"
    scale: [1, 1, 0.1]
    position: [0, 0, 0.05]
  }
  spatial_group "Carriage" {
    origin: [0.5, 0, 0.1]
    object "Rail" using "Rail" {
      @physics { mass: 3 }
      @joint { type: "slider", connectedBody: "Base", axis: {x: 1}, limits: { min: -0.4, max: 0.4 } }
      position: [0, 0, 0.5]
    }
    spatial_group "Head" {
      origin: [0, 0, 0.2]
      object "Turret" {
        behavior "RevoluteJoint" { axis: [0, 0, 1], lowerLimit: -1.5707963, upperLimit: 1.5707963, maxVelocity: 1, maxTorque: 4 }
        parent: "Rail"
        geometry: "cylinder"
        scale: [0.2, 0.1, 0.2]
        mass: 1
        color: "steelblue"
      }
    }
  }
  object "Wrist--1" {
    joint_type: "ball"
    parent: "Turret"
    axis: [0, 0, 1]
    geometry: "sphere"
    scale: 0.04
    position: [0.5, 0, 0.9]
    mass: 0.2
    color: "#11223344"
  }
  object "Spinner" {
    @joint { jointType: "hinge", connectedBody: "Wrist--1", axis: [1, 0, 0] }
    geometry: "capsule"
    scale: [0.02, 0.1, 0.02]
    position: [0.5, 0, 1.0]
    mass: 0.1
  }
  object "Tool" { geometry: "box" scale: 0.01 position: [0.5, 0, 1.1] mass: 0.05 }
  object "Ball" { @grabbable @physics { mass: 0.3 } geometry: "sphere" scale: 0.1 position: [2, 0, 0.05] color: "yellow" }
  object "Floor" { @physics { type: "static" } geometry: "plane" scale: [10, 1, 10] }
  state { counter: 0 }
  system "Hud" { show() { return `}` } }
}
"""


@pytest.fixture(scope="module")
def gantry() -> HoloResult:
    return load(ROBOT)


def test_joint_notations(gantry: HoloResult) -> None:
    r = gantry.robot
    rail, turret, wrist, spinner = (
        r.joint(n) for n in ("Rail_joint", "Turret_joint", "Wrist--1_joint", "Spinner_joint")
    )
    assert rail.type is JointType.PRISMATIC and rail.axis == (1.0, 0.0, 0.0)
    assert rail.limit is not None and (rail.limit.lower, rail.limit.upper) == (-0.4, 0.4)
    assert turret.type is JointType.REVOLUTE and turret.parent == "Rail" and turret.axis == (0.0, 0.0, 1.0)
    assert turret.limit is not None and turret.limit.upper == pytest.approx(math.pi / 2)
    assert (turret.limit.velocity, turret.limit.effort) == (1.0, 4.0)
    assert wrist.type is JointType.SPHERICAL and wrist.parent == "Turret"  # ball is not floating
    # A hinge without limits turns freely: continuous, reported.
    assert spinner.type is JointType.CONTINUOUS
    assert "unlimited-revolute" in codes(gantry)
    # The object without a joint rides on the most recent object before it.
    tool = r.parent_joint()["Tool"]
    assert tool.type is JointType.FIXED and tool.parent == "Spinner"


def test_groups_templates_and_world_positions(gantry: HoloResult) -> None:
    r = gantry.robot
    place = pose_matrix(r.placement)
    fk = {k: place @ v for k, v in forward_kinematics(r).items()}
    assert fk["Rail"][:3, 3] == pytest.approx([0.5, 0, 0.6])  # group origin + position
    assert fk["Turret"][:3, 3] == pytest.approx([0.5, 0, 0.3])  # nested groups add up
    assert fk["Wrist--1"][:3, 3] == pytest.approx([0.5, 0, 0.9])
    # The template gives geometry and colour; the object's @physics overrides the mass.
    rail = r.link("Rail")
    assert rail.inertial is not None and rail.inertial.mass == 3.0
    assert isinstance(rail.visuals[0].geometry, Box) and rail.visuals[0].geometry.size == (1.0, 0.05, 0.05)
    mat = rail.visuals[0].material
    assert mat is not None and mat.color == (1.0, 0.0, 0.0, 1.0)  # #f00 is red, not NaN
    # Sliding the rail moves everything above it.
    moved = forward_kinematics(r, {"Rail_joint": 0.25})
    assert (place @ moved["Tool"])[:3, 3] == pytest.approx([0.75, 0, 1.1])


def test_shapes_and_colours(gantry: HoloResult) -> None:
    r = gantry.robot
    cyl = r.link("Turret").visuals[0].geometry
    assert isinstance(cyl, Cylinder) and (cyl.radius, cyl.length) == (0.1, 0.1)
    sph = r.link("Wrist--1").visuals[0].geometry
    assert isinstance(sph, Sphere) and sph.radius == 0.02
    cap = r.link("Spinner").visuals[0].geometry
    assert isinstance(cap, Capsule) and cap.radius == 0.01 and cap.length == pytest.approx(0.08)
    wmat = r.link("Wrist--1").visuals[0].material
    assert wmat is not None and wmat.color == pytest.approx((0x11 / 255, 0x22 / 255, 0x33 / 255, 0x44 / 255))


def test_props_and_ignored_blocks(gantry: HoloResult) -> None:
    names = {p.name: p for p in gantry.props}
    assert set(names) == {"Ball", "Floor"}
    ball = names["Ball"]
    assert ball.kind == "grabbable" and ball.mass == 0.3 and ball.pose.xyz == (2.0, 0.0, 0.05)
    assert isinstance(ball.geometry, Sphere) and ball.color == (1.0, 1.0, 0.0, 1.0)
    assert names["Floor"].kind == "static"
    assert "Ball" not in {link.name for link in gantry.robot.links}
    skipped = [f.message for f in gantry.findings if f.code == "ignored-block"]
    assert any("'state'" in m for m in skipped) and any("'system'" in m for m in skipped)
    assert "ignored-environment" in codes(gantry)


def test_names_with_double_dash_are_kept(gantry: HoloResult) -> None:
    assert "Wrist--1" in {link.name for link in gantry.robot.links}


def test_y_up_composition_is_rotated_to_z_up() -> None:
    result = load("""composition "Y" {
      environment { gravity: [0, -9.81, 0] }
      object "Base" { @physics { type: "static" mass: 1 } geometry: "cylinder" scale: [0.2, 0.1, 0.2] position: [0, 0.05, 0] }
      object "Arm" { @joint { jointType: "revolute" connectedBody: "Base" axis: [0, 1, 0] limits: { min: -10, max: 10 } }
                     geometry: "box" scale: [0.05, 0.4, 0.05] position: [0, 0.3, 0] mass: 1 }
    }""")
    r = result.robot
    assert r.placement is not None and r.placement.xyz == pytest.approx((0, 0, 0.05))
    arm = forward_kinematics(r)["Arm"]
    assert (pose_matrix(r.placement) @ arm)[:3, 3] == pytest.approx([0, 0, 0.3])
    # The joint axis is in the object's frame, and that frame turned with the scene: local y is world z.
    world_axis = (pose_matrix(r.placement) @ arm)[:3, :3] @ np.asarray(r.joint("Arm_joint").effective_axis)
    assert world_axis == pytest.approx([0, 0, 1])
    # The cylinder's height still runs up.
    visual = r.link("Base").visuals[0]
    assert visual.origin is not None
    up = (pose_matrix(r.placement) @ pose_matrix(visual.origin))[:3, 2]
    assert abs(up[2]) == pytest.approx(1.0)
    assert "converted-up-axis" in codes(result)


def test_mass_contradiction_is_an_error() -> None:
    with pytest.raises(ParseError, match=r"^t\.holo:2:69: object 'A': physics\.mass 3 contradicts @physics\.mass 2"):
        load(
            'composition "C" {\n  object "A" { @physics { type: "static" mass: 2 } physics: { mass: 3 } }\n'
            '  object "B" { parent: "A" mass: 1 }\n}'
        )


def test_actuator_without_joint_is_an_error() -> None:
    with pytest.raises(ParseError, match="@actuator on an object without a joint"):
        load(
            'composition "C" { object "A" { @physics { type: "static" mass: 1 } }'
            ' object "B" { @actuator { hardwareInterface: "x" } mass: 1 }'
            ' object "C" { parent: "B" mass: 1 } }'
        )


def test_unknown_template_is_named() -> None:
    with pytest.raises(
        BrokenReferenceError, match=r"t\.holo:1:56: object 'A': template 'Lnk' is not defined; did you mean 'Link'\?"
    ):
        load('composition "C" { template "Link" { } object "A" using "Lnk" { } }')
