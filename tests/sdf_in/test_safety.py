"""Untrusted SDF: hardened XML, no escape from a model's folder or the model roots, include loops
stopped, each refusal a message at its file and line."""

from __future__ import annotations

from pathlib import Path

import pytest

from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import ParseError

LINK = '<link name="a"><inertial><mass>1</mass></inertial>{inner}</link>'


def _model(folder: Path, inner: str, name: str = "model.sdf") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    path.write_text(
        f'<?xml version="1.0"?>\n<sdf version="1.9">\n<model name="{folder.name}">\n{inner}\n</model>\n</sdf>\n'
    )
    return path


def _config(folder: Path, sdf: str) -> None:
    (folder / "model.config").write_text(f'<model><name>{folder.name}</name><sdf version="1.9">{sdf}</sdf></model>')


def test_entities_are_refused(tmp_path: Path) -> None:
    path = tmp_path / "m.sdf"
    path.write_text(
        '<?xml version="1.0"?><!DOCTYPE sdf [<!ENTITY x SYSTEM "file:///etc/passwd">]>'
        '<sdf version="1.9"><model name="m"><link name="&x;"/></model></sdf>'
    )
    with pytest.raises(ParseError):
        load_path(str(path))


def test_model_config_naming_a_file_outside_is_refused(tmp_path: Path) -> None:
    _model(tmp_path, LINK.format(inner=""), "outside.sdf")
    folder = tmp_path / "thing"
    folder.mkdir()
    _config(folder, "../outside.sdf")
    with pytest.raises(ParseError, match="outside its folder"):
        load_path(str(folder))


def test_included_model_mesh_cannot_leave_its_folder(tmp_path: Path) -> None:
    (tmp_path / "secret.stl").write_bytes(b"solid x\nendsolid x\n")
    part = tmp_path / "models" / "part"
    _model(
        part,
        LINK.format(inner='<visual name="v"><geometry><mesh><uri>../../secret.stl</uri></mesh></geometry></visual>'),
    )
    _config(part, "model.sdf")
    top = _model(tmp_path / "robot", "<include><uri>model://part</uri></include>")
    loaded = load_path(str(top), LoadOptions(model_path=(str(tmp_path / "models"),)))
    (visual,) = loaded.robot.link("part::a").visuals
    assert getattr(visual.geometry, "path", "x") is None
    missing = next(f for f in loaded.findings.items if f.code == "mesh-missing")
    assert missing.loc is not None and missing.loc.file == str(part / "model.sdf") and missing.loc.line == 4


def test_model_uri_cannot_climb_out_of_the_roots(tmp_path: Path) -> None:
    _model(tmp_path / "elsewhere", LINK.format(inner=""))
    _config(tmp_path / "elsewhere", "model.sdf")
    top = _model(
        tmp_path / "models" / "robot", LINK.format(inner="") + "<include><uri>model://../../elsewhere</uri></include>"
    )
    loaded = load_path(str(top), LoadOptions(model_path=(str(tmp_path / "models" / "robot"),)))
    assert [link.name for link in loaded.robot.links] == ["a"]
    assert any(f.code == "sdf-include-missing" for f in loaded.findings.items)


def test_include_loop_is_stopped(tmp_path: Path) -> None:
    part = tmp_path / "loop"
    _model(part, LINK.format(inner="") + "<include><uri>model://loop</uri><name>again</name></include>")
    _config(part, "model.sdf")
    with pytest.raises(ParseError, match="nest more than"):
        load_path(str(part / "model.sdf"), LoadOptions(model_path=(str(tmp_path),)))
