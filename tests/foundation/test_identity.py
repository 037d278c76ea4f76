"""URDF → IR → URDF identity over real robots.

An independent parser (Pinocchio) reads the source and robodesc's output; links, joints, masses,
inertias, limits and forward kinematics must agree. robodesc's own output must also be a fixed
point (emitting what it emitted changes nothing) and byte-stable across runs.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import yourdfpy

from robodesc.emit.common.paths import PathMode
from robodesc.emit.urdf import UrdfOptions, emit_urdf
from robodesc.frontends.load import load_path, load_string
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.frontends.packages import PackageResolver
from robodesc.frontends.xacro_expand import expand_xacro
from robodesc.ir.diagnostics import Findings
from robodesc.validation.corpora import CorpusRobot, all_robots
from tests.conftest import CORPUS

from .consumers import PinView

ROBOTS = all_robots(str(CORPUS))
# Sources that are structurally broken: the verifier reports them (tested in test_corpus_defects).
BROKEN = {"ur_description/urdf/ur3", "alex_description/urdf/alex_psyonic_hands", "talos_data/robots/talos_left_arm"}


def _source_text(robot: CorpusRobot) -> str:
    if robot.path.endswith(".xacro"):
        resolver = PackageResolver(explicit=robot.packages, input_file=robot.path)
        return expand_xacro(robot.path, robot.xacro_args, resolver, Findings())
    return Path(robot.path).read_text(encoding="utf-8")


def _roundtrip(robot: CorpusRobot) -> tuple[str, str]:
    opts = LoadOptions(package_paths=robot.packages, missing_mesh=MissingMesh.WARN)
    ir = load_path(robot.path, opts).robot
    out = emit_urdf(ir, UrdfOptions(path_mode=PathMode.ABSOLUTE))
    return _source_text(robot), out


@pytest.mark.parametrize("robot", [r for r in ROBOTS if r.name not in BROKEN], ids=lambda r: f"{r.corpus}:{r.name}")
def test_pinocchio_reads_output_as_source(robot: CorpusRobot) -> None:
    source, out = _roundtrip(robot)
    try:
        expected = PinView.from_text(source)
    except Exception as exc:  # the reference parser itself rejects the source
        pytest.skip(f"Pinocchio cannot read the source: {exc}")
    actual = PinView.from_text(out)
    assert expected.compare(actual) == []


@pytest.mark.parametrize("robot", [r for r in ROBOTS if r.name not in BROKEN], ids=lambda r: f"{r.corpus}:{r.name}")
def test_output_is_a_fixed_point_and_byte_stable(robot: CorpusRobot) -> None:
    _, first = _roundtrip(robot)
    _, again = _roundtrip(robot)
    assert first == again
    reread = load_string(first, LoadOptions(missing_mesh=MissingMesh.WARN)).robot
    assert emit_urdf(reread, UrdfOptions(path_mode=PathMode.ABSOLUTE)) == first


@pytest.mark.parametrize(
    "robot", [r for r in ROBOTS if r.name not in BROKEN][::7], ids=lambda r: f"{r.corpus}:{r.name}"
)
def test_yourdfpy_sees_the_same_links_and_joints(robot: CorpusRobot, tmp_path: Path) -> None:
    source, out = _roundtrip(robot)
    a = yourdfpy.URDF(yourdfpy.URDF._parse_robot(_xml(source)), build_scene_graph=False, load_meshes=False)
    b = yourdfpy.URDF(yourdfpy.URDF._parse_robot(_xml(out)), build_scene_graph=False, load_meshes=False)
    assert [link.name for link in a.robot.links] == [link.name for link in b.robot.links]
    assert sorted(j.name for j in a.robot.joints) == sorted(j.name for j in b.robot.joints)
    masses_a = {link.name: link.inertial.mass if link.inertial else None for link in a.robot.links}
    masses_b = {link.name: link.inertial.mass if link.inertial else None for link in b.robot.links}
    assert masses_a == masses_b


def _xml(text: str):  # type: ignore[no-untyped-def]
    from lxml import etree

    return etree.fromstring(text.encode("utf-8"), etree.XMLParser(remove_comments=True, resolve_entities=False))


_FIXED_MIMIC = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="lead" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="5" velocity="1"/></joint>
  <joint name="weld" type="fixed"><parent link="b"/><child link="c"/>
    <mimic joint="lead" multiplier="2"/></joint>
</robot>"""


def test_mimic_on_a_fixed_joint_is_left_out_of_urdf() -> None:
    """It has no effect (the verifier's 'ignored-mimic'), and Newton's add_urdf refuses the file
    (talos_reduced)."""
    loaded = load_string(_FIXED_MIMIC)
    text = emit_urdf(loaded.robot, UrdfOptions())
    assert "<mimic" not in text and '<joint name="weld" type="fixed">' in text
