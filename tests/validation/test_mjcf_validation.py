"""The MJCF validator passes faithful MuJoCo models and catches deliberately corrupted ones.

Until robodesc writes MJCF itself, the faithful models come from MuJoCo: robodesc's URDF output is
loaded by MuJoCo's URDF importer (``load_urdf_in_mujoco``), position actuators with known gains
are added through ``MjSpec``, and ``MjSpec.to_xml`` writes ``robot.xml``; ``scene.xml`` includes it
and adds a floor and a light, as menagerie's scenes do. Each corruption then edits that XML text
and the report must fail naming the corrupted element.

MuJoCo writes XML with 6 significant digits, so these faithful files are only faithful to ~5e-6:
the tolerances here are 1e-5 (the validator's defaults, for full-precision output, are tighter).
Every corruption is orders of magnitude above that.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import mujoco
import pytest
from helpers import CORPUS, ROOT, corpus_robot, load_and_emit
from lxml import etree

import robodesc
from robodesc.ir.model import Robot
from robodesc.validation.mujoco_load import load_urdf_in_mujoco
from robodesc.validation.mujoco_mjcf import validate_mjcf
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Status, ValidationReport

TOL = 1e-5
OPTS = ValidateOptions(
    fk_samples=4,
    mass_rel_tol=TOL,
    inertia_rel_tol=TOL,
    position_tol=TOL,
    rotation_tol=TOL,
    axis_tol=TOL,
    limit_tol=TOL,
    gain_rel_tol=TOL,
)
KP, KV = 100.0, 10.0
SCENE = """<mujoco model="scene">
  <include file="robot.xml"/>
  <worldbody>
    <light pos="0 0 3" dir="0 0 -1" directional="true"/>
    <geom name="floor" type="plane" size="0 0 0.05" pos="0 0 -1"/>
  </worldbody>
</mujoco>
"""


@dataclass
class Mjcf:
    robot: Robot
    xml: str  # robot.xml
    drives: dict[str, tuple[float, float]]


def to_mjcf(urdf_path: str, packages: dict[str, str] | None = None, *, fuse_static: bool = False) -> Mjcf:
    """robodesc's URDF output through MuJoCo's importer, with a position actuator per joint."""
    emitted = load_and_emit(urdf_path, packages)
    report = ValidationReport(emitted.robot.name, "urdf", "mujoco")
    loaded = load_urdf_in_mujoco(emitted.robot, emitted.text, emitted.base_dir, ValidateOptions(), report)
    assert loaded is not None, report.to_text()
    spec = loaded.spec
    drives = {}
    for joint in emitted.robot.joints:
        if joint.type.dof != 1 or joint.mimic is not None:
            continue
        act = spec.add_actuator(name=f"{joint.name}_act", target=joint.name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.set_to_position(kp=KP, kv=KV)
        lim = joint.limit
        if joint.type.value != "continuous" and lim is not None and lim.lower is not None and lim.upper is not None:
            act.ctrlrange, act.ctrllimited = [lim.lower, lim.upper], 1
        drives[joint.name] = (KP, KV)
    if fuse_static:
        _fuse_static(spec, emitted.robot)
    spec.compile()
    return Mjcf(emitted.robot, spec.to_xml(), drives)


def _fuse_static(spec: mujoco.MjSpec, robot: Robot) -> None:
    """Let MuJoCo merge every fixed, non-root link into its parent, leaving a site in its place:
    MuJoCo, not the validator, computes the merged masses. A sensor on the root keeps it a body."""
    for joint in robot.joints:
        if joint.type.value == "fixed":
            spec.body(joint.child).add_site(name=joint.child)
    spec.compiler.fusestatic = True
    spec.add_sensor(type=mujoco.mjtSensor.mjSENS_FRAMEPOS, objtype=mujoco.mjtObj.mjOBJ_BODY, objname=robot.root.name)


def validate(m: Mjcf, tmp: Path, xml: str | None = None, *, drives: bool = True) -> ValidationReport:
    tmp.mkdir(parents=True, exist_ok=True)
    (tmp / "robot.xml").write_text(xml if xml is not None else m.xml)
    (tmp / "scene.xml").write_text(SCENE)
    return validate_mjcf(
        m.robot, str(tmp / "robot.xml"), str(tmp / "scene.xml"), OPTS, expected_drives=m.drives if drives else None
    )


def edit(xml: str, change: Callable[[etree._Element], None]) -> str:
    root = etree.fromstring(xml.encode("utf-8"))
    change(root)
    return etree.tostring(root, encoding="unicode")


def find(root: etree._Element, path: str) -> etree._Element:
    found = root.find(path)
    assert found is not None, path
    return found


def failing(report: ValidationReport, name: str) -> list[str]:
    return [c.element for c in report.checks if c.name == name and c.status is Status.FAIL]


def scale(el: etree._Element, attr: str, factor: float, index: int | None = None) -> None:
    values = [float(v) for v in el.get(attr, "").split()]
    for k in range(len(values)) if index is None else [index]:
        values[k] *= factor
    el.set(attr, " ".join(repr(v) for v in values))


# ---- models ---------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def ur5() -> Mjcf:
    entry = corpus_robot("ur_description/urdf/ur5_robot", str(CORPUS))
    if entry is None:
        pytest.skip("example-robot-data is not installed")
    return to_mjcf(entry.path, entry.packages)


@pytest.fixture(scope="module")
def gripper() -> Mjcf:
    return to_mjcf(str(ROOT / "examples" / "urdf" / "gripper_arm.urdf"))


@pytest.fixture(scope="module")
def four_bar_urdf(tmp_path_factory: pytest.TempPathFactory) -> str:
    out = tmp_path_factory.mktemp("four_bar") / "four_bar.urdf"
    robodesc.compile_to_urdf(str(ROOT / "examples" / "four_bar.yaml"), str(out))
    return str(out)


def with_loop_connect(m: Mjcf) -> str:
    """The four-bar's spherical loop joint as the ``<equality connect>`` MJCF needs."""
    loop = m.robot.loop_joints[0]
    anchor = loop.link1.origin.xyz if loop.link1.origin is not None else (0.0, 0.0, 0.0)

    def add(root: etree._Element) -> None:
        eq = root.find("equality")
        if eq is None:
            eq = etree.SubElement(root, "equality")
        etree.SubElement(
            eq,
            "connect",
            name=loop.name,
            body1=loop.link1.link,
            body2=loop.link2.link,
            anchor=" ".join(repr(v) for v in anchor),
        )

    return edit(m.xml, add)


