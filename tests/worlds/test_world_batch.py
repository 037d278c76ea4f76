"""``robodesc batch`` with a world: every robot of the batch on the same terrain (the world options
of ``robodesc compile``), a manifest job's own world over the command line's, and a changed world
file re-running the jobs that read it."""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Any

import mujoco
import pytest
from pxr import Usd, UsdGeom

from robodesc.cli import main
from tests.conftest import EXAMPLES, WORLDS

STEP = WORLDS / "step_20cm" / "step_20cm.world"
SLOPE = WORLDS / "slope_20" / "slope_20.world"


def _batch(*args: str) -> tuple[int, dict[str, Any]]:
    argv = ["batch", *args, "-q", "-j", "1"]
    code = main(argv)
    out = Path(argv[argv.index("-o") + 1])
    return code, json.loads((out / "summary.json").read_text())


def _robots(tmp_path: Path) -> Path:
    robots = tmp_path / "robots"
    robots.mkdir()
    shutil.copy(EXAMPLES / "quadruped.yaml", robots / "quadruped.yaml")
    shutil.copy(EXAMPLES / "urdf" / "gripper_arm.urdf", robots / "gripper_arm.urdf")
    return robots


def test_batch_puts_every_robot_in_the_world(tmp_path: Path) -> None:
    out = tmp_path / "out"
    args = ("-t", "mjcf", "--world", str(STEP), "--spawn", "5,0", "--no-validate")
    code, summary = _batch(str(_robots(tmp_path)), "-o", str(out), *args)
    assert code == 0, summary
    jobs = {job["id"]: job for job in summary["jobs"]}
    assert set(jobs) == {"quadruped", "gripper_arm"}
    for job in jobs.values():
        scene = out / Path(job["files"]["scene"])
        model = mujoco.MjModel.from_xml_path(str(scene))
        assert model.nhfield == 1 and model.opt.timestep == pytest.approx(0.001)
        data = mujoco.MjData(model)
        mujoco.mj_forward(model, data)
        # Each robot on the step's top at x = 5 m: its lowest point no lower than the 0.2 m surface.
        root = data.xpos[1]
        assert root[0] == pytest.approx(5.0) and root[2] > 0.2


def test_manifest_job_world_and_a_changed_world_reruns(tmp_path: Path) -> None:
    robots = _robots(tmp_path)
    world = tmp_path / "step.world"
    world.write_text(STEP.read_text().replace("model:///step_20cm/", f"file://{STEP.parent}/"))
    (robots / "jobs.yaml").write_text(
        f"""jobs:
  - input: quadruped.yaml
    id: on_step
  - input: quadruped.yaml
    id: on_slope
    options: {{world: {SLOPE}, spawn: [1.0, 0.0]}}
"""
    )
    out = tmp_path / "out"
    args = (str(robots / "jobs.yaml"), "-o", str(out), "-t", "usd", "--world", str(world), "--no-validate")
    code, summary = _batch(*args)
    assert code == 0, summary
    stages = {job["id"]: Usd.Stage.Open(str(out / job["files"]["world"])) for job in summary["jobs"]}
    spawn = {
        k: UsdGeom.Xformable(s.GetPrimAtPath("/World/quadruped")).GetLocalTransformation() for k, s in stages.items()
    }
    assert spawn["on_step"].ExtractTranslation()[0] == 0.0  # the command line's world, at its origin
    assert spawn["on_slope"].ExtractTranslation()[0] == pytest.approx(1.0)  # the job's own world and spawn
    # The same batch again: nothing to do. The step's world edited: only the job that reads it reruns.
    assert {job["id"] for job in _batch(*args)[1]["jobs"] if not job["cached"]} == set()
    world.write_text(world.read_text().replace("<max_step_size>0.001<", "<max_step_size>0.002<"))
    code, summary = _batch(*args)
    assert {job["id"] for job in summary["jobs"] if not job["cached"]} == {"on_step"}
    job = next(job for job in summary["jobs"] if job["id"] == "on_step")
    # Read as text: usd-core keeps the layers opened above, and would hand back the old one.
    assert "timeStepsPerSecond = 500" in (out / job["files"]["world"]).read_text()
