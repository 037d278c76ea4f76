"""The MuJoCo validator passes faithful URDF and catches deliberately corrupted URDF.

Each corruption edits the text robodesc emitted for a real robot; the report must fail and the
failing check must name the element that was corrupted.
"""

from __future__ import annotations

import math

import pytest
from helpers import CORPUS, SPIRIT_XACRO, Emitted, corpus_robot, edit, joint_el, link_el, load_and_emit
from lxml import etree

from robodesc.validation.mujoco_urdf import validate_urdf_text
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Status, ValidationReport

OPTS = ValidateOptions(fk_samples=4)


@pytest.fixture(scope="module")
def ur5() -> Emitted:
    robot = corpus_robot("ur_description/urdf/ur5_robot", str(CORPUS))
    if robot is None:
        pytest.skip("example-robot-data is not installed")
    return load_and_emit(robot.path, robot.packages)


@pytest.fixture(scope="module")
def spirit() -> Emitted:
    if not SPIRIT_XACRO.exists():
        pytest.skip("quadsdk corpus not present")
    return load_and_emit(str(SPIRIT_XACRO))


def failing(report: ValidationReport, name: str) -> list[str]:
    return [c.element for c in report.checks if c.name == name and c.status is Status.FAIL]


def check(e: Emitted, text: str) -> ValidationReport:
    return validate_urdf_text(e.robot, text, e.base_dir, OPTS)


# ---- faithful output passes ---------------------------------------------------------------------
@pytest.mark.parametrize("which", ["ur5", "spirit"])
def test_faithful_output_passes(which: str, request: pytest.FixtureRequest) -> None:
    e: Emitted = request.getfixturevalue(which)
    report = check(e, e.text)
    assert report.ok, report.to_text()
    assert report.max_errors["fk_position"] < 1e-12
    assert report.max_errors["fk_rotation"] < 1e-12
    assert report.max_errors["mass"] < 1e-12
    assert report.max_errors["inertia"] < 1e-12
    names = {c.name for c in report.checks if c.status is Status.PASS}
    assert {"bodies", "mass", "com", "inertia", "joints", "axis", "limits", "fk", "simulation"} <= names


# ---- corruptions -------------------------------------------------------------------------------
def test_swapped_axis_fails_naming_the_joint(ur5: Emitted) -> None:
    def swap(root: etree._Element) -> None:
        axis = joint_el(root, "shoulder_lift_joint").find("axis")
        assert axis is not None
        x, y, z = axis.get("xyz", "").split()
        axis.set("xyz", f"{y} {x} {z}")  # 0 1 0 -> 1 0 0

    report = check(ur5, edit(ur5.text, swap))
    assert not report.ok
    assert failing(report, "axis") == ["joint 'shoulder_lift_joint'"]
    # FK blames the link the joint moves, not its whole subtree.
    assert failing(report, "fk") == ["link 'upper_arm_link'"]


def test_mass_off_by_one_percent_fails_naming_the_link(spirit: Emitted) -> None:
    def heavier(root: etree._Element) -> None:
        mass = link_el(root, "upper2").find("inertial/mass")
        assert mass is not None
        mass.set("value", repr(float(mass.get("value", "0")) * 1.01))

    report = check(spirit, edit(spirit.text, heavier))
    assert not report.ok
    assert failing(report, "mass") == ["link 'upper2'"]
    (row,) = [c for c in report.checks if c.name == "mass" and c.status is Status.FAIL]
    assert row.error == pytest.approx(0.01, rel=1e-9)
    assert not failing(report, "fk")


def test_limit_in_degrees_fails_naming_the_joint(ur5: Emitted) -> None:
    def degrees(root: etree._Element) -> None:
        limit = joint_el(root, "elbow_joint").find("limit")
        assert limit is not None
        for attr in ("lower", "upper"):
            limit.set(attr, repr(math.degrees(float(limit.get(attr, "0")))))

    report = check(ur5, edit(ur5.text, degrees))
    assert not report.ok
    assert failing(report, "limits") == ["joint 'elbow_joint'"]


def test_dropped_link_fails_naming_the_link(spirit: Emitted) -> None:
    def drop(root: etree._Element) -> None:
        # toe0 is a leaf: drop the link and the joint that carries it.
        root.remove(link_el(root, "toe0"))
        for joint in root.findall("joint"):
            child = joint.find("child")
            if child is not None and child.get("link") == "toe0":
                root.remove(joint)

    report = check(spirit, edit(spirit.text, drop))
    assert not report.ok
    assert "link 'toe0'" in failing(report, "bodies")


def test_link_dropped_without_its_joint_is_named_despite_mujoco(spirit: Emitted) -> None:
    # MuJoCo's own error only says "Element 'joint', line N".
    report = check(spirit, edit(spirit.text, lambda root: root.remove(link_el(root, "lower1"))))
    assert failing(report, "mujoco-parse") == ["document"]
    assert failing(report, "bodies") == ["link 'lower1'"]
    assert failing(report, "parents") == ["joint '3'", "joint 'jtoe1'"]


def test_inertia_rotated_fails_naming_the_link(ur5: Emitted) -> None:
    def rotate(root: etree._Element) -> None:
        origin = link_el(root, "forearm_link").find("inertial/origin")
        assert origin is not None
        origin.set("rpy", "0 0.2 0")

    report = check(ur5, edit(ur5.text, rotate))
    assert failing(report, "inertia") == ["link 'forearm_link'"]


def test_text_that_is_not_xml_is_a_failing_check(ur5: Emitted) -> None:
    report = check(ur5, ur5.text[: len(ur5.text) // 2])
    assert not report.ok
    assert failing(report, "mujoco-parse") == ["document"]
