"""Outputs are all or nothing, output paths are checked before any work, and every exit path of the
CLI is one clear message (and one JSON document with --json), never a traceback."""

from __future__ import annotations

import json
import os
import stat
from pathlib import Path
from typing import Any

import pytest

import robodesc.pipeline
from robodesc.cli import main
from robodesc.emit.common.staging import check_output
from tests.conftest import EXAMPLES

ARM = str(EXAMPLES / "urdf" / "gripper_arm.urdf")
BAD = Path(__file__).parent / "bad"


def _snapshot(folder: Path) -> dict[str, bytes | None]:
    """Every entry under ``folder``: file bytes, or None for a folder."""
    out: dict[str, bytes | None] = {}
    for path in sorted(folder.rglob("*")):
        out[str(path.relative_to(folder))] = path.read_bytes() if path.is_file() else None
    return out


def _failing_validation(monkeypatch: pytest.MonkeyPatch) -> None:
    """Validation finds a difference robodesc is to blame for (exit 1)."""
    real = robodesc.pipeline.validate_emitted

    def broken(*args: Any, **kwargs: Any) -> Any:
        from robodesc.validation.report import Status

        report = real(*args, **kwargs)
        report.add("mass", Status.FAIL, "link 'base'", "injected: mass differs by 1 %")
        return report

    monkeypatch.setattr(robodesc.pipeline, "validate_emitted", broken)


TARGETS = {
    "urdf": ["-t", "urdf", "-o", "out/arm.urdf"],
    "sdf": ["-t", "sdf", "-o", "out/arm.sdf"],
    "usd-layered": ["-t", "usd", "-o", "out/arm.usda", "--layered"],
    "isaac": ["--isaac-sim", "-o", "out/arm_isaac"],
}


@pytest.mark.parametrize("target", sorted(TARGETS))
def test_a_failed_run_leaves_the_earlier_output_byte_identical(
    target: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["compile", ARM, *TARGETS[target], "-q"]) == 0
    before = _snapshot(tmp_path)
    assert before
    _failing_validation(monkeypatch)
    assert main(["compile", ARM, *TARGETS[target]]) == 1
    err = capsys.readouterr().err
    assert "injected: mass differs" in err and "nothing was written" in err
    assert _snapshot(tmp_path) == before
    # --strict refusing a warning (exit 2) leaves it untouched too.
    monkeypatch.undo()
    monkeypatch.chdir(tmp_path)
    unknown = str(BAD / "unknown_tag.urdf")
    args = [a.replace("arm", "arm") for a in TARGETS[target]]
    assert main(["compile", unknown, *args, "--strict", "-q"]) == 2
    assert _snapshot(tmp_path) == before


