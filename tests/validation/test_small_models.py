"""Hand-written models for the cases the corpus robots do not isolate: mimic, continuous and
prismatic joints, massless moving links, non-physical inertia, meshes MuJoCo cannot read,
the simulation check and the report formats."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest
import trimesh
from helpers import SPIRIT_XACRO, edit, joint_el, link_el

from robodesc.api import validate_file
from robodesc.emit.common.paths import PathMode
from robodesc.emit.urdf import UrdfOptions, emit_urdf
from robodesc.frontends.load import load_string
from robodesc.ir.model import Robot
from robodesc.validation.mujoco_urdf import validate_urdf_text
from robodesc.validation.mujoco_usd import mujoco_usd_available, validate_usd
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Status, ValidationReport

INERTIA = '<inertia ixx="0.01" iyy="0.02" izz="0.025" ixy="0.001" ixz="0" iyz="0.002"/>'


def link(name: str, mass: float | None = 1.0, extra: str = "") -> str:
    inertial = (
        f'<inertial><origin xyz="0.01 0.02 0.03" rpy="0.1 0.2 0.3"/><mass value="{mass}"/>{INERTIA}</inertial>'
        if mass is not None
        else ""
    )
    return f'<link name="{name}">{inertial}{extra}</link>'


def joint(name: str, kind: str, parent: str, child: str, extra: str = "") -> str:
    return (
        f'<joint name="{name}" type="{kind}"><origin xyz="0 0.1 0.2" rpy="0.3 0 0.1"/>'
        f'<parent link="{parent}"/><child link="{child}"/>{extra}</joint>'
    )


ARM = (
    '<robot name="arm">'
    + link("base")
    + link("l1")
    + link("l2")
    + link("l3")
    + link("finger")
    + link("frame", None)
    + joint(
        "j1", "revolute", "base", "l1", '<axis xyz="0 0.6 0.8"/><limit lower="-1.5" upper="2" effort="5" velocity="1"/>'
    )
    + joint("j2", "continuous", "l1", "l2", '<axis xyz="1 0 0"/><dynamics damping="0.3" friction="0.1"/>')
    + joint(
        "j3", "prismatic", "l2", "l3", '<axis xyz="0 0 1"/><limit lower="-0.1" upper="0.2" effort="5" velocity="1"/>'
    )
    + joint(
        "j4",
        "revolute",
        "l3",
        "finger",
        '<axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/><mimic joint="j1" multiplier="-2" offset="0.25"/>',
    )
    + joint("tool", "fixed", "finger", "frame")
    + "</robot>"
)


def emitted(text: str, base_dir: str | None = None) -> tuple[Robot, str]:
    robot = load_string(text, base_dir=base_dir).robot
    return robot, emit_urdf(robot, UrdfOptions(path_mode=PathMode.ABSOLUTE))


def failing(report: ValidationReport, name: str) -> list[str]:
    return [c.element for c in report.checks if c.name == name and c.status is Status.FAIL]


def test_arm_with_mimic_continuous_prismatic_passes() -> None:
    robot, text = emitted(ARM)
    report = validate_urdf_text(robot, text, None, ValidateOptions())
    assert report.ok, report.to_text()
    assert report.max_errors["fk_position"] < 1e-12
    assert [c.status for c in report.by_name("mimic")] == [Status.PASS]
    assert [c.status for c in report.by_name("dynamics")] == [Status.PASS]


def test_floating_base_adds_a_free_joint_and_still_passes() -> None:
    robot, text = emitted(ARM)
    report = validate_urdf_text(robot, text, None, ValidateOptions(floating_base=True))
    assert report.ok, report.to_text()
    (sim,) = report.by_name("simulation")
    assert "floating base" in sim.message


def test_wrong_mimic_multiplier_fails_naming_the_joint() -> None:
    robot, text = emitted(ARM)
    bad = edit(text, lambda root: joint_el(root, "j4").find("mimic").set("multiplier", "2"))  # type: ignore[union-attr]
    report = validate_urdf_text(robot, bad, None, ValidateOptions())
    assert failing(report, "mimic") == ["joint 'j4'"]
    # FK sets mimic joints from the IR (MuJoCo's kinematics ignore equality constraints), so the
    # coupling is checked on the equality itself and FK stays clean.
    assert not failing(report, "fk")


def test_continuous_turned_revolute_fails_on_limits() -> None:
    robot, text = emitted(ARM)

    def limited(root):  # type: ignore[no-untyped-def]
        j = joint_el(root, "j2")
        j.set("type", "revolute")
        from lxml import etree

        etree.SubElement(j, "limit", lower="-1", upper="1", effort="1", velocity="1")

    report = validate_urdf_text(robot, edit(text, limited), None, ValidateOptions())
    assert failing(report, "limits") == ["joint 'j2'"]


def test_com_moved_fails_naming_the_link() -> None:
    robot, text = emitted(ARM)
    bad = edit(text, lambda root: link_el(root, "l2").find("inertial/origin").set("xyz", "0.01 0.02 0.04"))  # type: ignore[union-attr]
    report = validate_urdf_text(robot, bad, None, ValidateOptions())
    assert failing(report, "com") == ["link 'l2'"]


def test_massless_moving_link_is_a_finding_not_a_crash() -> None:
    text = ARM.replace(link("l3"), link("l3", None))
    robot, out = emitted(text)
    report = validate_urdf_text(robot, out, None, ValidateOptions())
    assert "link 'l3'" in failing(report, "mujoco-compile")
    # The rest of the comparison still ran.
    assert report.max_errors["fk_position"] < 1e-12
    assert any(c.status is Status.SKIP and "l3" in c.message for c in report.by_name("mass"))


def test_non_physical_inertia_is_reported_by_link() -> None:
    bad_inertia = '<inertia ixx="0.001" iyy="0.001" izz="0.01" ixy="0" ixz="0" iyz="0"/>'
    text = ARM.replace(link("l1"), link("l1").replace(INERTIA, bad_inertia))
    robot, out = emitted(text)
    report = validate_urdf_text(robot, out, None, ValidateOptions())
    assert failing(report, "mujoco-compile") == ["link 'l1'"]
    assert "A + B >= C" in report.failures[0].message


def test_dae_mesh_is_converted_and_missing_mesh_is_named(tmp_path: Path) -> None:
    box = trimesh.creation.box(extents=(0.1, 0.1, 0.1))
    (tmp_path / "box.dae").write_bytes(box.export(file_type="dae"))
    geom = '<collision><geometry><mesh filename="box.dae"/></geometry></collision>'
    text = ARM.replace(link("l2"), link("l2", extra=geom))
    robot, out = emitted(text, str(tmp_path))
    opts = ValidateOptions(mesh_cache_dir=str(tmp_path / "cache"))
    report = validate_urdf_text(robot, out, str(tmp_path), opts)
    assert report.ok, report.to_text()
    (row,) = report.by_name("mesh-files")
    assert "1 converted" in row.message
    assert os.listdir(tmp_path / "cache")

    missing = out.replace(str(tmp_path / "box.dae"), str(tmp_path / "gone.dae"))
    report = validate_urdf_text(robot, missing, str(tmp_path), opts)
    (row,) = [c for c in report.by_name("mesh-files") if c.status is Status.FAIL]
    assert "gone.dae" in row.element and "l2" in row.message


def test_interpenetration_at_rest_names_the_links() -> None:
    geom = '<collision><geometry><box size="0.5 0.5 0.5"/></geometry></collision>'
    text = ARM.replace(link("base"), link("base", extra=geom)).replace(link("l2"), link("l2", extra=geom))
    robot, out = emitted(text)
    report = validate_urdf_text(robot, out, None, ValidateOptions())
    (row,) = report.by_name("penetration")
    assert row.status is Status.WARN
    assert "base/l2" in row.message
    assert report.ok  # a warning, not a failure


def test_explosion_is_reported_with_the_joint() -> None:
    robot, out = emitted(ARM)
    report = validate_urdf_text(robot, out, None, ValidateOptions(max_speed=1e-9))
    (row,) = report.by_name("simulation")
    assert row.status is Status.FAIL
    assert row.element.startswith("joint '")


def test_report_formats() -> None:
    robot, text = emitted(ARM)
    bad = edit(text, lambda root: link_el(root, "l1").find("inertial/mass").set("value", "1.5"))  # type: ignore[union-attr]
    report = validate_urdf_text(robot, bad, None, ValidateOptions())
    data = json.loads(report.to_json())
    assert data["ok"] is False
    assert data["checks"][0]["status"] == "fail" and data["checks"][0]["element"] == "link 'l1'"
    md = report.to_markdown()
    assert "| fail | mass | link 'l1' |" in md
    txt = report.to_text()
    assert txt.splitlines()[0].startswith("urdf of 'arm' checked with mujoco: FAILED")
    assert "link 'l1'" in txt
    assert all(len(line) <= 120 for line in txt.splitlines()[1:-1])


def test_validate_file_reports_source_defects_of_spirit() -> None:
    if not SPIRIT_XACRO.exists():
        pytest.skip("quadsdk corpus not present")
    report = validate_file(str(SPIRIT_XACRO), ValidateOptions(fk_samples=2))
    assert report.ok, report.to_text()
    defects = [c.element for c in report.by_name("source") if c.status is Status.WARN]
    assert defects == ["link 'text_right'", "link 'text_left'"]


def test_usd_without_mujoco_usd_is_a_clear_skip(tmp_path: Path) -> None:
    if mujoco_usd_available():
        pytest.skip("mujoco-usd is installed here")
    from robodesc.emit.usd import emit_usd
    from robodesc.passes import PassOptions, run_passes

    robot, _ = emitted(ARM)
    # What the USD target runs first: the massless 'frame' takes its mass from 'finger'.
    run_passes(robot, options=PassOptions(mass_from_colliders=True, placeholder_masses=True))
    emit_usd(robot, str(tmp_path / "arm.usda"))
    report = validate_usd(robot, str(tmp_path / "arm.usda"))
    # usd-core's own parser still checks the file; only the mujoco-usd part is skipped.
    (row,) = report.by_name("mujoco-usd")
    assert row.status is Status.SKIP and "mujoco-usd not installed" in row.message
    assert report.ok and report.by_name("fk")[0].status is Status.PASS


def test_fk_samples_stay_within_limits() -> None:
    from robodesc.validation.compare import sample_configurations

    robot, _ = emitted(ARM)
    for q in sample_configurations(robot, 50, 3):
        if q:
            assert -1.5 <= q["j1"] <= 2 and -0.1 <= q["j3"] <= 0.2 and "j4" not in q
    assert np.isfinite(sum(sum(q.values()) for q in sample_configurations(robot, 5, 0)))
