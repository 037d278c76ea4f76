"""The rough edges a new user met (issue 26), each reproduced: folders given to compile, a folder
target named like a file, the summary line's figures, batch output in a log, the API's dir()."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

import robodesc
from robodesc.cli import main
from robodesc.cli.render import verdict
from robodesc.ir.model import Link, Robot
from robodesc.pipeline import CompileResult
from robodesc.validation.report import Check, Status, ValidationReport

ROOT = Path(__file__).resolve().parents[2]
ARM = str(ROOT / "examples" / "urdf" / "gripper_arm.urdf")


def test_a_folder_given_to_compile_says_so_and_names_batch(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["compile", str(ROOT / "examples"), "-o", str(tmp_path / "x.urdf")]) == 2
    err = capsys.readouterr().err
    assert "is a folder" in err and "robodesc batch" in err and "unknown input type" not in err


def test_unknown_input_lists_what_is_read_python_included(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    odd = tmp_path / "robot.stl"
    odd.write_bytes(b"solid x\nendsolid x\n")
    assert main(["compile", str(odd)]) == 2
    err = capsys.readouterr().err
    assert "unknown input type" in err and ".holo" in err and ".py" in err and ".xacro" in err


def test_a_folder_target_named_like_a_file_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["compile", ARM, "-t", "isaac", "-o", str(tmp_path / "x.usda")]) == 2
    assert "names a file, but this target writes a folder" in capsys.readouterr().err
    assert not (tmp_path / "x.usda").exists()


def test_a_usd_output_without_a_usd_suffix_is_named_as_typed(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["compile", ARM, "-t", "usd", "-o", str(tmp_path / "x.urdf")]) == 2
    err = capsys.readouterr().err
    assert "x.urdf" in err and ".robodesc-" not in err and ".usda" in err


def test_passed_line_shows_no_figure_of_a_carried_source_defect() -> None:
    report = ValidationReport(robot="r", target="sdf", consumer="drake")
    report.note_error("mass", 1e12)
    report.note_error("fk_position", 2e-9)
    defect = Check("mass", Status.WARN, "link 'a'", "mass differs [a defect of the source, carried through unchanged]")
    result = CompileResult(robot=Robot(name="r", links=[Link(name="a")]), findings=[], target="sdf")
    result.validation, result.source_failures = report, [defect]
    line = verdict(result)
    assert "passed" in line and "1e+12" not in line and "fk_position 2e-09 m" in line
    assert "1 source defect(s)" in line


def test_dir_shows_the_api() -> None:
    names = dir(robodesc)
    assert {"compile_to_urdf", "compile_to_usd", "compile_for_isaac_sim", "compile_to", "load", "validate"} <= set(
        names
    )


def test_validate_help_names_no_consumer_it_does_not_use(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["validate", "--help"])
    text = capsys.readouterr().out
    assert "mujoco-usd (USD)" not in text and "target's independent consumer" in text


def test_batch_in_a_log_prints_whole_lines(tmp_path: Path) -> None:
    """Piped: a line per job, the failure table unwrapped, the closing line whole."""
    robots = tmp_path / "robots"
    robots.mkdir()
    (robots / "arm.urdf").write_text(Path(ARM).read_text().replace("meshes/", str(ROOT / "examples/urdf/meshes") + "/"))
    long_name = "a_robot_whose_file_name_is_long_enough_to_wrap_a_narrow_table_" * 2
    (robots / f"{long_name}.urdf").write_text('<robot name="broken"><link name="a"/><joint/></robot>')
    env = {**os.environ, "COLUMNS": "80"}
    proc = subprocess.run(
        [sys.executable, "-m", "robodesc", "batch", str(robots), "-o", str(tmp_path / "out"), "--no-validate"],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )
    assert proc.returncode == 2, proc.stderr
    lines = proc.stderr.splitlines()
    assert any(line.startswith("robodesc batch: [") and line.endswith(" ok arm") for line in lines)
    assert any(long_name in line and "error" in line for line in lines)  # never wrapped mid-path
    assert any(line.startswith("robodesc batch: 2 jobs in ") and line.endswith(" s") for line in lines)


def test_a_folder_output_that_holds_the_input_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    folder = tmp_path / "d"
    folder.mkdir()
    source = folder / "arm.urdf"
    source.write_text(Path(ARM).read_text())
    assert main(["compile", str(source), "--ros2", "-o", str(folder)]) == 2
    assert "holds the input file" in capsys.readouterr().err
    assert source.read_text() == Path(ARM).read_text()


def test_a_composition_that_exits_is_an_error_not_a_success(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    script = tmp_path / "exits.py"
    script.write_text("import robodesc\n\ndef build():\n    raise SystemExit(0)\n")
    assert main(["compile", str(script), "-o", str(tmp_path / "x.urdf")]) == 2
    assert "called exit(0)" in capsys.readouterr().err
    out = tmp_path / "out"
    assert main(["batch", str(script), "-o", str(out), "-q"]) == 2
    assert not [p for p in out.rglob("*") if p.name.startswith(".robodesc-") and p.is_file() and "batch" not in str(p)]


DUPLICATE_GEOMS = """<robot name="dup">
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision name="c"><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
    <collision name="c"><geometry><box size="0.1 0.1 0.2"/></geometry></collision></link>
