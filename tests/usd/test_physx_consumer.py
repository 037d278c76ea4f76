"""PhysX as a consumer: the example robots' USD loaded in ovphysx (validation/physx_usd.py), its
numbers compared with the IR, and hand-edited files caught. Skipped without a PhysX interpreter
(tests/consumers/run.sh builds one; ROBODESC_PHYSX_PYTHON names another)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from robodesc.api import compile_to
from robodesc.ir.model import Robot
from robodesc.validation import physx_usd
from robodesc.validation.compare import expected_inertial
from robodesc.validation.physx_python import physx_python
from robodesc.validation.physx_usd import PENDING_FIXES, PHYSX_REL_TOL, read_physx, validate_usd_physx
from robodesc.validation.report import Status, Tally, ValidationReport

ROOT = Path(__file__).resolve().parents[2]
PYTHON = physx_python()
needs_physx = pytest.mark.skipif(PYTHON is None, reason="no PhysX interpreter (tests/consumers/run.sh builds one)")
EXAMPLES = {
    "gripper_arm": (ROOT / "examples" / "urdf" / "gripper_arm.urdf", {}),
    "quadruped": (ROOT / "examples" / "quadruped.yaml", {"fix_base": False}),
    "pendulum": (ROOT / "examples" / "urdf" / "pendulum.urdf.xacro", {}),
}
# A base, a massless tool frame without geometry, and a massless bracket with a 0.2 x 0.1 x 0.1 m box.
MASSLESS = """<robot name="massless">
  <link name="base"><inertial><mass value="2"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="arm"><inertial><origin xyz="0 0 0.1"/><mass value="1"/>
    <inertia ixx="0.004" iyy="0.004" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="tool_frame"/>
  <link name="bracket"><collision><geometry><box size="0.2 0.1 0.1"/></geometry></collision></link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.05"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="2"/></joint>
  <joint name="tool" type="fixed"><parent link="arm"/><child link="tool_frame"/><origin xyz="0 0 0.2"/></joint>
  <joint name="mount" type="fixed"><parent link="arm"/><child link="bracket"/><origin xyz="0 0 0.1"/></joint>
</robot>
"""


def _compile(tmp_path: Path, name: str) -> tuple[Robot, str]:
    source, options = EXAMPLES[name]
    out = tmp_path / f"{name}.usda"
    result = compile_to(str(source), "usd", str(out), validate=False, **options)
    return result.robot, str(out)


def _rows(report: ValidationReport, name: str, status: Status | None = None) -> list[str]:
    return [c.element for c in report.checks if c.name == name and (status is None or c.status is status)]


@needs_physx
@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_physx_reads_what_the_ir_says(tmp_path: Path, name: str) -> None:
    robot, usd = _compile(tmp_path, name)
    report = validate_usd_physx(robot, usd)
    assert report.ok, report.to_text()
    assert not _rows(report, "physx", Status.SKIP)
    for check in ("physx-load", "physx-bodies", "physx-articulation", "physx-mass", "physx-com", "physx-limits"):
        assert _rows(report, check, Status.PASS), f"{check} did not pass:\n{report.to_text()}"
    # What PhysX holds, number by number, besides the report's verdict.
    got = read_physx(usd, str(PYTHON))
    assert not isinstance(got, str), got
    by_name = {path.rsplit("/", 1)[-1]: body for path, body in got.bodies.items()}
    for link in robot.links:
        mass, com, tensor = expected_inertial(link)
        if not mass > 0.0:
            continue
        body = by_name[link.name]
        assert body["mass"] == pytest.approx(mass, rel=PHYSX_REL_TOL)
        assert np.allclose(body["com"], com, atol=PHYSX_REL_TOL)
        if tensor is not None:
            scale = float(np.max(np.abs(np.linalg.eigvalsh(tensor))))
            assert np.allclose(np.reshape(body["inertia"], (3, 3)), tensor, atol=PHYSX_REL_TOL * scale)
    assert sum(b["mass"] for b in got.bodies.values()) == pytest.approx(robot.total_mass(), rel=PHYSX_REL_TOL)


@needs_physx
def test_gripper_arm_joint_numbers_in_physx_units(tmp_path: Path) -> None:
    """Limits in degrees, gains per degree, velocity in deg/s: PhysX's units for an angular DOF."""
    source, _ = EXAMPLES["gripper_arm"]
    usd = str(tmp_path / "gripper_arm.usda")
    compile_to(str(source), "usd", usd, validate=False, stiffness=100.0, damping=1.0)
    got = read_physx(usd, str(PYTHON))
    assert not isinstance(got, str), got
    yaw = next(axes[0] for path, axes in got.joints.items() if path.endswith("/shoulder_yaw"))
    deg = 180.0 / math.pi
    assert yaw["limit"] == pytest.approx([-2.9 * deg, 2.9 * deg], rel=1e-6)
    assert yaw["stiffness"] == pytest.approx(100.0 / deg, rel=1e-6)  # 100 N·m/rad given
    assert yaw["damping"] == pytest.approx(1.0 / deg, rel=1e-6)
    assert yaw["max_force"] == pytest.approx(40.0)
    assert yaw["max_velocity"] == pytest.approx(2.5 * deg, rel=1e-6)
    assert yaw["dynamic_friction"] == pytest.approx(0.1, rel=1e-6)
    finger = next(axes[0] for path, axes in got.joints.items() if path.endswith("/finger_left_joint"))
    assert finger["limit"] == pytest.approx([0.0, 0.04], abs=1e-7)  # metres: a prismatic DOF is not converted
    assert finger["max_velocity"] == pytest.approx(0.2, rel=1e-6)