# ---- faithful models pass ---------------------------------------------------------------------
@pytest.mark.parametrize("which", ["ur5", "gripper"])
def test_faithful_model_passes(which: str, request: pytest.FixtureRequest, tmp_path: Path) -> None:
    m: Mjcf = request.getfixturevalue(which)
    report = validate(m, tmp_path)
    assert report.ok, report.to_text()
    passed = {c.name for c in report.checks if c.status is Status.PASS}
    expected = {"mjcf-load", "scene-load", "bodies", "mass", "inertia", "joints", "axis", "limits", "fk"}
    assert expected | {"dynamics", "armature", "actuators", "gains", "actuator-range", "menagerie"} <= passed
    assert report.max_errors["fk_position"] < TOL


def test_mimic_is_compared_and_a_wrong_coupling_fails(gripper: Mjcf, tmp_path: Path) -> None:
    report = validate(gripper, tmp_path / "ok")
    assert [c.status for c in report.by_name("mimic")] == [Status.PASS]

    def double(root: etree._Element) -> None:
        eq = find(root, "equality/joint")
        eq.set("polycoef", "0 2 0 0 0")

    report = validate(gripper, tmp_path / "bad", edit(gripper.xml, double))
    assert failing(report, "mimic") == ["joint 'finger_right_joint'"]

    def drop(root: etree._Element) -> None:
        eq = find(root, "equality")
        root.remove(eq)

    report = validate(gripper, tmp_path / "none", edit(gripper.xml, drop))
    assert failing(report, "mimic") == ["joint 'finger_right_joint'"]


@pytest.mark.parametrize(("polycoef", "ok"), [("0 1 0 0 0", True), ("0 2 0 0 0", False), ("0 1 0.5 0 0", False)])
def test_mimic_written_leader_first_is_the_inverse_coupling(
    gripper: Mjcf, tmp_path: Path, polycoef: str, ok: bool
) -> None:
    """urdf-to-mjcf writes ``joint1`` = leader: q_leader = a0 + a1·q is the same coupling inverted."""

    def leader_first(root: etree._Element) -> None:
        eq = find(root, "equality/joint")
        eq.set("joint1", "finger_left_joint")
        eq.set("joint2", "finger_right_joint")
        eq.set("polycoef", polycoef)

    report = validate(gripper, tmp_path, edit(gripper.xml, leader_first))
    assert failing(report, "mimic") == ([] if ok else ["joint 'finger_right_joint'"])


