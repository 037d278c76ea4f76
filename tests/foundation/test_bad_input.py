"""Every class of bad input, by consequence (docs/diagnostics.md).

Refused: one clear line naming the element and file:line, exit code 2, no traceback, nothing
written. Source defects the output can carry: exit 0 with a warning naming the element and
file:line, and ``--strict`` refuses them like the first class."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from robodesc.cli import main

BAD = Path(__file__).parent / "bad"
EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "urdf"

# file -> (line it must name, fragment the message must contain)
CASES = {
    "malformed.urdf": ("malformed.urdf:3", "malformed XML"),
    "xxe.urdf": ("xxe.urdf:2", "<!DOCTYPE>/<!ENTITY> declarations are not allowed"),
    "entity_bomb.urdf": ("entity_bomb.urdf:2", "<!DOCTYPE>/<!ENTITY> declarations are not allowed"),
    "dangling_parent.urdf": ("dangling_parent.urdf:4", "joint 'knee': parent link 'nope' is not a link"),
    "cycle.urdf": ("cycle.urdf:", "joints form a cycle: a -> b -> c -> a"),
    "nan.urdf": ("nan.urdf:6", "joint 'knee': origin.xyz[1] is nan"),
    "bad_number.urdf": ("bad_number.urdf:4", "<mass value='1/12*m'>: expected a number"),
    "two_roots.urdf": ("two_roots.urdf:3", "2 root links"),
    "duplicate_link.urdf": ("duplicate_link.urdf:2", "link 'a': 2 links share this name"),
    "zero_axis.urdf": ("zero_axis.urdf:4", "joint 'elbow': axis is the zero vector"),
    "unknown_joint_type.urdf": ("unknown_joint_type.urdf:4", "joint 'elbow': unknown joint type 'hinge'"),
    "package_escape.urdf": ("package_escape.urdf:3", "leaves its package root"),
    "not_a_robot.urdf": ("not_a_robot.urdf:1", "root element is <sdf>, expected <robot>"),
}
# Source defects the output carries faithfully: written, with a warning (file -> line, fragment).
WARNED = {
    "missing_mesh.urdf": ("missing_mesh.urdf:3", "link 'a': mesh file"),
    "invalid_inertia.urdf": ("invalid_inertia.urdf:5", "link 'a': principal moments break the triangle inequality"),
    "negative_mass.urdf": ("negative_mass.urdf:3", "link 'a': mass must be > 0 (is -2)"),
    "dangling_mimic.urdf": ("dangling_mimic.urdf:7", "joint 'finger': mimics joint 'ghost', which does not exist"),
    # pybullet reads lower > upper as an unlimited joint (issue 35): so does robodesc, with a warning.
    "bad_limits.urdf": ("bad_limits.urdf:6", "joint 'elbow': lower limit 1 is above upper limit -1: read as pybullet"),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_bad_input_gives_one_clear_line(name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = tmp_path / name
    shutil.copy(BAD / name, src)
    (tmp_path / "package.xml").write_text("<package><name>robodesc_examples</name></package>")
    out = tmp_path / "out" / "robot.urdf"
    code = main(["compile", str(src), "-o", str(out), "-q"])
    err = capsys.readouterr().err
    where, what = CASES[name]
    lines = [line for line in err.splitlines() if line.startswith("error:")]
    assert code == 2, err
    assert lines, err
    assert where in lines[0] and what in lines[0], err
    assert "Traceback" not in err
    assert not out.exists()
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


@pytest.mark.parametrize("name", sorted(WARNED))
def test_source_defect_is_a_warning_and_strict_refuses_it(
    name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    src = tmp_path / name
    shutil.copy(BAD / name, src)
    where, what = WARNED[name]
    out = tmp_path / "out" / "robot.urdf"
    assert main(["compile", str(src), "-o", str(out)]) == 0
    err = capsys.readouterr().err
    warnings = [line for line in err.splitlines() if line.startswith("warning:")]
    assert any(where in w and what in w for w in warnings), err
    assert "Traceback" not in err and out.exists()
    strict = tmp_path / "strict" / "robot.urdf"
    assert main(["compile", str(src), "-o", str(strict), "--strict"]) == 2
    err = capsys.readouterr().err
    errors = [line for line in err.splitlines() if line.startswith("error:")]
    assert any(where in e and what in e for e in errors), err
    assert "--strict turned these warnings into errors" in err
    assert not strict.exists()


def test_dangling_mimic_is_dropped_from_the_output(tmp_path: Path) -> None:
    out = tmp_path / "r.urdf"
    assert main(["compile", str(BAD / "dangling_mimic.urdf"), "-o", str(out), "-q"]) == 0
    assert "<mimic" not in out.read_text()


def test_secret_never_reaches_output(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    main(["inspect", str(BAD / "xxe.urdf")])
    captured = capsys.readouterr()
    assert "root:" not in captured.out + captured.err


def test_unknown_tag_is_kept_with_a_warning_and_strict_refuses(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "r.urdf"
    assert main(["compile", str(BAD / "unknown_tag.urdf"), "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "unknown_tag.urdf:3: unknown element <wobble> in robot: kept verbatim" in err
    assert '<wobble name="x"/>' in out.read_text()
    assert main(["compile", str(BAD / "unknown_tag.urdf"), "-o", str(tmp_path / "s.urdf"), "--strict"]) == 2
    assert "unknown_tag.urdf:3: unknown element <wobble> in robot" in capsys.readouterr().err
    assert not (tmp_path / "s.urdf").exists()


def test_failed_compile_leaves_previous_output_untouched(tmp_path: Path) -> None:
    out = tmp_path / "robot.urdf"
    out.write_text("previous")
    assert main(["compile", str(BAD / "cycle.urdf"), "-o", str(out), "-q"]) == 2
    assert out.read_text() == "previous"
    assert [p.name for p in tmp_path.iterdir()] == ["robot.urdf"]


def test_missing_input_file(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["compile", "no/such/robot.urdf", "-q"]) == 2
    assert capsys.readouterr().err.strip() == "error: no/such/robot.urdf: input file not found"


def test_invalid_inertia_policies(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = str(BAD / "invalid_inertia.urdf")
    assert main(["compile", bad, "-q", "--invalid-inertia", "error"]) == 2
    assert "hint: --invalid-inertia repair" in capsys.readouterr().err
    assert main(["compile", bad, "-o", str(tmp_path / "w.urdf")]) == 0  # warn is the default
    err = capsys.readouterr().err
    assert "passed through" in err and "Repair: --invalid-inertia repair" in err


def test_unknown_api_option_names_the_closest() -> None:
    import robodesc
    from robodesc.ir.diagnostics import ConfigError

    with pytest.raises(ConfigError, match="unknown option 'missing_meshes'; did you mean 'missing_mesh'"):
        robodesc.compile_to_urdf(str(EXAMPLES / "gripper_arm.urdf"), missing_meshes="warn")
    with pytest.raises(ConfigError, match="expected one of 'error', 'warn', 'primitive', 'drop'"):
        robodesc.compile_to_urdf(str(EXAMPLES / "gripper_arm.urdf"), missing_mesh="ignore")


def test_bad_cli_usage_exits_2(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["compile", "x.urdf", "--package", "nodir"]) == 2
    assert "expected NAME=VALUE" in capsys.readouterr().err


def test_a_consumer_refusing_a_source_defect_is_a_warning(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # A massless link on a revolute joint: MuJoCo refuses to compile the model. robodesc wrote
    # what the source says, so the run succeeds and the refusal is listed as a warning.
    src = tmp_path / "massless.urdf"
    src.write_text(
        '<robot name="r">\n'
        '  <link name="base"><inertial><mass value="1"/>'
        '<inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>\n'
        '  <link name="arm"/>\n'
        '  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>\n'
        '    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>\n'
        "</robot>\n"
    )
    out = tmp_path / "o.urdf"
    assert main(["compile", str(src), "-o", str(out), "--json"]) == 0
    import json

    doc = json.loads(capsys.readouterr().out)
    assert out.exists() and doc["ok"]
    refused = [c for c in doc["validation"]["checks"] if "a defect of the source" in c["message"]]
    assert refused and refused[0]["status"] == "warn"
    assert "source defect" in doc["summary"]["validation"]
    assert main(["compile", str(src), "-o", str(tmp_path / "s.urdf"), "--strict"]) == 2
    assert not (tmp_path / "s.urdf").exists()
