"""One base policy for every target (issue 38; docs/isaac.md, "The base"): a robot on three or more legs
floats in USD, the Isaac folder and its Isaac Lab module, SDF and MJCF alike; an arm stays welded;
--fix-base and --no-fix-base win; the summary line says which applied and why."""

from __future__ import annotations

import json
import runpy
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import pytest
from pxr import Usd, UsdPhysics

import robodesc
from robodesc.emit.common.base import choose_base
from tests.conftest import EXAMPLES, GO2_XACRO, ROOT, SPIRIT_XACRO

ARM = str(EXAMPLES / "urdf" / "gripper_arm.urdf")
ARM_OPTIONS = {"package_paths": {"robodesc_examples": str(EXAMPLES / "urdf")}}
QUADRUPEDS = {"spirit": SPIRIT_XACRO, "go2": GO2_XACRO, "quadruped.yaml": EXAMPLES / "quadruped.yaml"}
TARGETS = ("usd", "isaac", "sdf", "mjcf")


def _floats(target: str, out: Path) -> bool:
    """Whether the written file lets the root move, read from the file itself."""
    if target in ("usd", "isaac"):
        # The Isaac folder's robot, not its physics layer for Isaac Sim 6's importer (overs only).
        usd = out if target == "usd" else next(p for p in out.glob("*.usd*") if not p.name.endswith("_physics.usda"))
        stage = Usd.Stage.Open(str(usd))
        welds = [
            p
            for p in stage.Traverse()
            if p.IsA(UsdPhysics.FixedJoint) and not UsdPhysics.Joint(p).GetBody0Rel().GetTargets()
        ]
        return not welds
    if target == "sdf":
        model = ET.parse(out).getroot().find("model")
        assert model is not None
        return not any(j.findtext("parent") == "world" for j in model.findall("joint"))
    body = ET.parse(out).getroot().find("worldbody/body")
    assert body is not None
    return body.find("freejoint") is not None


def _compile(source: Any, target: str, tmp_path: Path, **options: Any) -> tuple[robodesc.CompileResult, Path]:
    out = tmp_path / {"usd": "robot.usda", "isaac": "isaac", "sdf": "robot.sdf", "mjcf": "robot.xml"}[target]
    result = robodesc.compile_to(str(source), target, out, validate=False, **options)
    return result, out


@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize("name", QUADRUPEDS)
def test_quadruped_floats_in_every_target(name: str, target: str, tmp_path: Path) -> None:
    source = QUADRUPEDS[name]
    if not source.exists():
        pytest.skip("corpus not present")
    result, out = _compile(source, target, tmp_path)
    assert result.base is not None and not result.base.fixed
    assert _floats(target, out)
    if name != "quadruped.yaml":  # the example's composition says "base: floating" itself
        assert result.base.summary() == "base: floating (stands on 4 feet; --fix-base to weld)"
        assert any(f.code == "base-floating" for f in result.findings)
    if target == "isaac":
        module = runpy.run_path(str(next(out.glob("*_isaaclab.py"))))["ROBOT"]
        assert module["fix_base"] is False and module["articulation"]["fix_root_link"] is False
        settings = json.loads((out / "importer_settings.json").read_text())
        assert [v["fix_base"] for v in settings.values() if isinstance(v, dict) and "fix_base" in v] == [False] * 4


def test_the_legs_decide_where_the_composition_does_not() -> None:
    """The example quadruped without its ``base: floating`` line: its four legs float it."""
    robot = robodesc.load(str(EXAMPLES / "quadruped.yaml"))
    assert robot.fixed_base is False
    robot.fixed_base = None
    choice = choose_base(robot, None)
    assert not choice.fixed and len(choice.legs) == 4
    assert choose_base(robot, True).fixed
    assert choose_base(robodesc.load(ARM, **ARM_OPTIONS), None).fixed


@pytest.mark.parametrize("target", TARGETS)
def test_arm_stays_welded_in_every_target(target: str, tmp_path: Path) -> None:
    result, out = _compile(ARM, target, tmp_path, **ARM_OPTIONS)
    assert result.base is not None and result.base.fixed
    assert result.base.summary() == "base: fixed (no legs: fewer than 3 to stand on; --no-fix-base to float)"
    assert not _floats(target, out)
    assert not any(f.code == "base-floating" for f in result.findings)


@pytest.mark.parametrize("target", TARGETS)
def test_flags_win(target: str, tmp_path: Path) -> None:
    welded, out = _compile(EXAMPLES / "quadruped.yaml", target, tmp_path / "w", fix_base=True)
    assert welded.base is not None and welded.base.summary() == "base: fixed (--fix-base)"
    assert not _floats(target, out)
    floating, out = _compile(ARM, target, tmp_path / "f", fix_base=False, **ARM_OPTIONS)
    assert floating.base is not None and floating.base.summary() == "base: floating (--no-fix-base)"
    assert _floats(target, out)


@pytest.mark.parametrize("target", ["usd", "mjcf"])
def test_flag_against_the_composition_passes_validation(target: str, tmp_path: Path) -> None:
    """quadruped.yaml says ``base: floating``; ``--fix-base`` wins, and the consumer's check compares the
    file with the base asked for (it once failed: "the source says floating base, the USD is fixed-base")."""
    out = tmp_path / {"usd": "robot.usda", "mjcf": "robot.xml"}[target]
    result = robodesc.compile_to(str(EXAMPLES / "quadruped.yaml"), target, out, fix_base=True)
    assert result.validation is not None and result.validation.ok
    assert not _floats(target, out)


def test_summary_line_says_the_base(tmp_path: Path) -> None:
    out = tmp_path / "robot.usda"
    run = subprocess.run(
        [sys.executable, "-m", "robodesc", "compile", str(EXAMPLES / "quadruped.yaml"), "-t", "usd", "-o", str(out)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=True,
    )
    line = next(x for x in run.stderr.splitlines() if x.startswith("robodesc: usd"))
    assert "; base: floating (the composition's base; --fix-base to weld); validation" in line
    package = f"--package=robodesc_examples={EXAMPLES / 'urdf'}"
    doc = subprocess.run(
        [
            sys.executable,
            "-m",
            "robodesc",
            "compile",
            ARM,
            "-t",
            "sdf",
            "-o",
            str(tmp_path / "a.sdf"),
            "--json",
            package,
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=True,
    )
    assert json.loads(doc.stdout)["summary"]["base"] == {
        "fixed": True,
        "reason": "no legs: fewer than 3 to stand on",
    }