def test_loop_joint_needs_its_equality(four_bar_urdf: str, tmp_path: Path) -> None:
    m = to_mjcf(four_bar_urdf)
    report = validate(m, tmp_path / "ok", with_loop_connect(m))
    assert report.ok, report.to_text()
    assert [c.status for c in report.by_name("loops")] == [Status.PASS]
    report = validate(m, tmp_path / "bad")
    assert failing(report, "loops") == ["loop joint 'coupler_rocker'"]


def test_link_merged_into_a_site_is_compared(four_bar_urdf: str, tmp_path: Path) -> None:
    m = to_mjcf(four_bar_urdf, fuse_static=True)
    root = etree.fromstring(m.xml.encode("utf-8"))
    assert root.find(".//body[@name='crank_hub']") is None and root.find(".//site[@name='crank_hub']") is not None
    report = validate(m, tmp_path / "ok", with_loop_connect(m))
    assert report.ok, report.to_text()
    assert [c.status for c in report.by_name("sites")] == [Status.PASS]

    def moved(r: etree._Element) -> None:
        find(r, ".//site[@name='crank_hub']").set("pos", "0 0 0.01")

    report = validate(m, tmp_path / "moved", edit(with_loop_connect(m), moved))
    assert failing(report, "fk") == ["link 'crank_hub'"]

    def hub_mass_lost(r: etree._Element) -> None:
        inertial = find(r, ".//body[@name='crank']/inertial")
        inertial.set("mass", repr(float(inertial.get("mass", "0")) - 0.05))

    report = validate(m, tmp_path / "light", edit(with_loop_connect(m), hub_mass_lost))
    assert failing(report, "mass") == ["link 'crank'"]


# ---- corruptions ------------------------------------------------------------------------------
def test_swapped_axis_fails_naming_the_joint(ur5: Mjcf, tmp_path: Path) -> None:
    def swap(root: etree._Element) -> None:
        find(root, ".//joint[@name='shoulder_lift_joint']").set("axis", "1 0 0")

    report = validate(ur5, tmp_path, edit(ur5.xml, swap))
    assert failing(report, "axis") == ["joint 'shoulder_lift_joint'"]
    assert failing(report, "fk") == ["link 'upper_arm_link'"]


def test_mass_off_by_one_percent_fails_naming_the_link(ur5: Mjcf, tmp_path: Path) -> None:
    def heavier(root: etree._Element) -> None:
        scale(find(root, ".//body[@name='forearm_link']/inertial"), "mass", 1.01)

    report = validate(ur5, tmp_path, edit(ur5.xml, heavier))
    assert failing(report, "mass") == ["link 'forearm_link'"]


def test_range_in_degrees_fails_naming_the_joint(ur5: Mjcf, tmp_path: Path) -> None:
    def degrees(root: etree._Element) -> None:
        scale(find(root, ".//joint[@name='elbow_joint']"), "range", 180 / math.pi)

    report = validate(ur5, tmp_path, edit(ur5.xml, degrees))
    assert failing(report, "limits") == ["joint 'elbow_joint'"]


def test_ctrlrange_in_degrees_fails_naming_the_joint(ur5: Mjcf, tmp_path: Path) -> None:
    def degrees(root: etree._Element) -> None:
        scale(find(root, "actuator/general[@joint='elbow_joint']"), "ctrlrange", 180 / math.pi)

    report = validate(ur5, tmp_path, edit(ur5.xml, degrees))
    assert failing(report, "actuator-range") == ["joint 'elbow_joint'"]


def test_per_degree_gain_in_a_per_radian_slot_fails(ur5: Mjcf, tmp_path: Path) -> None:
    """IsaacSim#842: a per-degree kp copied where MuJoCo expects per-radian is 57.3x too stiff."""

    def per_degree(root: etree._Element) -> None:
        act = find(root, "actuator/general[@joint='elbow_joint']")
        scale(act, "gainprm", 180 / math.pi, 0)
        scale(act, "biasprm", 180 / math.pi, 1)

    report = validate(ur5, tmp_path, edit(ur5.xml, per_degree))
    assert failing(report, "gains") == ["joint 'elbow_joint'"]
    # Without the expected drives the servo is still consistent: only the caller knows the gain.
    assert validate(ur5, tmp_path / "nodrives", edit(ur5.xml, per_degree), drives=False).ok


def test_missing_actuator_fails_naming_the_joint(ur5: Mjcf, tmp_path: Path) -> None:
    def drop(root: etree._Element) -> None:
        act = find(root, "actuator/general[@joint='wrist_2_joint']")
        act.getparent().remove(act)

    report = validate(ur5, tmp_path, edit(ur5.xml, drop))
    assert failing(report, "actuators") == ["joint 'wrist_2_joint'"]


