"""What the MJCF target writes so that every consumer reads it, not only MuJoCo: a floor under a welded
robot's colliders, OBJ files MuJoCo can index, and an explicit <inertial> on every jointed body
(Newton's add_mjcf; docs/mjcf.md, "Consumers")."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import mujoco
import pytest

from robodesc.api import compile_to_mjcf
from robodesc.emit.mjcf.floor import FLOOR_GAP
from robodesc.emit.mjcf.meshes import obj_layout_mixed
from tests.mjcf.helpers import load_clean

INERTIA = '<inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/>'


def _legged(z: float, fixed: str = "") -> str:
    """A base with one leg hanging ``z`` below it: a box collider whose bottom is at ``z - 0.05``."""
    return f"""<robot name="hanging">{fixed}
  <link name="base"><inertial><mass value="2"/>{INERTIA}</inertial>
    <collision><origin xyz="0 0 0.05"/><geometry><box size="0.2 0.2 0.05"/></geometry></collision></link>
  <link name="leg"><inertial><mass value="0.5"/>{INERTIA}</inertial>
    <collision><origin xyz="0 0 {z}"/><geometry><box size="0.04 0.04 0.1"/></geometry></collision></link>
  <joint name="hip" type="revolute"><parent link="base"/><child link="leg"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="20" velocity="5"/></joint>
