"""The corpus report script runs on the small subset and writes a deterministic file."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest
from helpers import ROOT


def _script():  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location("corpus_report", ROOT / "benchmarks" / "corpus_report.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["corpus_report"] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


def test_small_subset_urdf_report(tmp_path: Path) -> None:
    script = _script()
    out = tmp_path / "report.md"
    assert script.main(["--subset", "small", "--targets", "urdf", "--out", str(out)]) == 0
    text = out.read_text(encoding="utf-8")
    if "| robots | 0 |" in text:
        pytest.skip("no corpus installed")
    assert "## Source defects" in text and "## Failures" in text
    # anymal_c's defective inertia is reported as a source defect, named, never a crash.
    assert "link 'depth_camera_front_camera': [bad-inertia]" in text
    assert "| not converted: robodesc crashed | 0 |" in text
    assert "robodesc crashed:" not in text
    assert script.main(["--subset", "small", "--targets", "urdf", "--out", str(out), "--check"]) == 0


def test_consumer_verdicts_become_extra_columns(tmp_path: Path) -> None:
    script = _script()
    path = tmp_path / "consumers.json"
    path.write_text(
        '{"spirit": {"newton": "pass", "newton_isaac": {"status": "FAIL"}, "isaac_importer": null},'
        ' "other": {"newton": true}}'
    )
    consumers = script.load_consumers(str(path))
    robot = script.CorpusRobot("quadsdk", "spirit", "spirit.urdf.xacro")
    result = script.RobotResult(robot, links=3, targets=[script.TargetResult("urdf", "yes")])
    text = script.render([result], ["urdf"], "small", consumers)
    assert "| note | newton | newton_isaac | isaac_importer |" in text
    assert "| pass | FAIL | – |" in text
    # Without the file the table keeps its columns.
    assert script.load_consumers(str(tmp_path / "absent.json")) == {}
    assert "newton" not in script.render([result], ["urdf"], "small", {})


def test_dynamics_verdicts_become_a_column(tmp_path: Path) -> None:
    script = _script()
    path = tmp_path / "dynamics.json"
    path.write_text(
        '{"quadsdk/spirit": {"status": "ok", "agreement": {"hold-fixed": "agree", "drop": "agree", "slide": "n/a"}}}'
    )
    cells = script.load_dynamics(str(path))
    assert cells == {"quadsdk/spirit": {"dynamics": "ok: hold agree, drop agree"}}
    robot = script.CorpusRobot("quadsdk", "spirit", "spirit.urdf.xacro")
    result = script.RobotResult(robot, links=3, targets=[script.TargetResult("urdf", "yes")])
    text = script.render([result], ["urdf"], "small", cells)
    assert "| note | dynamics |" in text and "| ok: hold agree, drop agree |" in text
