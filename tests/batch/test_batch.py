"""robodesc batch: planning (folders, manifests, sweeps), the cache, isolation of failing jobs,
Ctrl-C, and the Ray executor against the local pool."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pebble
import pytest

from robodesc.batch import sweep
from robodesc.batch.discover import discover
from robodesc.batch.plan import plan
from robodesc.cli import main
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.ir.diagnostics import ConfigError
from robodesc.options import CompileOptions

from .robots import CORRUPT_IR, STL, make_collection, mesh_urdf, python_robot


def batch(*args: str) -> tuple[int, dict[str, Any]]:
    """Run ``robodesc batch ARGS -q`` in this process; the summary it wrote."""
    argv = ["batch", *args, "-q"]
    code = main(argv)
    out = Path(argv[argv.index("-o") + 1])
    return code, json.loads((out / "summary.json").read_text())


def by_id(summary: dict[str, Any]) -> dict[str, dict[str, Any]]:
    return {job["id"]: job for job in summary["jobs"]}


def rerun(summary: dict[str, Any]) -> set[str]:
    """The jobs a run actually compiled (not skipped as unchanged)."""
    return {job["id"] for job in summary["jobs"] if not job["cached"]}


# ---- planning ----------------------------------------------------------------------------------
def test_folder_discovery_finds_robots_and_skips_macro_files_and_configs(tmp_path: Path) -> None:
    robots = make_collection(tmp_path)
    python_robot(robots / "gripper.py", "gripper")
    (robots / "manifest.yaml").write_text("jobs:\n  - input: alpha.urdf\n")
    os.mkfifo(robots / "pipe.urdf")  # a named pipe is passed over, never opened for reading (it would hang)
    found = dict((job_id, os.path.basename(path)) for path, job_id in discover(str(robots), run_python=True))
    assert found == {
        "alpha": "alpha.urdf",
        "arm/arm": "arm.urdf.xacro",  # parts.xacro is included by it: a macro file, not a robot
        "beta": "beta.urdf",
        "gripper": "gripper.py",
        "pendulum": "pendulum.yaml",  # controllers.yaml, notes.py and the manifest are not robots
    }
    # Python compositions run when read: a folder's are compiled only when asked (--run-python).
    assert "gripper" not in dict((job_id, path) for path, job_id in discover(str(robots)))


def test_batch_on_a_folder_writes_one_folder_per_job_and_the_summary(tmp_path: Path) -> None:
    robots = make_collection(tmp_path)
    out = tmp_path / "out"
    code, summary = batch(str(robots), "-o", str(out), "-j", "2", "-t", "sdf", "--no-validate")
    assert code == 0
    jobs = by_id(summary)
    assert set(jobs) == {"alpha", "beta", "arm/arm", "pendulum"}
    for job in jobs.values():
        assert job["status"] == "ok" and job["validation"] == "off"
        assert (out / job["files"]["sdf"]).is_file()
    assert jobs["arm/arm"]["files"] == {"sdf": "arm/arm/arm.sdf"}
    assert jobs["pendulum"]["robot"] == {"joints": 1, "links": 2, "name": "pendulum"}
    assert summary["totals"]["by_outcome"]["ok"] == 4
    markdown = (out / "summary.md").read_text()
    assert "| arm/arm |" in markdown and "| ok | 4 |" in markdown


def test_yaml_manifest_rows_carry_target_output_args_and_options(tmp_path: Path) -> None:
    robots = make_collection(tmp_path)
    (robots / "jobs.yaml").write_text(
        """defaults:
  options: {validate: false}
jobs:
  - input: arm/arm.urdf.xacro
    id: long_arm
    args: {length: "0.75"}
  - input: alpha.urdf
    target: sdf
    output: custom/alpha_model.sdf
  - input: pendulum.yaml
    options: {preset: mujoco}
