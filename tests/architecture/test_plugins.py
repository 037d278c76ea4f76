"""A target and a frontend added from outside the package run through every driver command:
``compile``, ``validate``, ``batch`` and ``inspect``, with no driver code touched."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path

import pytest

from robodesc.cli import main
from robodesc.frontends.load import FRONTENDS
from robodesc.targets import TARGETS

PLUGIN = ["--plugin", "tests.architecture.toy"]
TOY = "link base 2.0\nlink arm 0.5\njoint j base arm\n"


@pytest.fixture(autouse=True)
def _clean_tables() -> Iterator[None]:
    """Loading the plugin adds it to the tables: leave them as they were for the other tests."""
    saved = dict(TARGETS), dict(FRONTENDS)
    yield
    for table, before in zip((TARGETS, FRONTENDS), saved, strict=True):
        table.clear()
        table.update(before)


@pytest.fixture
def robot(tmp_path: Path) -> Path:
    path = tmp_path / "two.toy"
    path.write_text(TOY)
    return path


def test_compile_with_the_targets_own_flag(robot: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "two.toyjson"
    assert main(["compile", str(robot), "-t", "toy", "-o", str(out), "--toy-indent", "2", *PLUGIN]) == 0
    assert json.loads(out.read_text()) == {"name": "two", "links": {"base": 2.0, "arm": 0.5}}
    assert out.read_text().startswith('{\n  "name"')  # --toy-indent reached the target's options
    assert "validation by json passed" in capsys.readouterr().err


def test_help_lists_the_target_and_its_flag(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["compile", "--help", *PLUGIN])
    text = capsys.readouterr().out
    assert "toy     a toy JSON target (.toyjson)" in text and "--toy-indent N" in text and "toy robots (.toy)" in text


def test_validate_and_inspect(robot: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", str(robot), "-t", "toy", *PLUGIN]) == 0
    assert "mass" in capsys.readouterr().out
    assert main(["inspect", str(robot), *PLUGIN]) == 0
    assert "arm" in capsys.readouterr().out


def test_content_decides_between_frontends_of_one_suffix(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``.xml`` is URDF's suffix too: the root element decides."""
    toy = tmp_path / "toy.xml"
    toy.write_text("<toy>\n" + TOY + "</toy>\n")
    assert main(["inspect", str(toy), *PLUGIN]) == 0
    assert "arm" in capsys.readouterr().out
    neither = tmp_path / "other.xml"
    neither.write_text("<scene/>")  # no frontend reads <scene>
    assert main(["inspect", str(neither), *PLUGIN]) == 2
    err = capsys.readouterr().err
    assert "other.xml" in err and "URDF (.urdf, .xml)" in err and "toy robots (.toy)" in err


def test_batch(robot: Path, tmp_path: Path) -> None:
    out = tmp_path / "batch"
    assert main(["batch", str(robot.parent), "-t", "toy", "-o", str(out), "-q", *PLUGIN]) == 0
    assert json.loads((out / "two" / "two.toyjson").read_text())["links"] == {"base": 2.0, "arm": 0.5}
    summary = json.loads((out / "summary.json").read_text())
    assert [j["status"] for j in summary["jobs"]] == ["ok"]
