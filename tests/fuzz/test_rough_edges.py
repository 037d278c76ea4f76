"""Rough edges a new user meets (issue 34): the README's first command is quiet; an Isaac folder's
findings say what set each derived gain, and do not ask for a spawn pose the folder already has."""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

import robodesc
from robodesc.cli import main
from robodesc.emit.common.gains import E_SAT
from robodesc.ir.diagnostics import Severity
from robodesc.validation.corpora import example_robot_data_root

REPO = Path(__file__).resolve().parents[2]


def test_readme_first_command_prints_at_most_one_line_besides_the_summary(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    first = re.search(r"robodesc (compile \S+ .*?)\n", readme)
    assert first is not None
    argv = first.group(1).split()
    assert argv[:2] == ["compile", "examples/urdf/gripper_arm.urdf"], argv
    monkeypatch.chdir(REPO)
    out = tmp_path / "gripper_arm.urdf"
    assert main([*argv[: argv.index("-o")], "-o", str(out)]) == 0
    lines = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert len(lines) <= 2, lines  # one warning (the source's capsule) and the summary
    assert lines[-1].startswith("robodesc: urdf ")


GO1 = os.path.join(example_robot_data_root() or "", "robots", "go1_description", "urdf", "go1.urdf")


@pytest.mark.skipif(not os.path.isfile(GO1), reason="example-robot-data is not installed")
def test_isaac_folder_says_what_set_each_gain_and_where_it_spawns(tmp_path: Path) -> None:
    result = robodesc.compile_for_isaac_sim(GO1, tmp_path / "go1", fix_base=False, validate=False)
    zero = [f for f in result.findings if f.code == "zero-outside-limits"]
    assert zero and all(f.severity is Severity.INFO for f in zero), zero
    assert all("the Isaac folder spawns it at -1.853, inside them" in f.message for f in zero)
    limits = {j.name: j.limit.effort for j in result.robot.joints if j.limit is not None}
    gains = next(f for f in result.findings if f.code == "default-gains").message
    rows = re.findall(r"(\w+) ([\d.e+-]+)/[\d.e+-]+ \(I [\d.e+-]+(, effort-capped|, gravity floor)?\)", gains)
    labels = {label for _, _, label in rows}
    # Which labels appear depends on the gains' floors (issue 35 made go1's stiffer): each that does
    # must say what set its stiffness.
    assert ", gravity floor" in labels and labels <= {", effort-capped", ", gravity floor", ""}, gains
    for name, kp, label in rows:
        cap = limits[name] / E_SAT if limits.get(name) else None
        # Labelled effort-capped, the stiffness is the cap (it was the gravity floor's, above it).
        if label == ", effort-capped":
            assert cap is not None and float(kp) == pytest.approx(cap, rel=1e-3)
        elif label == ", gravity floor":
            assert cap is None or float(kp) != pytest.approx(cap, rel=1e-3)
