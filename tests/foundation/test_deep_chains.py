"""Very deep chains (issue 26: a 50,000-link chain to every target, with validation, without a crash).

``benchmarks/deep_chain.py`` runs the 50,000-link chain (results in benchmarks/results/deep_chain.md);
here each limit and each fix takes the same code path at a small depth, the limit monkeypatched down.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from benchmarks.deep_chain import chain_urdf

from robodesc.cli import main
from robodesc.emit.common import gains
from robodesc.emit.common.stance import Stance
from robodesc.frontends.load import load_path
from robodesc.ir.rules import lookup

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def chain(tmp_path: Path) -> Path:
    src = tmp_path / "chain.urdf"
    src.write_text(chain_urdf(6))
    return src


def test_mjcf_refuses_a_tree_deeper_than_tinyxml2_reads(
    chain: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """MuJoCo's XML reader refuses elements nested 500 deep: 496 nested bodies. The refusal comes
    before anything is written (it was a RecursionError after 80 s at 2,000 links)."""
    monkeypatch.setattr("robodesc.emit.mjcf.emitter.MAX_BODY_DEPTH", 5)
    out = tmp_path / "mjcf" / "robot.xml"
    assert main(["compile", str(chain), "-t", "mjcf", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "6 bodies deep" in err and "tinyxml2" in err and "at most 5 nested bodies" in err
    assert not out.exists() and not (out.parent / "scene.xml").exists()


def test_mjcf_writes_the_deepest_tree_mujoco_reads_without_recursion(tmp_path: Path) -> None:
    """496 nested bodies: the writer used two Python frames per level and hit the recursion limit."""
    from robodesc.emit.mjcf.emitter import MAX_BODY_DEPTH

    src = tmp_path / "deep.urdf"
    src.write_text(chain_urdf(MAX_BODY_DEPTH))
    out = tmp_path / "mjcf" / "robot.xml"
    assert main(["compile", str(src), "-t", "mjcf", "-o", str(out), "-q", "--no-validate"]) == 0
    import mujoco

    assert mujoco.MjModel.from_xml_path(str(out)).nbody == MAX_BODY_DEPTH + 1


def test_sdf_poses_deep_trees_in_the_model_frame_and_drake_agrees(
    chain: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """sdformat resolves relative_to poses in time growing with depth² (61 s at 2,000 links)."""
    monkeypatch.setattr("robodesc.emit.sdf.model.RELATIVE_POSES_UP_TO", 3)
    out = tmp_path / "chain.sdf"
    assert main(["compile", str(chain), "-t", "sdf", "-o", str(out), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert "sdf-model-poses" in {f["code"] for f in doc["findings"]}
    text = out.read_text()
    assert 'relative_to="j' not in text
    # l5 sits 5 x 0.1 m up the chain, in the model frame.
    assert re.search(r'<link name="l5">\s*<pose>0 0 0\.5', text)
    assert doc["validation"]["ok"]


def test_drake_validation_of_a_deep_tree_skips_only_fk(
    chain: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """Drake's Finalize grows with depth² in memory: past the limit the SDF is parsed and its bodies
    and joints compared, FK is a WARN row that says why."""
    monkeypatch.setattr("robodesc.validation.drake_sdf.DRAKE_FINALIZE_DEPTH", 3)
    assert main(["compile", str(chain), "-t", "sdf", "-o", str(tmp_path / "c.sdf"), "--json"]) == 0
    checks = json.loads(capsys.readouterr().out)["validation"]["checks"]
    fk = [c for c in checks if c["name"] == "fk"]
    assert fk and fk[0]["status"] == "warn" and "5 joints deep" in fk[0]["message"]
    assert any(c["name"] == "mass" and c["status"] == "pass" for c in checks)


def test_drake_does_not_parse_a_tree_deeper_than_its_graph_checks_take(
    chain: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """libsdformat's graph checks grow with depth²: past the limit validation says so, exit 0."""
    monkeypatch.setattr("robodesc.validation.drake_sdf.DRAKE_PARSE_DEPTH", 3)
    assert main(["compile", str(chain), "-t", "sdf", "-o", str(tmp_path / "c.sdf"), "--json"]) == 0
    checks = json.loads(capsys.readouterr().out)["validation"]["checks"]
    assert [c["status"] for c in checks if c["name"] == "drake-parse"] == ["warn"]
    assert "5 joints deep" in checks[0]["message"] and (tmp_path / "c.sdf").is_file()


def test_derived_gains_vectorised_equal_the_exact_sums(monkeypatch: pytest.MonkeyPatch) -> None:
    """Beyond 512 moved links the subtree sums run in numpy (a chain's n²/2 terms); they equal the
    exact per-link sums to rounding, on a branching robot."""
    robot = load_path(str(ROOT / "examples" / "quadruped.yaml")).robot
    stance = Stance({j.name: 0.0 for j in robot.joints if j.type.dof == 1}, "zeros")
    exact = gains.derived_gains(robot, stance, floating=True)
    monkeypatch.setattr(gains, "_VECTOR_FROM", 0)
    vector = gains.derived_gains(robot, stance, floating=True)
    assert exact.keys() == vector.keys() and exact
    for name, g in exact.items():
        assert vector[name].inertia == pytest.approx(g.inertia, rel=1e-12)
        assert vector[name].stiffness == pytest.approx(g.stiffness, rel=1e-12)


def test_rule_tables_keep_first_match_with_literal_runs() -> None:
    """Tables are compiled once, runs of literal patterns as one dict: the first matching rule
    still wins, and a new table (tables are replaced, not edited) is compiled anew."""
    table = {"a.*": 1.0, "ab": 2.0, re.escape("x.y"): 3.0, "x.y": 5.0, ".*": 4.0}
    assert lookup(table, "ab", "t") == 1.0
    assert lookup(table, "x.y", "t") == 3.0
    assert lookup(table, "xzy", "t") == 5.0
    assert lookup(table, "q", "t") == 4.0
    assert lookup({"ab": 7.0}, "ab", "t") == 7.0
    assert lookup({"a\\-b": 1.0}, "a-b", "t") == 1.0
    assert lookup({"j1": 1.0, "j1": 2.0}, "j1", "t") == 2.0  # noqa: F601 (a dict keeps the last)


def test_isaac_folder_of_a_long_chain_is_linear_in_gains(tmp_path: Path) -> None:
    """The Isaac folder's derived gains walked every joint's subtree and looked each joint up in a
    table of every joint (2,000 links did not finish in 300 s); a 300-link chain now writes."""
    src = tmp_path / "chain300.urdf"
    src.write_text(chain_urdf(300))
    out = tmp_path / "isaac"
    assert main(["compile", str(src), "--isaac-sim", "-o", str(out), "-q", "--no-validate", "--no-preview"]) == 0
    assert (out / "chain300.usda").is_file()