def test_a_new_output_is_not_created_when_validation_fails(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    _failing_validation(monkeypatch)
    assert main(["compile", ARM, "--isaac-sim", "-o", str(tmp_path / "isaac")]) == 1
    assert list(tmp_path.iterdir()) == []


def test_folder_outputs_get_the_usual_permissions(tmp_path: Path) -> None:
    mask = os.umask(0o022)
    try:
        assert main(["compile", ARM, "--isaac-sim", "-o", str(tmp_path / "isaac"), "-q"]) == 0
        assert main(["compile", ARM, "-t", "usd", "--layered", "-o", str(tmp_path / "u" / "arm.usda"), "-q"]) == 0
    finally:
        os.umask(mask)
    for folder in (tmp_path / "isaac", tmp_path / "u" / "Payload"):
        assert stat.S_IMODE(folder.stat().st_mode) == 0o755, folder


# ---- output paths, each with its own message, before any work ---------------------------------
def _err(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str]:
    code = main(argv)
    return code, capsys.readouterr().err


def test_output_is_an_existing_folder(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, err = _err(["compile", ARM, "-o", str(tmp_path)], capsys)
    assert code == 2 and "is an existing folder; give a file name inside it" in err


def test_output_ends_with_a_slash(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, err = _err(["compile", ARM, "-o", str(tmp_path / "new") + "/"], capsys)
    assert code == 2 and "ends with '/'" in err
    assert not (tmp_path / "new").exists()


def test_output_under_a_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "file.txt").write_text("x")
    code, err = _err(["compile", ARM, "-o", str(tmp_path / "file.txt" / "robot.urdf")], capsys)
    assert code == 2 and "is a file, so nothing can be written under it" in err


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes everywhere")
def test_output_in_an_unwritable_folder(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    locked = tmp_path / "locked"
    locked.mkdir(mode=0o500)
    code, err = _err(["compile", ARM, "-o", str(locked / "robot.urdf")], capsys)
    assert code == 2 and "is not writable" in err


def test_unwritable_folder_check(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # The same check as above, also when the tests run as root (who may write anywhere).
    from robodesc.ir.diagnostics import ConfigError

    monkeypatch.setattr(os, "access", lambda path, mode: False)
    with pytest.raises(ConfigError, match="is not writable"):
        check_output(str(tmp_path / "robot.urdf"), folder=False)


def test_report_on_a_folder(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, err = _err(["compile", ARM, "-o", str(tmp_path / "r.urdf"), "--report", str(tmp_path)], capsys)
    assert code == 2 and "--report" in err and "is an existing folder" in err
    assert not (tmp_path / "r.urdf").exists()


def test_output_is_the_input(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = tmp_path / "robot.urdf"
    src.write_bytes(Path(ARM).read_bytes())
    before = src.read_bytes()
    code, err = _err(["compile", str(src), "-o", str(src)], capsys)
    assert code == 2 and "is the input file" in err
    assert src.read_bytes() == before


def test_output_is_a_device(capsys: pytest.CaptureFixture[str]) -> None:
    before = os.stat(os.devnull)
    code, err = _err(["compile", ARM, "-o", os.devnull], capsys)
    assert code == 2 and "is a device or special file" in err
    after = os.stat(os.devnull)
    assert stat.S_ISCHR(after.st_mode) and after.st_rdev == before.st_rdev


def test_folder_target_on_an_existing_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "f").write_text("x")
    code, err = _err(["compile", ARM, "--isaac-sim", "-o", str(tmp_path / "f")], capsys)
    assert code == 2 and "is an existing file; this target writes a folder" in err
    assert (tmp_path / "f").read_text() == "x"


# ---- one message, one JSON document, exit codes -----------------------------------------------
def test_internal_error_is_one_line_and_exit_3(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    def boom(*args: Any, **kwargs: Any) -> Any:
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(robodesc.pipeline, "verify_source", boom)
    assert main(["compile", ARM, "-o", str(tmp_path / "r.urdf")]) == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("robodesc bug: ZeroDivisionError") and "--debug" in err
    assert main(["compile", ARM, "-o", str(tmp_path / "r.urdf"), "--debug"]) == 3
    assert "Traceback" in capsys.readouterr().err


def test_environment_error_is_a_message(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    def full(*args: Any, **kwargs: Any) -> Any:
        raise OSError(28, "No space left on device", str(tmp_path / "r.urdf"))

    monkeypatch.setattr(robodesc.pipeline, "verify_source", full)
    assert main(["compile", ARM, "-o", str(tmp_path / "r.urdf")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and "No space left on device" in err and "Traceback" not in err


@pytest.mark.parametrize(
    ("argv", "code"),
    [
        (["compile", ARM, "-q"], 0),
        (["compile", str(BAD / "cycle.urdf")], 2),
        (["compile", "no/such.urdf"], 2),
        (["compile", ARM, "--no-such-flag"], 2),
        (["compile", ARM, "-o", os.devnull], 2),
        (["compile", str(BAD / "unknown_tag.urdf"), "--strict"], 2),
        (["validate", ARM], 0),
    ],
)
def test_json_on_every_exit_path(argv: list[str], code: int, capsys: pytest.CaptureFixture[str]) -> None:
    assert main([*argv, "--json"]) == code
    doc = json.loads(capsys.readouterr().out)
    assert doc["exit_code"] == code and doc["ok"] is (code == 0)
    if code:
        assert doc["errors"] and all(e["message"] for e in doc["errors"])
    else:
        assert doc["summary"]["links"] == 8 and doc["validation"]["checks"]


def test_json_carries_consumers_and_repair(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["compile", str(BAD / "invalid_inertia.urdf"), "-o", str(tmp_path / "r.urdf"), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    (bad,) = [f for f in doc["findings"] if f["code"] == "bad-inertia"]
    assert "MuJoCo" in bad["consumers"] and "--invalid-inertia repair" in bad["repair"]


def test_warnings_are_grouped_and_verbose_lists_them(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = tmp_path / "r.urdf"
    links = "".join(
        f'<link name="l{i}"/><joint name="j{i}" type="fixed"><parent link="l{i - 1}"/><child link="l{i}"/></joint>'
        for i in range(1, 4)
    )
    src.write_text(f'<robot name="r"><link name="l0"/>{links}\n<wobble/>\n<wobble/>\n<wobble/></robot>')
    assert main(["compile", str(src), "-o", str(tmp_path / "o.urdf")]) == 0
    err = capsys.readouterr().err.splitlines()
    unknown = [line for line in err if "unknown element <wobble>" in line]
    assert len(unknown) == 1 and "(and 2 more unknown-element; -v lists them)" in unknown[0]
    assert err[-1].startswith("robodesc: urdf ") and "4 links, 3 joints, 0 DOF" in err[-1]
    assert main(["compile", str(src), "-o", str(tmp_path / "o.urdf"), "-v"]) == 0
    assert sum("unknown element <wobble>" in line for line in capsys.readouterr().err.splitlines()) == 3


def test_paths_are_relative_to_the_working_directory(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    src = tmp_path / "robots" / "r.urdf"
    src.parent.mkdir()
    src.write_text('<robot name="r"><link name="a"/><wobble/></robot>')
    monkeypatch.chdir(tmp_path)
    assert main(["compile", str(src), "-o", str(tmp_path / "out" / "r.urdf")]) == 0
    err = capsys.readouterr().err
    assert "warning: robots/r.urdf:1:" in err and "robodesc: urdf out/r.urdf:" in err
    assert str(tmp_path) not in err


def test_usd_banner_never_shown(tmp_path: Path) -> None:
    import subprocess
    import sys

    env = dict(os.environ, PXR_WORK_THREAD_LIMIT="1")
    proc = subprocess.run(
        [sys.executable, "-m", "robodesc", "compile", ARM, "-t", "usd", "-o", str(tmp_path / "a.usda")],
        capture_output=True,
        text=True,
        env=env,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr
    assert "PXR_WORK_THREAD_LIMIT" not in proc.stderr + proc.stdout


def test_copy_meshes_into_a_folder_output(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "isaac"
    assert main(["compile", ARM, "--isaac-sim", "--copy-meshes", "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "could not be read" not in err  # the USD read the copied meshes
    copied = out / "meshes" / "finger.stl"
    assert copied.is_file() and stat.S_IMODE(copied.stat().st_mode) & 0o044 == 0o044
    assert 'filename="meshes/finger.stl"' in (out / "gripper_arm.urdf").read_text()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["isaac"]  # no staging left behind


def test_progress_shows_only_for_slow_steps_on_a_terminal() -> None:
    import io
    import time

    from rich.console import Console

    from robodesc.cli.render import Progress as _Progress

    quiet = _Progress(True)  # standard error is not a terminal under pytest: no output at all
    assert quiet.console is None
    shown = _Progress(False)
    buffer = io.StringIO()
    shown.console = Console(file=buffer, force_terminal=True, width=80)
    shown.DELAY = 0.05  # stands for the two seconds
    shown("loading")
    shown.stop()  # a fast step: nothing shown
    assert "loading" not in buffer.getvalue()
    shown("validating")
    time.sleep(0.5)
    shown.stop()
    assert "validating" in buffer.getvalue()
