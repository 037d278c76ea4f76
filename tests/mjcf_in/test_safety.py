"""Untrusted MJCF: no escape from the model's folder, no code, no memory blow-up, clear messages."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from robodesc.frontends.load import load_path
from robodesc.ir.diagnostics import BrokenReferenceError, ParseError, PathEscapeError

BODY = '<worldbody><body name="b"><freejoint/><geom type="sphere" size="0.1"/></body></worldbody>'


def _model(folder: Path, inner: str, name: str = "model.xml") -> Path:
    path = folder / name
    path.write_text(f'<mujoco model="m">{inner}</mujoco>')
    return path


def test_include_outside_the_folder_is_refused(tmp_path: Path) -> None:
    outside = tmp_path / "outside.xml"
    outside.write_text(f"<mujoco>{BODY}</mujoco>")
    folder = tmp_path / "model"
    folder.mkdir()
    path = _model(folder, '<include file="../outside.xml"/>')
    with pytest.raises(PathEscapeError, match="outside the model's folder") as err:
        load_path(str(path))
    assert "model.xml:1" in str(err.value)


def test_include_through_a_symlink_out_is_refused(tmp_path: Path) -> None:
    outside = tmp_path / "secret.xml"
    outside.write_text(f"<mujoco>{BODY}</mujoco>")
    folder = tmp_path / "model"
    folder.mkdir()
    os.symlink(outside, folder / "parts.xml")
    with pytest.raises(PathEscapeError):
        load_path(str(_model(folder, '<include file="parts.xml"/>')))


def test_include_cycle_is_refused(tmp_path: Path) -> None:
    (tmp_path / "a.xml").write_text('<mujoco><include file="model.xml"/></mujoco>')
    with pytest.raises(ParseError, match="includes itself"):
        load_path(str(_model(tmp_path, '<include file="a.xml"/>' + BODY)))


def test_included_elements_name_their_own_file(tmp_path: Path) -> None:
    (tmp_path / "robot.xml").write_text(
        '<mujoco model="inner">\n<worldbody>\n<body name="b">\n<joint type="ball" range="0 30"/>\n'
        '<geom type="sphere" size="0.1"/></body></worldbody></mujoco>'
    )
    result = load_path(str(_model(tmp_path, '<include file="robot.xml"/>', "scene.xml")))
    assert result.robot.name == "inner"  # a scene is named after the robot it includes
    limit = next(f for f in result.findings if f.code == "mjcf-ball-limit")
    assert limit.loc is not None and limit.loc.file == str(tmp_path / "robot.xml") and limit.loc.line == 4


def test_doctype_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "model.xml"
    path.write_text('<!DOCTYPE m [<!ENTITY x SYSTEM "/etc/passwd">]><mujoco>' + BODY + "</mujoco>")
    with pytest.raises(ParseError, match="DOCTYPE"):
        load_path(str(path))


def test_replicate_bomb_is_refused(tmp_path: Path) -> None:
    inner = (
        '<worldbody><replicate count="1000" offset="0.1 0 0"><replicate count="1000" offset="0 0.1 0">'
        '<body><geom type="sphere" size="0.01"/></body></replicate></replicate></worldbody>'
    )
    with pytest.raises(ParseError, match="more than 10000 bodies"):
        load_path(str(_model(tmp_path, inner)))


def test_plugins_are_removed_with_a_warning(tmp_path: Path) -> None:
    inner = (
        '<extension><plugin plugin="mujoco.elasticity.cable"/></extension>'
        '<worldbody><body name="b"><freejoint/><geom type="sphere" size="0.1"/>'
        '<plugin plugin="mujoco.elasticity.cable" instance="x"/></body></worldbody>'
    )
    result = load_path(str(_model(tmp_path, inner)))
    removed = [f for f in result.findings if f.code == "mjcf-removed"]
    assert len(removed) == 2 and all("native code" in f.message for f in removed)
    assert result.robot.link("b").inertial is not None


def test_a_mesh_that_is_not_a_file_is_missing(tmp_path: Path) -> None:
    inner = (
        '<asset><mesh name="m" file="/dev/zero.stl"/><mesh name="p" file="pipe.stl"/></asset>'
        '<worldbody><body name="b"><freejoint/><geom type="mesh" mesh="m"/><geom type="mesh" mesh="p"/>'
        '<inertial mass="1" diaginertia="1 1 1" pos="0 0 0"/></body></worldbody>'
    )
    os.mkfifo(tmp_path / "pipe.stl")
    result = load_path(str(_model(tmp_path, inner)))
    missing = [f for f in result.findings if f.code == "missing-mesh"]
    assert len(missing) == 2
    assert result.robot.link("b").inertial.mass == pytest.approx(1.0)  # type: ignore[union-attr]


def test_mujoco_errors_are_messages(tmp_path: Path) -> None:
    inner = '<worldbody><body name="b"><joint type="bogus"/><geom size="0.1"/></body></worldbody>'
    with pytest.raises(ParseError, match="MuJoCo cannot compile this model") as err:
        load_path(str(_model(tmp_path, inner)))
    assert "Traceback" not in str(err.value)


def test_missing_include(tmp_path: Path) -> None:
    with pytest.raises(BrokenReferenceError, match="file not found"):
        load_path(str(_model(tmp_path, '<include file="nowhere.xml"/>')))


def test_memory_sizes_are_not_allocated(tmp_path: Path) -> None:
    """<size memory> would make MuJoCo allocate an arena when robodesc makes MjData (loop closures)."""
    inner = '<size memory="900G"/>' + BODY
    result = load_path(str(_model(tmp_path, inner)))
    assert result.robot.link("b").inertial is not None


def test_deformables_are_removed_with_warnings(tmp_path: Path) -> None:
    inner = (
        '<worldbody><body name="b"><freejoint/><geom size="0.1"/></body>'
        '<flexcomp name="cloth" type="grid" count="300 300 1" spacing="0.01 0.01 0.01" dim="2"/>'
        "</worldbody>"
    )
    result = load_path(str(_model(tmp_path, inner)))
    lost = [f for f in result.findings if f.code == "mjcf-not-held"]
    assert len(lost) == 1 and "'cloth'" in lost[0].message and lost[0].loc is not None
    assert [link.name for link in result.robot.links] == ["b"]


def test_attached_model_outside_the_folder_is_refused(tmp_path: Path) -> None:
    outside = tmp_path / "other.xml"
    outside.write_text(f"<mujoco>{BODY}</mujoco>")
    folder = tmp_path / "model"
    folder.mkdir()
    path = _model(folder, '<asset><model name="o" file="../other.xml"/></asset>' + BODY)
    with pytest.raises(PathEscapeError, match="outside the model's folder"):
        load_path(str(path))


def test_attached_model_that_reads_files_is_refused(tmp_path: Path) -> None:
    (tmp_path / "part.xml").write_text('<mujoco><include file="/etc/passwd"/></mujoco>')
    path = _model(tmp_path, '<asset><model name="p" file="part.xml"/></asset>' + BODY)
    with pytest.raises(ParseError, match="not supported yet"):
        load_path(str(path))


def test_mujoco_errors_point_at_the_named_element(tmp_path: Path) -> None:
    path = tmp_path / "model.xml"
    path.write_text(
        '<mujoco>\n<worldbody>\n<body name="b"><joint name="knee"/><geom size="0.1"/></body>\n</worldbody>\n'
        '<actuator>\n<position name="act" joint="nothere"/>\n</actuator>\n</mujoco>\n'
    )
    with pytest.raises(ParseError, match="unknown transmission target 'nothere'") as err:
        load_path(str(path))
    assert err.value.loc is not None and err.value.loc.line == 6


def test_height_fields_are_not_decoded(tmp_path: Path) -> None:
    """A height field's PNG (or nrow x ncol samples) of any size is never given to MuJoCo."""
    (tmp_path / "terrain.png").write_bytes(b"not a png at all")
    inner = (
        '<asset><hfield name="terrain" file="terrain.png" size="1 1 0.1 0.1"/>'
        '<hfield name="huge" nrow="100000" ncol="100000" size="1 1 0.1 0.1"/></asset>'
        '<worldbody><geom name="ground" type="hfield" hfield="terrain"/>'
        '<body name="b"><freejoint/><geom size="0.1"/></body></worldbody>'
    )
    result = load_path(str(_model(tmp_path, inner)))
    lost = [f for f in result.findings if f.code == "mjcf-shape-not-held"]
    assert len(lost) == 1 and "'ground'" in lost[0].message


def test_include_fan_out_is_capped(tmp_path: Path) -> None:
    """Each file includes the next one many times: a few bytes that would expand exponentially."""
    (tmp_path / "leaf.xml").write_text('<mujoco><worldbody><body><geom size="0.1"/></body></worldbody></mujoco>')
    for level in range(6):
        child = "leaf.xml" if level == 0 else f"level{level - 1}.xml"
        (tmp_path / f"level{level}.xml").write_text("<mujoco>" + f'<include file="{child}"/>' * 10 + "</mujoco>")
    with pytest.raises(ParseError, match="more than 256 includes"):
        load_path(str(_model(tmp_path, '<include file="level5.xml"/>')))