@needs_physx
def test_quadruped_armature_and_friction_reach_physx(tmp_path: Path) -> None:
    robot, usd = _compile(tmp_path, "quadruped")
    report = validate_usd_physx(robot, usd)
    for check in ("physx-armature", "physx-friction", "physx-max-velocity", "physx-drive", "physx-max-force"):
        assert _rows(report, check, Status.PASS), report.to_text()
    got = read_physx(usd, str(PYTHON))
    assert not isinstance(got, str), got
    armatures = [axes[0]["armature"] for axes in got.joints.values()]
    assert len(armatures) == 12
    assert armatures == pytest.approx([0.005] * 12, rel=1e-6)
    assert got.articulations[0]["fixed_base"] == 0


@needs_physx
@pytest.mark.parametrize(
    ("pattern", "replacement", "check", "element"),
    [
        (r"float physics:mass = 1\.5\b", "float physics:mass = 1.6", "physx-mass", "link 'shoulder'"),
        (
            r"(def PhysicsRevoluteJoint \"elbow\"[^}]*?physics:maxForce = )20",
            r"\g<1>25",
            "physx-max-force",
            "joint 'elbow'",
        ),
        (
            r"(def PhysicsRevoluteJoint \"elbow\"[^}]*?physics:upperLimit = )[0-9.]+",
            r"\g<1>120",
            "physx-limits",
            "joint 'elbow'",
        ),
    ],
)
def test_a_hand_edited_usd_is_caught(tmp_path: Path, pattern: str, replacement: str, check: str, element: str) -> None:
    robot, usd = _compile(tmp_path, "gripper_arm")
    text = Path(usd).read_text(encoding="utf-8")
    edited, count = re.subn(pattern, replacement, text, count=1, flags=re.DOTALL)
    assert count == 1, f"the edit {pattern!r} found nothing to change"
    Path(usd).write_text(edited, encoding="utf-8")
    report = validate_usd_physx(robot, usd)
    # A link's mass also changes the robot's: the total-mass row fails beside it.
    also = ["robot"] if check == "physx-mass" else []
    assert [c.element for c in report.failures] == [element, *also], report.to_text()
    assert element in _rows(report, check, Status.FAIL), report.to_text()