def test_dropped_body_fails_naming_the_link(ur5: Mjcf, tmp_path: Path) -> None:
    def drop(root: etree._Element) -> None:
        body = find(root, ".//body[@name='ee_link']")
        body.getparent().remove(body)

    report = validate(ur5, tmp_path, edit(ur5.xml, drop))
    assert failing(report, "bodies") == ["link 'ee_link'"]


def test_armature_is_compared(ur5: Mjcf, tmp_path: Path) -> None:
    def armature(root: etree._Element) -> None:
        find(root, ".//joint[@name='wrist_1_joint']").set("armature", "0.01")

    report = validate(ur5, tmp_path, edit(ur5.xml, armature))
    assert failing(report, "armature") == ["joint 'wrist_1_joint'"]


def test_model_that_does_not_load_fails(ur5: Mjcf, tmp_path: Path) -> None:
    def bad_ref(root: etree._Element) -> None:
        find(root, "actuator/general[@joint='elbow_joint']").set("joint", "no_such_joint")

    report = validate(ur5, tmp_path, edit(ur5.xml, bad_ref))
    assert failing(report, "mjcf-load") == ["robot.xml"]
    assert failing(report, "scene-load") == ["scene.xml"]


# ---- the menagerie test -----------------------------------------------------------------------
PENDULUM = """<mujoco model="pendulum">
  <compiler angle="radian"/>
  <option timestep="{timestep}"/>
  <worldbody>
    <body name="base">
      <body name="arm">
        <joint name="hinge" axis="0 1 0" range="-1 1"/>
        <inertial pos="0 0 -0.5" mass="1" diaginertia="0.01 0.01 0.01"/>
      </body>
    </body>
  </worldbody>
  <actuator>
    <position name="servo" joint="hinge" kp="{kp}" kv="1" ctrlrange="-1 1"/>
  </actuator>
</mujoco>
"""


def pendulum(tmp_path: Path, kp: float, timestep: float) -> ValidationReport:
    from robodesc.ir.geometry import Inertia, Inertial, Pose
    from robodesc.ir.model import Joint, JointType, Limit, Link

    robot = Robot(
        name="pendulum",
        links=[
            Link("base"),
            Link("arm", Inertial(1.0, Pose(xyz=(0.0, 0.0, -0.5)), Inertia(0.01, 0.01, 0.01))),
        ],
        joints=[Joint("hinge", JointType.REVOLUTE, "base", "arm", axis=(0.0, 1.0, 0.0), limit=Limit(-1.0, 1.0))],
    )
    path = tmp_path / "robot.xml"
    path.write_text(PENDULUM.format(kp=kp, timestep=timestep))
    return validate_mjcf(robot, str(path), None, OPTS, expected_drives={"hinge": (kp, 1.0)})


def test_stable_pendulum_passes_the_menagerie_test(tmp_path: Path) -> None:
    report = pendulum(tmp_path, kp=10.0, timestep=0.002)
    assert report.ok, report.to_text()
    (row,) = report.by_name("menagerie")
    assert row.status is Status.PASS and "500" in row.message


def test_nan_producing_model_fails_the_menagerie_test(tmp_path: Path) -> None:
    # A stiff servo on a light link at a coarse step: explicit Euler diverges to NaN.
    report = pendulum(tmp_path, kp=1e12, timestep=0.01)
    assert failing(report, "menagerie") == ["robot.xml"]
    (row,) = report.by_name("menagerie")
    assert "mjWARN_BADQACC" in row.message


def test_token_mass_on_a_massless_link_warns_and_a_real_one_fails(ur5: Mjcf, tmp_path: Path) -> None:
    def token(mass: str) -> Callable[[etree._Element], None]:
        def change(root: etree._Element) -> None:
            body = find(root, ".//body[@name='ee_link']")
            for old in body.findall("inertial"):
                body.remove(old)
            body.insert(0, etree.Element("inertial", pos="0 0 0", mass=mass, diaginertia="1e-9 1e-9 1e-9"))

        return change

    report = validate(ur5, tmp_path / "token", edit(ur5.xml, token("1e-06")))
    assert report.ok, report.to_text()
    assert [c.element for c in report.warnings if c.name == "mass"] == ["link 'ee_link'"]
    report = validate(ur5, tmp_path / "real", edit(ur5.xml, token("0.01")))
    assert failing(report, "mass") == ["link 'ee_link'"]
