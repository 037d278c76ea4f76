"""The command line as a user meets it."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from robodesc.cli import main
from tests.conftest import EXAMPLES, SPIRIT_XACRO

ARM = str(EXAMPLES / "urdf" / "gripper_arm.urdf")


def test_compile_to_stdout(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["compile", ARM, "-q"]) == 0
    out = capsys.readouterr().out
    assert out.startswith('<?xml version="1.0" encoding="utf-8"?>\n<robot name="gripper_arm">')


def test_compile_json_summary(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "arm.urdf"
    assert main(["compile", str(SPIRIT_XACRO), "-o", str(out), "--json", "--invalid-inertia", "warn"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["files"] == {"urdf": str(out)}
    codes = {f["code"] for f in summary["findings"]}
    assert {"unknown-element", "bad-inertia"} <= codes
    text_right = [f for f in summary["findings"] if f["element"] == "link 'text_right'"]
    assert text_right and text_right[0]["line"] is not None


def test_inspect_reports_tree_dof_mass(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["inspect", ARM]) == 0
    text = capsys.readouterr().out
    assert "robot 'gripper_arm': 8 links, 7 joints, 5 DOF, total mass 8.02 kg" in text
    assert "          finger_right  <- finger_right_joint [prismatic]" in text
    assert main(["inspect", ARM, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["dof"] == 5 and data["actuated_joints"][:2] == ["shoulder_yaw", "shoulder_pitch"]


def test_inspect_shares_compiles_severity_and_grouping(capsys: pytest.CaptureFixture[str]) -> None:
    """A source defect compile carries with a warning is a warning in inspect too (exit 0), grouped
    by kind on standard error with paths as typed; --invalid-inertia error and --strict refuse."""
    assert main(["inspect", str(SPIRIT_XACRO)]) == 0
    out, err = capsys.readouterr()
    assert "warning: " in err and "link 'text_right': inertia tensor is zero" in err and "-v lists them" in err
    assert "inertia tensor is zero" not in out and "robot 'spirit'" in out
    from robodesc.cli.render import display_path

    assert display_path(str(SPIRIT_XACRO)) in err  # the path as compile shows it (relative when shorter)
    assert main(["inspect", str(SPIRIT_XACRO), "-q"]) == 0
    assert capsys.readouterr() == ("", "")
    assert main(["inspect", str(SPIRIT_XACRO), "--invalid-inertia", "error"]) == 2
    assert "error: " in capsys.readouterr().err
    assert main(["inspect", str(SPIRIT_XACRO), "--strict"]) == 2  # as compile: the first unknown element
    assert capsys.readouterr().err.startswith("error: ")


def test_expand_prints_the_lines_messages_refer_to(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["inspect", str(SPIRIT_XACRO), "--json"]) == 0
    findings = json.loads(capsys.readouterr().out)["findings"]
    line = next(f["line"] for f in findings if f["element"] == "link 'text_right'")
    assert main(["expand", str(SPIRIT_XACRO)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert '<inertia ixx="0.00"' in lines[line - 1] and '<link name="text_right">' in "".join(lines[line - 15 : line])


def test_console_script_runs_as_module() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "robodesc", "compile", "--help"], capture_output=True, text=True, check=False
    )
    assert proc.returncode == 0
    for option in ("--package", "--arg", "--missing-mesh", "--invalid-inertia", "--mesh-paths", "--strict", "--json"):
        assert option in proc.stdout


def test_console_script_flushes_and_keeps_the_exit_code(tmp_path: Path) -> None:
    # The script leaves with os._exit (no interpreter teardown): buffered output must still arrive.
    gripper = Path(__file__).resolve().parents[1] / "usd" / "data" / "gripper.urdf"
    ok = subprocess.run(
        [sys.executable, "-m", "robodesc", "compile", str(gripper), "--no-validate"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert ok.returncode == 0 and ok.stdout.rstrip().endswith("</robot>")
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot name='r'><link name='a'/>")
    failed = subprocess.run(
        [sys.executable, "-m", "robodesc", "compile", str(bad)], capture_output=True, text=True, check=False
    )
    errors = [line for line in failed.stderr.splitlines() if line.startswith("error:")]
    assert failed.returncode == 2 and len(errors) == 1 and "bad.urdf:1:" in errors[0]


def test_xacro_args_are_passed(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "s.urdf"
    assert (
        main(["compile", str(SPIRIT_XACRO), "-o", str(out), "--arg", "prefix=sp_", "--invalid-inertia", "warn", "-q"])
        == 0
    )
    assert '<link name="sp_body">' in out.read_text()
    assert main(["compile", str(SPIRIT_XACRO), "-q", "--arg", "use_sim=maybe"]) == 2
    assert "xacro" in capsys.readouterr().err
