"""Nothing written means nothing written, and nothing escapes (issue 34): MJCF's converted meshes
are staged with the rest of the output, are never written through a link out of the output folder
nor made from a file outside the input's roots, and ``view`` embeds no such file."""

from __future__ import annotations

import json
import os
import re
import shutil
from pathlib import Path

import pytest

from robodesc.cli import main
from tests.fuzz.fuzzer import ASCII_STL

SEEDS = Path(__file__).parent / "seeds"
# ASCII_STL: MuJoCo reads binary STL only, so -t mjcf converts this one to OBJ under meshes/.


def _robot(folder: Path, mesh_uri: str, *, bad_inertia: bool = False) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    text = (SEEDS / "arm.urdf").read_text().replace("meshes/finger.stl", mesh_uri)
    if bad_inertia:  # a warning: --strict refuses the run after the meshes were converted
        text = text.replace('izz="0.001"', 'izz="1e30"')
    path = folder / "arm.urdf"
    path.write_text(text)
    return path


def test_failed_mjcf_run_leaves_no_converted_mesh_nor_folder(tmp_path: Path) -> None:
    robot = tmp_path / "robot"
    (robot / "meshes").mkdir(parents=True)
    (robot / "meshes" / "t.stl").write_text(ASCII_STL)
    source = _robot(robot, "meshes/t.stl", bad_inertia=True)
    out = tmp_path / "new" / "deeper" / "robot.xml"
    assert main(["compile", str(source), "-t", "mjcf", "-o", str(out), "--strict", "-q"]) == 2
    assert not (tmp_path / "new").exists()
    # An existing folder keeps what it had, and only that.
    shared = tmp_path / "shared"
    (shared / "meshes").mkdir(parents=True)
    (shared / "meshes" / "other_robot.obj").write_text("v 0 0 0\n")
    assert main(["compile", str(source), "-t", "mjcf", "-o", str(shared / "robot.xml"), "--strict", "-q"]) == 2
    assert sorted(p.name for p in shared.rglob("*")) == ["meshes", "other_robot.obj"]
    # The same run without --strict converts the mesh into the output's meshes/.
    assert main(["compile", str(source), "-t", "mjcf", "-o", str(shared / "robot.xml"), "-q"]) == 0
    assert len(list((shared / "meshes").glob("t_*.obj"))) == 1


def test_converted_meshes_are_not_written_through_a_link(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    robot = tmp_path / "robot"
    (robot / "meshes").mkdir(parents=True)
    (robot / "meshes" / "t.stl").write_text(ASCII_STL)
    source = _robot(robot, "meshes/t.stl")
    outside = tmp_path / "outside"
    outside.mkdir()
    out = tmp_path / "out"
    out.mkdir()
    os.symlink(outside, out / "meshes")
    assert main(["compile", str(source), "-t", "mjcf", "-o", str(out / "robot.xml")]) == 2
    err = capsys.readouterr().err
    assert "outside the output folder" in err and "Traceback" not in err
    assert list(outside.iterdir()) == []
    assert sorted(p.name for p in out.iterdir()) == ["meshes"]


def test_mesh_outside_the_roots_is_not_converted(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "elsewhere").mkdir()
    (tmp_path / "elsewhere" / "t.stl").write_text(ASCII_STL)
    source = _robot(tmp_path / "robot", "../elsewhere/t.stl")
    out = tmp_path / "out" / "robot.xml"
    assert main(["compile", str(source), "-t", "mjcf", "-o", str(out), "--copy-meshes"]) == 0
    err = capsys.readouterr().err
    # -t mjcf places its meshes itself (the copy pass does not run for it): one refusal, the writer's.
    assert "it is not converted to OBJ" in err and "(--copy-meshes refuses the same file)" in err
    assert sorted(p.name for p in out.parent.iterdir()) == ["robot.xml", "scene.xml"]


def test_view_embeds_no_file_outside_the_roots_and_names_files_as_typed(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "elsewhere").mkdir()
    shutil.copy(SEEDS / "meshes" / "finger.stl", tmp_path / "elsewhere" / "finger.stl")
    robot = tmp_path / "robot"
    (robot / "meshes").mkdir(parents=True)
    (robot / "meshes" / "broken.stl").write_text("solid x\nvertex 1 2\n")
    text = (SEEDS / "arm.urdf").read_text().replace("meshes/finger.stl", "../elsewhere/finger.stl")
    text = text.replace('<sphere radius="0.02"/>', '<mesh filename="meshes/broken.stl"/>')
    (robot / "arm.urdf").write_text(text)
    monkeypatch.chdir(tmp_path)
    assert main(["view", "robot/arm.urdf", "-t", "usd", "-o", "page.html"]) == 0
    page = (tmp_path / "page.html").read_text()
    found = re.search(r'<script id="robodesc-data" type="application/json">(.*?)</script>', page, re.S)
    assert found is not None
    data = json.loads(found.group(1).replace("<\\/", "</"))
    assert data["meshes"] == [None, None]
    assert data["mesh_notes"] == [
        "../elsewhere/finger.stl: outside the input's folder and its packages' roots; not embedded",
        "meshes/broken.stl: file is too short to be an STL mesh",
    ]
    codes = [f["code"] for f in data["findings"]]
    assert "view-mesh-not-read" in codes
    assert str(tmp_path) not in page
    assert any(f["where"] == "robot/arm.urdf:16" for f in data["findings"])
