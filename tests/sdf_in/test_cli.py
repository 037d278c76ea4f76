"""SDF models through the commands: compile to every file target (each checked by its consumer),
inspect, validate, view and render; a model folder as input; a world sent to --world."""

from __future__ import annotations

from pathlib import Path

import pytest

from robodesc.cli import main

DATA = Path(__file__).parent / "data"
FEATURES = DATA / "feature_bot.sdf"
MODEL_PATH = ["--model-path", str(DATA / "models")]


@pytest.mark.parametrize(("target", "suffix"), [("urdf", "urdf"), ("sdf", "sdf"), ("usd", "usda"), ("mjcf", "xml")])
def test_compile_every_target(target: str, suffix: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / f"robot.{suffix}"
    assert main(["compile", str(FEATURES), *MODEL_PATH, "-t", target, "-o", str(out)]) == 0
    printed = capsys.readouterr()
    # Every degree of freedom (the universal joint's two) and every kilogram; the consumer's check passed.
    # (Links and joints are not counted: targets may merge the fixed joint.)
    assert "9 DOF, 5.57" in printed.out + printed.err
    assert "passed" in printed.out + printed.err


def test_inspect_view_and_validate(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["inspect", str(FEATURES), *MODEL_PATH]) == 0
    shown = capsys.readouterr().out
    assert "robot 'feature_bot'" in shown and "hand::finger::tip  <- hand::finger::bend [revolute]" in shown
    page = tmp_path / "feature_bot.html"
    assert main(["view", str(FEATURES), *MODEL_PATH, "-o", str(page)]) == 0
    assert page.stat().st_size > 1000
    assert main(["validate", str(FEATURES), *MODEL_PATH, "-t", "mjcf"]) == 0


def test_render(tmp_path: Path) -> None:
    pytest.importorskip("mujoco")
    picture = tmp_path / "feature_bot.png"
    assert main(["render", str(FEATURES), *MODEL_PATH, "-o", str(picture)]) == 0
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_model_folder_as_input(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["inspect", str(DATA / "models" / "finger_part")]) == 0
    assert "robot 'finger_part': 2 links, 1 joints" in capsys.readouterr().out


def test_world_file_is_sent_to_world(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    world = tmp_path / "empty.world"
    world.write_text('<sdf version="1.9"><world name="w"/></sdf>')
    assert main(["inspect", str(world)]) == 2
    assert "give it with --world" in capsys.readouterr().err


def test_batch_discovers_models_not_worlds(tmp_path: Path) -> None:
    from robodesc.batch.discover import discover

    (tmp_path / "robot.sdf").write_text('<sdf version="1.9"><model name="r"><link name="a"/></model></sdf>')
    (tmp_path / "place.world").write_text('<sdf version="1.9"><world name="w"><model name="m"/></world></sdf>')
    assert [job for _, job in discover(str(tmp_path))] == ["robot"]


def test_xml_suffix_is_chosen_by_content(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "robot.xml"
    path.write_text((DATA / "models" / "finger_part" / "model.sdf").read_text())
    assert main(["inspect", str(path)]) == 0
    assert "robot 'finger_part'" in capsys.readouterr().out