</robot>"""


def test_consumer_output_becomes_findings_and_q_silences_it(tmp_path: Path) -> None:
    """MuJoCo's own 'WARNING: Geom with duplicate name' lines reached the terminal even with -q."""
    src = tmp_path / "dup.urdf"
    src.write_text(DUPLICATE_GEOMS)
    run = [sys.executable, "-m", "robodesc", "compile", str(src), "-o", str(tmp_path / "out.urdf")]
    quiet = subprocess.run([*run, "-q"], capture_output=True, text=True, timeout=120)
    assert quiet.returncode == 0 and quiet.stdout == "" and quiet.stderr == ""
    loud = subprocess.run(run, capture_output=True, text=True, timeout=120)
    assert "warning: robot 'dup': mujoco says: Geom with duplicate name 'c'" in loud.stderr
    assert "WARNING: Geom" not in loud.stdout + loud.stderr


def test_isaac_findings_name_no_absolute_path(tmp_path: Path) -> None:
    """findings.md travels with the folder: no path of this machine in it."""
    out = tmp_path / "isaac"
    assert (
        main(
            ["compile", str(ROOT / "examples" / "quadruped.yaml"), "--isaac-sim", "-o", str(out), "-q", "--no-preview"]
        )
        == 0
    )
    text = (out / "findings.md").read_text()
    assert str(ROOT) not in text and str(tmp_path) not in text and "quadruped.yaml:" in text


@pytest.mark.parametrize(
    "target, out", [("mjcf", "robot.xml"), ("usd", "x.usda"), ("sdf", "x.sdf"), ("urdf", "x.urdf")]
)
def test_validation_rows_name_the_output_not_its_staged_copy(
    target: str, out: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Checks run on a staged copy (.robodesc-…); the table names the file the user typed."""
    path = tmp_path / "out" / out
    code = main(["compile", ARM, "-t", target, "-o", str(path), "-v"])
    assert code == 0
    text = capsys.readouterr()
    assert ".robodesc-" not in text.out + text.err


def test_a_composition_whose_build_raises_is_an_input_error_at_its_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """build() raising an ordinary exception was a traceback-class exit 3 ("robodesc bug")."""
    script = tmp_path / "raises.py"
    script.write_text(
        "import robodesc\n\n\ndef helper():\n    return {}['missing']\n\n\ndef build():\n    return helper()\n"
    )
    assert main(["compile", str(script), "-o", str(tmp_path / "x.urdf")]) == 2
    err = capsys.readouterr().err
    assert "raises.py:5:" in err and "raised KeyError" in err and "robodesc bug" not in err
    assert not (tmp_path / "x.urdf").exists()
    broken = tmp_path / "syntax.py"
    broken.write_text("import robodesc\n\ndef build(:\n    pass\n")
    assert main(["compile", str(broken), "-o", str(tmp_path / "x.urdf")]) == 2
    assert "syntax.py:3:" in capsys.readouterr().err
    # In a batch it is that job's error, not a crash.
    out = tmp_path / "out"
    assert main(["batch", str(script), "-o", str(out), "-q", "-j", "1"]) == 2
    import json

    (job,) = json.loads((out / "summary.json").read_text())["jobs"]
    assert job["status"] == "error" and "raises.py:5" in job["error"]


def test_a_composition_raising_keyboard_interrupt_ends_its_job_not_the_batch(tmp_path: Path) -> None:
    """A KeyboardInterrupt from a job's own code made the whole batch exit 130 as if Ctrl-C."""
    import json

    script = tmp_path / "interrupts.py"
    script.write_text("import robodesc\n\n\ndef build():\n    raise KeyboardInterrupt\n")
    out = tmp_path / "out"
    assert main(["batch", str(script), ARM, "-o", str(out), "-q", "-j", "1"]) == 2
    jobs = {j["id"]: j for j in json.loads((out / "summary.json").read_text())["jobs"]}
    assert jobs["interrupts"]["status"] == "error" and jobs["gripper_arm"]["status"] == "ok"


@pytest.mark.parametrize("flag", ["--ros2", "--isaac-sim"])
def test_folder_targets_name_files_after_the_input_not_the_robot(tmp_path: Path, flag: str) -> None:
    """pybullet's humanoid (robot name 'dumpUrdf') gave a ROS 2 folder of dumpUrdf.* files."""
    source = tmp_path / "humanoid.urdf"
    source.write_text(Path(ARM).read_text().replace('name="gripper_arm"', 'name="dumpUrdf"', 1))
    out = tmp_path / "out"
    assert main(["compile", str(source), flag, "-o", str(out), "-q", "--no-validate", "--no-preview"]) == 0
    names = sorted(p.name for p in out.iterdir())
    assert "humanoid.urdf" in names and not [n for n in names if "dumpUrdf" in n]
    expected = {"--ros2": "humanoid.launch.py", "--isaac-sim": "humanoid_isaaclab.py"}[flag]
    assert expected in names
