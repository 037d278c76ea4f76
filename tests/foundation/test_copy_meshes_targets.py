"""``--copy-meshes`` means one thing for every target: afterwards the output refers to no mesh or
texture file outside its folder. Each target copies only the kinds of file it refers to
(``Target.copies``): USD embeds mesh geometry and refers to textures; MJCF's writer places its meshes
itself and writes no texture, so there the flag changes nothing."""

from __future__ import annotations

from pathlib import Path

import pytest
import trimesh

from robodesc.cli import main
from robodesc.targets import TARGETS, target_spec

# A box mesh with a textured material, beside the URDF.
URDF = """<robot name="textured">
  <material name="skin"><color rgba="1 1 1 1"/><texture filename="skin.png"/></material>
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><mesh filename="part.stl"/></geometry><material name="skin"/></visual>
    <collision><geometry><mesh filename="part.stl"/></geometry></collision>
  </link>
</robot>
"""
# The smallest PNG: the copy pass checks a texture's signature.
PNG = bytes.fromhex(
    "89504e470d0a1a0a0000000d4948445200000001000000010802000000907753de0000000c4944415478da6360f8ff"
    "3f0005fe02fea7d6a0a60000000049454e44ae426082"
)


@pytest.fixture
def source(tmp_path: Path) -> Path:
    src = tmp_path / "src"
    src.mkdir()
    trimesh.creation.box(extents=(0.1, 0.2, 0.3)).export(src / "part.stl")
    (src / "skin.png").write_bytes(PNG)
    (src / "robot.urdf").write_text(URDF)
    return src / "robot.urdf"


def _files(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*") if p.is_file())


def test_every_target_says_what_it_copies() -> None:
    kinds = {name: target_spec(name).copies for name in TARGETS}
    assert kinds["usd"] == {"textures"} and kinds["mjcf"] == frozenset()
    assert all(kinds[name] == {"meshes", "textures"} for name in ("urdf", "sdf", "ros2", "isaac"))


def test_urdf_copies_mesh_and_texture(source: Path, tmp_path: Path) -> None:
    out = tmp_path / "out" / "robot.urdf"
    assert main(["compile", str(source), "-t", "urdf", "--copy-meshes", "-o", str(out), "--no-validate"]) == 0
    assert _files(out.parent) == ["meshes/part.stl", "meshes/skin.png", "robot.urdf"]
    text = out.read_text()
    assert 'filename="meshes/part.stl"' in text and 'filename="meshes/skin.png"' in text


def test_usd_embeds_the_mesh_and_copies_only_the_texture(source: Path, tmp_path: Path) -> None:
    from pxr import Usd, UsdGeom

    out = tmp_path / "out" / "robot.usda"
    assert main(["compile", str(source), "-t", "usd", "--copy-meshes", "-o", str(out), "--no-validate"]) == 0
    # Before: the mesh was copied too, and the writer then refused to read the copy (outside the
    # input's folder): the shape was left out.
    assert _files(out.parent) == ["meshes/skin.png", "robot.usda"]
    stage = Usd.Stage.Open(str(out))
    points = [
        len(UsdGeom.Mesh(p).GetPointsAttr().Get() or [])
        for p in stage.Traverse()
        if p.IsA(UsdGeom.Mesh) and UsdGeom.Imageable(p).ComputePurpose() != UsdGeom.Tokens.guide
    ]
    assert points and min(points) >= 8  # the box's geometry is in the layer
    assert "@./meshes/skin.png@" in out.read_text()


def test_usd_without_the_flag_refers_to_the_source_texture(source: Path, tmp_path: Path) -> None:
    out = tmp_path / "out" / "robot.usda"
    assert main(["compile", str(source), "-t", "usd", "-o", str(out), "--no-validate"]) == 0
    assert _files(out.parent) == ["robot.usda"]
    assert "@../src/skin.png@" in out.read_text()


def test_mjcf_is_the_same_with_or_without_the_flag(
    source: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    plain, copied = tmp_path / "plain" / "robot.xml", tmp_path / "copied" / "robot.xml"
    assert main(["compile", str(source), "-t", "mjcf", "-o", str(plain), "--no-validate"]) == 0
    capsys.readouterr()
    assert main(["compile", str(source), "-t", "mjcf", "--copy-meshes", "-v", "-o", str(copied), "--no-validate"]) == 0
    assert "the flag changes nothing" in capsys.readouterr().err
    assert _files(plain.parent) == _files(copied.parent)
    assert plain.read_text() == copied.read_text()
    assert not any(name.endswith(".png") for name in _files(copied.parent))
