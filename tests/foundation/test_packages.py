"""Resolving package://, model://, file://, relative and absolute references."""

from __future__ import annotations

from pathlib import Path

import pytest

from robodesc.frontends.packages import PackageResolver
from robodesc.ir.diagnostics import BrokenReferenceError, PathEscapeError
from tests.conftest import QUADSDK, SPIRIT_XACRO


def _pkg(root: Path, name: str, with_xml: bool = True) -> Path:
    root.mkdir(parents=True, exist_ok=True)
    if with_xml:
        (root / "package.xml").write_text(f"<package format='3'><name>{name}</name></package>")
    (root / "meshes").mkdir(exist_ok=True)
    (root / "meshes" / "m.stl").write_text("solid m\nendsolid m\n")
    return root


def test_explicit_package_wins(tmp_path: Path) -> None:
    a = _pkg(tmp_path / "a", "pkg")
    b = _pkg(tmp_path / "b", "pkg")
    r = PackageResolver(explicit={"pkg": str(b)}, environ={"ROS_PACKAGE_PATH": str(a)})
    res = r.resolve("package://pkg/meshes/m.stl", None)
    assert res.path == str(b / "meshes" / "m.stl")
    assert res.package == ("pkg", "meshes/m.stl")


def test_package_xml_above_input_and_beside_it(tmp_path: Path) -> None:
    ws = tmp_path / "ws" / "src"
    own = _pkg(ws / "robot_description", "robot_description")
    other = _pkg(ws / "some_folder", "shared_meshes")
    bare = _pkg(ws / "decals", "decals", with_xml=False)
    urdf = own / "urdf" / "r.urdf"
    urdf.parent.mkdir()
    urdf.write_text("<robot name='r'/>")
    r = PackageResolver(input_file=str(urdf), environ={})
    assert r.resolve("package://robot_description/meshes/m.stl", None).path == str(own / "meshes" / "m.stl")
    assert r.resolve("package://shared_meshes/meshes/m.stl", None).path == str(other / "meshes" / "m.stl")
    found = r.find_package("decals")
    assert found is not None and found[0] == str(bare) and "no package.xml" in found[1]


def test_ros_package_path_and_ament_prefix_path(tmp_path: Path) -> None:
    _pkg(tmp_path / "src" / "deep" / "p1", "p1")
    prefix = tmp_path / "install"
    _pkg(prefix / "share" / "p2", "p2")
    r = PackageResolver(environ={"ROS_PACKAGE_PATH": str(tmp_path / "src"), "AMENT_PREFIX_PATH": str(prefix)})
    assert r.find_package("p1") == (str(tmp_path / "src" / "deep" / "p1"), "ROS_PACKAGE_PATH")
    assert r.find_package("p2") == (str(prefix / "share" / "p2"), "AMENT_PREFIX_PATH")
    with pytest.raises(BrokenReferenceError, match=r"package .p3. not found .*--package p3=DIR"):
        r.resolve("package://p3/x.stl", None)


def test_escape_through_dotdot_is_refused(tmp_path: Path) -> None:
    root = _pkg(tmp_path / "p", "p")
    r = PackageResolver(explicit={"p": str(root)}, environ={})
    with pytest.raises(PathEscapeError, match="leaves its package root"):
        r.resolve("package://p/../../etc/passwd", None)
    with pytest.raises(PathEscapeError):
        r.resolve("package://p/meshes/../../p2/x.stl", None)
    assert r.resolve("package://p/meshes/../meshes/m.stl", None).path == str(root / "meshes" / "m.stl")


def test_file_model_relative_absolute(tmp_path: Path) -> None:
    models = tmp_path / "models"
    _pkg(models / "table", "table", with_xml=False)
    r = PackageResolver(environ={"GZ_SIM_RESOURCE_PATH": str(models)})
    assert r.resolve("model://table/meshes/m.stl", None).path == str(models / "table" / "meshes" / "m.stl")
    assert r.resolve(f"file://{tmp_path}/a%20b.stl", None).path == str(tmp_path / "a b.stl")
    assert r.resolve("meshes/x.stl", str(tmp_path)).path == str(tmp_path / "meshes" / "x.stl")
    assert r.resolve("/abs/x.stl", str(tmp_path)).path == "/abs/x.stl"
    with pytest.raises(BrokenReferenceError, match="unsupported URI scheme"):
        r.resolve("http://example.com/x.stl", None)


def test_quadsdk_decal_package_resolves_beside_spirit() -> None:
    r = PackageResolver(input_file=str(SPIRIT_XACRO), environ={})
    found = r.find_package("objects_description")
    assert found is not None and Path(found[0]) == QUADSDK / "objects_description"