</robot>"""


def _floor_z(scene: Path) -> float:
    floor = ET.parse(scene).getroot().find(".//geom[@name='floor']")
    assert floor is not None
    return float(floor.get("pos", "0 0 0").split()[2])


def test_floor_goes_under_a_welded_robot(tmp_path: Path) -> None:
    """A welded robot with colliders below z = 0: the floor sits under them (it went NaN in
    mujoco_menagerie's test with the floor through the legs: pybullet_data's spirit40)."""
    result = compile_to_mjcf(_legged(-0.3), str(tmp_path / "robot.xml"), fix_base=True)
    assert result.validation is not None and result.validation.ok
    z = _floor_z(tmp_path / "scene.xml")
    lowest = -0.3 - 0.05
    assert lowest - FLOOR_GAP - 1e-4 <= z <= lowest - FLOOR_GAP
    assert "mjcf-floor-lowered" in {f.code for f in result.findings}
    # Nothing touches the floor at the start.
    model = load_clean(tmp_path / "scene.xml")
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert data.ncon == 0


@pytest.mark.parametrize(("z", "fix_base"), [(0.2, True), (-0.3, False)], ids=["above", "floating"])
def test_floor_stays_at_zero(z: float, fix_base: bool, tmp_path: Path) -> None:
    """A welded robot above the floor keeps it at 0 (the scene's text unchanged); a floating one is
    raised onto it instead."""
    result = compile_to_mjcf(_legged(z), str(tmp_path / "robot.xml"), fix_base=fix_base)
    assert result.validation is not None and result.validation.ok
    text = (tmp_path / "scene.xml").read_text()
    assert re.search(r'<geom name="floor" size=', text)
    assert "mjcf-floor-lowered" not in {f.code for f in result.findings}


MIXED_OBJ = """o table
v -0.5 -0.5 0.5
v 0.5 -0.5 0.5
v -0.5 0.5 0.5
v 0.5 0.5 0.5
v -0.5 0.5 -0.5
v 0.5 0.5 -0.5
v -0.5 -0.5 -0.5
v 0.5 -0.5 -0.5
vt 0 0
vt 1 0
vt 0 1
vt 1 1
vn 0 0 1
f 1/1/1 2/2/1 3/3/1
f 3/3/1 2/2/1 4/4/1
f 3 4 5
f 5 4 6
f 5 6 7
f 7 6 8
f 7 8 1
f 1 8 2
f 2 8 4
f 4 8 6
f 7 1 5
f 5 1 3
"""


def test_obj_mixing_face_layouts_is_converted(tmp_path: Path) -> None:
    """pybullet_data's table_square.obj: faces with normals (``f 1/1/1``) and without (``f 1 2 3``) in
    one file; MuJoCo refuses it ("normal index out of bounds"). It is written as a plain OBJ."""
    mesh = tmp_path / "src" / "table.obj"
    mesh.parent.mkdir()
    mesh.write_text(MIXED_OBJ)
    with pytest.raises(ValueError, match="normal index"):
        mujoco.MjModel.from_xml_string(f'<mujoco><asset><mesh file="{mesh}"/></asset></mujoco>')
    urdf = f"""<robot name="t"><link name="top"><inertial><mass value="1"/>{INERTIA}</inertial>
      <visual><geometry><mesh filename="{mesh}" scale="0.6 0.6 0.08"/></geometry></visual>
      <collision><geometry><mesh filename="{mesh}" scale="0.6 0.6 0.08"/></geometry></collision></link></robot>"""
    # A file beside the mesh: converting reads the mesh into the output, only from the input's folder.
    (tmp_path / "src" / "t.urdf").write_text(urdf)
    result = compile_to_mjcf(str(tmp_path / "src" / "t.urdf"), str(tmp_path / "out/robot.xml"))
    assert result.validation is not None and result.validation.ok
    assert "mjcf-obj-layout" in {f.code for f in result.warnings}
    model = load_clean(tmp_path / "out/robot.xml")
    assert model.nmesh == 1
    # Scale applied while converting: the mesh spans the scaled box (MuJoCo turns a mesh into its
    # principal axes, so the spans are compared sorted).
    span = sorted(model.mesh_vert.max(axis=0) - model.mesh_vert.min(axis=0))
    assert span == pytest.approx([0.08, 0.6, 0.6], rel=1e-6)


@pytest.mark.parametrize(
    ("faces", "mixed"),
    [
        ("f 1 2 3\nf 1 3 4\n", False),
        ("f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n", False),
        ("f 1/1/1 2/2/1 3/3/1\n", False),
        ("f 1/1 2/2 3/3\nf 1 2 3\n", True),
        ("f 1//1 2//1 3//1\nf 1 3 4\n", True),
        ("f 1/1/1 2/2/1 3/3/1\nf 1//1 2//1 3//1\n", True),
    ],
)
def test_obj_layout_detection(faces: str, mixed: bool, tmp_path: Path) -> None:
    path = tmp_path / "m.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n" + faces)
    assert obj_layout_mixed(str(path)) is mixed


def test_jointed_body_with_welded_mass_has_an_inertial(tmp_path: Path) -> None:
    """A jointed link without mass whose mass its welded child carries: MuJoCo takes the child's mass
    as the body's, and writes no token mass; Newton's add_mjcf (with inertiafromgeom="false") refuses
    a jointed body without <inertial>, so a zero one is written. (With fixed links kept as bodies:
    by default the payload is fused into the carrier, which then carries the mass itself.)"""
    urdf = f"""<robot name="w">
      <link name="base"><inertial><mass value="1"/>{INERTIA}</inertial></link>
      <link name="carrier"/>
      <link name="payload"><inertial><origin xyz="0.1 0 0"/><mass value="0.3"/>{INERTIA}</inertial></link>
      <joint name="j" type="revolute"><parent link="base"/><child link="carrier"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="5" velocity="1"/></joint>
      <joint name="weld" type="fixed"><parent link="carrier"/><child link="payload"/></joint>
    </robot>"""
    result = compile_to_mjcf(urdf, str(tmp_path / "robot.xml"), merge_fixed=False)
    assert result.validation is not None and result.validation.ok
    assert "mjcf-massless-body" not in {f.code for f in result.warnings}
    root = ET.parse(tmp_path / "robot.xml").getroot()
    carrier = root.find(".//body[@name='carrier']")
    assert carrier is not None
    inertial = carrier.find("inertial")
    assert inertial is not None and float(inertial.get("mass", "nan")) == 0.0
    model = load_clean(tmp_path / "robot.xml")
    bid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "carrier")
    assert model.body_subtreemass[bid] == pytest.approx(0.3)