@needs_physx
def test_massless_links_are_measured_as_physx_weighs_them(tmp_path: Path) -> None:
    """Links without <inertial> (a bracket with a collider, a tool frame without) fixed to a link with
    mass: the massless pass moves a 1 g placeholder onto each from the heavy link, so PhysX weighs the
    robot as the source does (3 kg) and every body's mass, centre of mass and inertia agree. Before it,
    PhysX weighed the bracket by its colliders (2 kg) and the frame at its default 1 kg: 6 kg."""
    source = tmp_path / "massless.urdf"
    source.write_text(MASSLESS, encoding="utf-8")
    out = tmp_path / "massless.usda"
    result = compile_to(str(source), "usd", str(out), validate=False)
    report = validate_usd_physx(result.robot, str(out))
    total = report.by_name("physx-total-mass")[0]
    assert total.status is Status.PASS and "3 kg" in total.message
    for name in ("physx-mass", "physx-com", "physx-inertia"):
        assert [c.status for c in report.by_name(name)] == [Status.PASS], name
    assert not report.by_name("physx-massless")  # no link left without a mass
    assert not PENDING_FIXES


def test_without_physx_the_report_says_skipped(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(physx_usd, "physx_python", lambda given=None: None)
    robot = Robot(name="nothing")
    report = validate_usd_physx(robot, str(tmp_path / "absent.usda"))
    assert [(c.name, c.status) for c in report.checks] == [("physx", Status.SKIP)]
    assert report.ok


@needs_physx
def test_a_file_physx_cannot_load_fails_naming_it(tmp_path: Path) -> None:
    bad = tmp_path / "broken.usda"
    bad.write_text('#usda 1.0\n(\n  defaultPrim = "r"\n)\ndef Xform "r" {\n', encoding="utf-8")
    report = validate_usd_physx(Robot(name="r"), str(bad))
    assert [c.name for c in report.failures] == ["physx-load"]
    assert "broken.usda" in report.failures[0].message


MIMIC = """<robot name="m">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="a"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="b"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="lead" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="1" effort="2" velocity="1"/></joint>
  <joint name="follow" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0.1 0 0"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="1" effort="0" velocity="0"/><mimic joint="lead"/></joint>
</robot>
"""


@needs_physx
def test_a_follower_without_a_drive_has_no_force_bound(tmp_path: Path) -> None:
    """Romeo's fingers: a mimic follower with URDF effort 0 gets no drive; PhysX reads its force
    bound as 0, which bounds nothing (22 false failures on romeo before)."""
    source = tmp_path / "mimic.urdf"
    source.write_text(MIMIC, encoding="utf-8")
    out = tmp_path / "mimic.usda"
    result = compile_to(str(source), "usd", str(out), validate=False)
    got = read_physx(str(out), str(PYTHON))
    assert not isinstance(got, str), got
    follow = next(axes[0] for path, axes in got.joints.items() if path.endswith("/follow"))
    assert (follow["drive_type"], follow["max_force"]) == (0, 0)
    report = validate_usd_physx(result.robot, str(out))
    assert _rows(report, "physx-max-force", Status.PASS) == ["2 joints"], report.to_text()


def test_a_source_bound_of_1e30_is_no_bound() -> None:
    """``effort="1e30" velocity="1e30"`` (a URDF's "no limit"): PhysX reads both as unbounded; that
    failed ``compile -t usd`` on main fc66c1d with exit 1, "robodesc's fault"."""
    report = ValidationReport(robot="r", target="usd", consumer="physx")
    tally = Tally(report, "physx-max-force", PHYSX_REL_TOL, "relative")
    physx_usd._bound(tally, "joint 'hinge'", None, 1e30, "maximum N·m", "N·m")
    physx_usd._bound(tally, "joint 'hinge'", 3.4e38, 5.7e31, "maximum velocity", "deg/s")
    assert (tally.checked, tally.failed) == (2, 0)
    physx_usd._bound(tally, "joint 'hinge'", None, 100.0, "maximum N·m", "N·m")  # a real bound PhysX lost
    assert tally.failed == 1


@needs_physx
def test_a_urdf_without_limits_written_as_1e30_validates(tmp_path: Path) -> None:
    source = tmp_path / "big.urdf"
    source.write_text(MASSLESS.replace('effort="10" velocity="2"', 'effort="1e30" velocity="1e30"'), encoding="utf-8")
    result = compile_to(str(source), "usd", str(tmp_path / "big.usda"))  # validated: raises on exit 1
    assert result.validation is not None and result.validation.ok, result.validation.to_text()