"""
    )
    out = tmp_path / "out"
    code, summary = batch(str(robots / "jobs.yaml"), "-o", str(out))
    assert code == 0, summary
    jobs = by_id(summary)
    assert set(jobs) == {"long_arm", "alpha", "pendulum"}
    assert 'xyz="0 0 0.75"' in (out / "long_arm" / "arm.urdf").read_text()
    assert jobs["alpha"]["files"] == {"sdf": "custom/alpha_model.sdf"}
    assert "<sdf" in (out / "custom" / "alpha_model.sdf").read_text()


def test_csv_manifest(tmp_path: Path) -> None:
    robots = make_collection(tmp_path)
    (robots / "jobs.csv").write_text(
        "input,target,args,missing_mesh,validate\n"
        "arm/arm.urdf.xacro,urdf,length=0.25,,false\n"
        "alpha.urdf,sdf,,warn,false\n"
    )
    out = tmp_path / "out"
    code, summary = batch(str(robots / "jobs.csv"), "-o", str(out))
    assert code == 0
    assert [(j["id"], j["target"], j["status"]) for j in summary["jobs"]] == [
        ("arm", "urdf", "ok"),
        ("alpha", "sdf", "ok"),
    ]
    assert 'xyz="0 0 0.25"' in (out / "arm" / "arm.urdf").read_text()


def test_manifest_mistakes_name_the_file_and_line(tmp_path: Path) -> None:
    robots = make_collection(tmp_path)
    (robots / "jobs.yaml").write_text("jobs:\n  - input: alpha.urdf\n  - input: beta.urdf\n    targt: sdf\n")
    with pytest.raises(ConfigError, match=r"jobs\.yaml:3: unknown job key 'targt'; did you mean 'target'\?"):
        plan([str(robots / "jobs.yaml")], target="urdf", options=CompileOptions(), root=str(tmp_path / "o"))
    (robots / "jobs.yaml").write_text("jobs:\n  - {input: alpha.urdf, id: ../elsewhere}\n")
    with pytest.raises(ConfigError, match="must stay inside the output folder"):
        plan([str(robots / "jobs.yaml")], target="urdf", options=CompileOptions(), root=str(tmp_path / "o"))
    (robots / "jobs.csv").write_text("input,missing_mesh\nalpha.urdf,sometimes\n")
    with pytest.raises(ConfigError, match=r"jobs\.csv:2: option missing_mesh='sometimes'"):
        plan([str(robots / "jobs.csv")], target="urdf", options=CompileOptions(), root=str(tmp_path / "o"))


def test_sweeps_grid_and_seeded_random() -> None:
    grid = sweep.expand({"grid": {"a": [1, 2], "b": ["x", "y", "z"]}}, "test")
    assert grid == [{"a": str(a), "b": b} for a in (1, 2) for b in "xyz"]
    spec = {
        "random": {"m": {"uniform": [1.0, 2.0]}, "n": {"randint": [1, 3]}, "c": ["p", "q"]},
        "samples": 5,
        "seed": 7,
    }
    first, second = sweep.expand(spec, "test"), sweep.expand(spec, "test")
    assert first == second and len(first) == 5
    assert all(1.0 <= float(p["m"]) <= 2.0 and p["n"] in "123" and p["c"] in "pq" for p in first)
    assert first != sweep.expand({**spec, "seed": 8}, "test")
    assert sweep.from_cli(["a=1,2", "m=0.5..1"], 3, 1) == {
        "grid": {"a": ["1", "2"]},
        "random": {"m": {"uniform": [0.5, 1.0]}},
        "seed": 1,
        "samples": 3,
    }
    with pytest.raises(ConfigError, match="--samples"):
        sweep.from_cli(["m=0.5..1"], None, 0)


def test_sweep_expands_into_jobs_with_their_xacro_arguments(tmp_path: Path) -> None:
    robots = make_collection(tmp_path)
    out = tmp_path / "out"
    xacro = str(robots / "arm" / "arm.urdf.xacro")
    code, summary = batch(
        xacro, "-o", str(out), "--no-validate", "--sweep", "length=0.3,0.4", "--sweep", "length2=1..2", "--samples", "2"
    )
    assert code == 0
    variants = [(j["id"], j["variant"]["length"]) for j in summary["jobs"]]
    assert variants == [("arm-v1", "0.3"), ("arm-v2", "0.3"), ("arm-v3", "0.4"), ("arm-v4", "0.4")]
    assert 'xyz="0 0 0.4"' in (out / "arm-v4" / "arm.urdf").read_text()


# ---- the cache ---------------------------------------------------------------------------------
def test_resume_skips_unchanged_jobs_and_redoes_exactly_the_changed_ones(tmp_path: Path) -> None:
    robots = make_collection(tmp_path)
    out = tmp_path / "out"
    args = (str(robots), "-o", str(out), "-j", "2", "-t", "usd", "--no-validate")
    _, first = batch(*args)
    assert rerun(first) == {"alpha", "beta", "arm/arm", "pendulum"}
    _, again = batch(*args)
    assert rerun(again) == set() and again["totals"]["cached"] == 4
    # A mesh one robot reads: only that robot.
    (robots / "meshes" / "a.stl").write_text(STL.format(s=0.15))
    _, after_mesh = batch(*args)
    assert rerun(after_mesh) == {"alpha"}
    # Touching a file without changing it is not a change (content hashes, not times).
    os.utime(robots / "meshes" / "b.stl", (time.time() + 60, time.time() + 60))
    _, touched = batch(*args)
    assert rerun(touched) == set()
    # A file the xacro includes: only the xacro robot.
    parts = robots / "arm" / "parts.xacro"
    parts.write_text(parts.read_text().replace("0.1 0.1 0.1", "0.1 0.1 0.2"))
    _, after_include = batch(*args)
    assert rerun(after_include) == {"arm/arm"}
    # Another option, --force, or a deleted output: those jobs again.
    _, other_option = batch(*args, "--fix-base")
    assert rerun(other_option) == {"alpha", "beta", "arm/arm", "pendulum"}
    (out / "beta" / "beta.usda").unlink()
    _, deleted = batch(*args, "--fix-base")
    assert rerun(deleted) == {"beta"}
    _, forced = batch(*args, "--fix-base", "--force")
    assert rerun(forced) == {"alpha", "beta", "arm/arm", "pendulum"}


def test_a_mesh_shared_by_two_robots_reruns_both_and_only_them(tmp_path: Path) -> None:
    robots = make_collection(tmp_path)
    (robots / "gamma.urdf").write_text(mesh_urdf("gamma", "meshes/a.stl"))
    out = tmp_path / "out"
    args = (str(robots), "-o", str(out), "--no-validate")
    batch(*args)
    (robots / "meshes" / "a.stl").write_text(STL.format(s=0.3))
    _, after = batch(*args)
    assert rerun(after) == {"alpha", "gamma"}


def test_failed_jobs_are_not_cached(tmp_path: Path) -> None:
    robots = make_collection(tmp_path)
    (robots / "meshes" / "b.stl").unlink()
    out = tmp_path / "out"
    # A missing mesh is a warning by default; as an error it makes a job that fails.
    args = (str(robots), "-o", str(out), "--no-validate", "--missing-mesh", "error")
    code, first = batch(*args)
    assert code == 2 and by_id(first)["beta"]["status"] == "error"
    assert "b.stl" in by_id(first)["beta"]["error"] and first["totals"]["by_finding_kind"]["broken-reference"] == 1
    _, second = batch(*args)
    assert rerun(second) == {"beta"}


# ---- isolation -----------------------------------------------------------------------------------
def test_a_crash_an_exception_and_a_timeout_are_results_and_the_batch_goes_on(tmp_path: Path) -> None:
    robots = make_collection(tmp_path)
    python_robot(
        robots / "segfault.py", "segfault", body="os.kill(os.getpid(), signal.SIGSEGV)", prelude="import os, signal"
    )
    python_robot(robots / "raises.py", "raises", body="raise RuntimeError('boom')")
    python_robot(robots / "corrupt.py", "corrupt", after=CORRUPT_IR)
    python_robot(robots / "hangs.py", "hangs", body="time.sleep(120)", prelude="import time")
    out = tmp_path / "out"
    started = time.monotonic()
    code, summary = batch(str(robots), "-o", str(out), "-j", "2", "--no-validate", "--timeout", "5", "--run-python")
    assert time.monotonic() - started < 60
    assert code == 2
    assert pebble.common.CONSTS.sleep_unit == 0.1  # the finer tick of a batch's pools is put back
    jobs = by_id(summary)
    assert jobs["segfault"]["status"] == "crashed" and "SIGSEGV" in jobs["segfault"]["error"]
    # The composition's own exception is its error, at its line (issue 26: it was a crash).
    assert jobs["raises"]["status"] == "error" and "raises.py:" in jobs["raises"]["error"]
    assert "raised RuntimeError: boom" in jobs["raises"]["error"]
    assert jobs["corrupt"]["status"] == "crashed" and jobs["corrupt"]["error"].startswith("AttributeError")
    assert jobs["hangs"]["status"] == "timeout"
    assert {jobs[k]["status"] for k in ("alpha", "beta", "arm/arm", "pendulum")} == {"ok"}
    assert summary["totals"]["by_outcome"] == {
        "ok": 4,
        "validation-failed": 0,
        "error": 1,
        "crashed": 2,
        "timeout": 1,
        "not-run": 0,
    }


@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGTERM], ids=["ctrl-c", "kill"])
def test_ctrl_c_stops_cleanly_keeps_finished_jobs_and_the_next_run_resumes(tmp_path: Path, stop: int) -> None:
    robots = make_collection(tmp_path)
    python_robot(
        robots / "zz_slow.py",
        "slow",
        body="time.sleep(float(os.environ.get('SLOW', '120')))",
        prelude="import os, time",
    )
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "robodesc", "batch", str(robots), "-o", str(out), "-j", "1", "--run-python"]
    cmd += ["--no-validate", "-q"]
    proc = subprocess.Popen(cmd, stderr=subprocess.PIPE, text=True)
    records = out / ".robodesc-batch" / "records.jsonl"

    def finished() -> int:
        return len(records.read_text().splitlines()) if records.is_file() else 0

    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and finished() < 4:
        time.sleep(0.2)
    assert finished() == 4, "the four quick jobs did not finish"
    time.sleep(0.5)  # the slow one is running now
    proc.send_signal(stop)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    summary = json.loads((out / "summary.json").read_text())
    assert summary["interrupted"] is True
    jobs = by_id(summary)
    assert jobs["zz_slow"]["status"] == "not-run"
    assert {jobs[k]["status"] for k in ("alpha", "beta", "arm/arm", "pendulum")} == {"ok"}
    # Resume: only the job that did not finish runs.
    env = {**os.environ, "SLOW": "0"}
    done = subprocess.run([*cmd[:-1], "-q"], env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    resumed = json.loads((out / "summary.json").read_text())
    assert rerun(resumed) == {"zz_slow"}


def test_json_goes_to_stdout(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    robots = make_collection(tmp_path)
    assert (
        main(["batch", str(robots / "alpha.urdf"), "-o", str(tmp_path / "out"), "--json", "-q", "--no-validate"]) == 0
    )
    summary = json.loads(capsys.readouterr().out)
    assert [j["id"] for j in summary["jobs"]] == ["alpha"]


def test_bad_batch_options_are_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["batch", str(tmp_path / "nothing"), "-o", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err.strip() == f"error: {tmp_path / 'nothing'}: no such file or folder"


# ---- Ray ---------------------------------------------------------------------------------------
def _comparable(summary: dict[str, Any]) -> dict[str, Any]:
    """The summary without what is measured (times) or depends on earlier runs (cached)."""
    copy = json.loads(json.dumps(summary))
    for job in copy["jobs"]:
        del job["seconds"], job["cached"]
    for key in ("seconds", "wall_seconds", "cached"):
        del copy["totals"][key]
    return copy


def _tree(root: Path) -> dict[str, bytes]:
    return {
        str(p.relative_to(root)): p.read_bytes()
        for p in sorted(root.rglob("*"))
        if p.is_file() and ".robodesc-batch" not in p.parts and not p.name.startswith("summary.")
    }


@pytest.mark.slow
def test_ray_gives_the_same_summary_and_bytes_as_the_local_pool(tmp_path: Path) -> None:
    pytest.importorskip("ray")
    robots = make_collection(tmp_path)
    python_robot(robots / "raises.py", "raises", after=CORRUPT_IR)
    common = ("-t", "usd", "-j", "2", "--run-python")
    code_local, local = batch(str(robots), "-o", str(tmp_path / "local"), *common)
    code_ray, on_ray = batch(str(robots), "-o", str(tmp_path / "ray"), *common, "--executor", "ray")
    assert code_local == code_ray == 2
    assert _comparable(local) == _comparable(on_ray)
    assert by_id(on_ray)["raises"]["status"] == "crashed"
    local_files, ray_files = _tree(tmp_path / "local"), _tree(tmp_path / "ray")
    assert len(local_files) == 4 and local_files == ray_files


def test_progress_bar_and_final_table_on_a_terminal(tmp_path: Path) -> None:
    import io

    from rich.console import Console

    from robodesc.batch.runner import run_batch
    from robodesc.batch.summary import print_table

    robots = make_collection(tmp_path)
    (robots / "meshes" / "b.stl").unlink()
    out = tmp_path / "out"
    options = CompileOptions(validate=False, load=LoadOptions(missing_mesh=MissingMesh.ERROR))  # beta fails
    jobs = plan([str(robots)], target="urdf", options=options, root=str(out))
    screen = io.StringIO()
    console = Console(file=screen, force_terminal=True, width=120)
    run = run_batch(jobs, str(out), workers=2, progress=True, console=console)
    print_table(run.summary, console)
    text = screen.getvalue()
    assert "4/4" in text and "3 ok" in text and "1 error" in text  # done/total and the outcomes so far
    assert "jobs that did not succeed" in text and "b.stl" in text
