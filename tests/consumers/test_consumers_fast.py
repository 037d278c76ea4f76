"""The fast subset of the consumer tier, for the normal test run.

Newton (and Isaac Lab) need Python 3.12 environments of their own that CI does not build (Newton,
Warp and MuJoCo-Warp are about 2 GB and compile kernels on first use), so these tests run only
where ``tests/consumers/run.sh`` has built them (``$ROBODESC_CONSUMERS_DIR``, default
``~/.cache/robodesc-consumers``) and are skipped elsewhere. The full tier's results are in
benchmarks/results/consumers.json.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from robodesc.cli import main
from tests.conftest import EXAMPLES, ROOT

HERE = Path(__file__).resolve().parent
ENVS = Path(os.environ.get("ROBODESC_CONSUMERS_DIR", Path.home() / ".cache" / "robodesc-consumers"))
USD_DATA = ROOT / "tests" / "usd" / "data"


def _env_python(name: str) -> Path:
    python = ENVS / name / "bin" / "python"
    if not (ENVS / name / ".built").is_file() or not python.is_file():
        pytest.skip(f"no {name} consumer environment in {ENVS} (tests/consumers/run.sh builds it)")
    return python


def _newton(cases: list[dict[str, object]], tmp_path: Path) -> dict[str, dict[str, object]]:
    python = _env_python("newton")
    cases_path = tmp_path / "cases.json"
    cases_path.write_text(json.dumps(cases))
    out = tmp_path / "newton.json"
    proc = subprocess.run(
        [str(python), str(HERE / "newton_check.py"), "--cases", str(cases_path), "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=900,
        check=False,
    )
    assert out.is_file(), proc.stderr[-3000:]
    result: dict[str, dict[str, object]] = json.loads(out.read_text())
    return result


@pytest.mark.parametrize(
    ("source", "floating"),
    [
        (USD_DATA / "gripper.urdf", False),
        (USD_DATA / "arm.urdf", False),
        (EXAMPLES / "urdf" / "gripper_arm.urdf", True),
    ],
    ids=["gripper", "arm", "gripper_arm_floating"],
)
def test_newton_reads_the_usd_as_it_reads_the_urdf(source: Path, floating: bool, tmp_path: Path) -> None:
    """Mimic (with offset and effort), damping, friction, velocity limits, armature-free drives: every
    number Newton derives from robodesc's USD equals what it derives from the URDF, and 200 MuJoCo
    steps agree."""
    usd = tmp_path / "robot.usda"
    flags = ["--no-fix-base"] if floating else []
    # The constants newton_check gives Newton's URDF reader (-t usd derives per-joint gains otherwise).
    flags += ["--stiffness", "100", "--damping", "1"]
    assert main(["compile", str(source), "-t", "usd", "-o", str(usd), "-q", "--no-validate", *flags]) == 0
    result = _newton([{"name": "usd", "urdf": str(source), "usd": str(usd), "floating": floating}], tmp_path)["usd"]
    failed = [c for c in result["checks"] if not c["ok"]]  # type: ignore[union-attr]
    assert result["status"] == "pass", failed or result


FAITHFUL = ("--no-merge-fixed", "--no-default-armature")


@pytest.mark.parametrize("floating", [False, True], ids=["fixed", "floating"])
def test_newton_reads_the_mjcf_as_it_reads_the_urdf(floating: bool, tmp_path: Path) -> None:
    """Newton's add_mjcf of robodesc's robot.xml against its add_urdf of the source: masses, inertias,
    joints, limits, actuator kp/kv (SI per radian), force ranges, damping, friction, mimic, FK and
    200 MuJoCo steps (the tier's newton_mjcf column on the example)."""
    source = EXAMPLES / "urdf" / "gripper_arm.urdf"
    xml = tmp_path / "mjcf" / "robot.xml"
    base = "--no-fix-base" if floating else "--fix-base"
    # Number by number against add_urdf: the source's bodies and armature, not the MJCF preset's fused
    # fixed links and estimated armature.
    argv = ["compile", str(source), "-t", "mjcf", "-o", str(xml), "-q", "--no-validate", base, *FAITHFUL]
    assert main([*argv, "--stiffness", "100", "--damping", "1"]) == 0
    case = {"name": "mjcf", "urdf": str(source), "mjcf": str(xml), "floating": floating}
    result = _newton([case], tmp_path)["mjcf"]
    failed = [c for c in result["checks"] if not c["ok"]]  # type: ignore[union-attr]
    assert result["status"] == "pass", failed or result


def test_newton_reads_the_isaac_folder(tmp_path: Path) -> None:
    out = tmp_path / "isaac"
    source = EXAMPLES / "urdf" / "gripper_arm.urdf"
    # Uniform gains: the checker gives Newton's URDF import one stiffness and damping (the folder's own
    # default gains are derived per joint: tests/isaac/test_default_stance.py).
    argv = ["compile", str(source), "--isaac-sim", "-o", str(out), "-q", "--no-validate", "--no-preview", *FAITHFUL]
    assert main([*argv, "--stiffness", "100", "--damping", "1"]) == 0
    case = {"name": "isaac", "urdf": str(out / "gripper_arm.urdf"), "usd": str(out / "gripper_arm.usda")}
    result = _newton([case], tmp_path)["isaac"]
    assert result["status"] == "pass", [c for c in result["checks"] if not c["ok"]]  # type: ignore[union-attr]


_REAL_CLASSES = """
import json, runpy, sys
from isaaclab.actuators import ImplicitActuatorCfg
from isaaclab.assets import ArticulationCfg
module = runpy.run_path(sys.argv[1])
cfg = module["ROBOT_CFG"]
group = next(iter(cfg.actuators.values()))
print(json.dumps({
    "rot": list(cfg.init_state.rot),
    "default_rot": list(ArticulationCfg.InitialStateCfg().rot),
    "joint_effort_limit": group.joint_effort_limit,
    "effort_limit_sim": group.effort_limit_sim,
    "type": type(group).__name__,
    "sim": (lambda c: {
        "dt": c.dt, "num_substeps": c.physics.num_substeps, "cone": c.physics.solver_cfg.cone,
        "impratio": c.physics.solver_cfg.impratio, "integrator": c.physics.solver_cfg.integrator,
    })(module["make_sim_cfg"]("cpu")),
}))
"""


@pytest.mark.parametrize("version", ["3", "2"])
def test_isaac_lab_module_builds_real_classes(version: str, tmp_path: Path) -> None:
    """Both module flavours build Isaac Lab 3.0's real ArticulationCfg, upright and with the solver
    limits in 3.0's non-deprecated fields."""
    python = _env_python("isaaclab")
    out = tmp_path / "isaac"
    source = EXAMPLES / "urdf" / "gripper_arm.urdf"
    args = ["compile", str(source), "--isaac-sim", "-o", str(out), "-q", "--no-validate"]
    assert main([*args, "--isaac-lab-version", version]) == 0
    script = tmp_path / "probe.py"
    script.write_text(_REAL_CLASSES)
    proc = subprocess.run(
        [str(python), str(script), str(out / "gripper_arm_isaaclab.py")],
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    seen = json.loads(proc.stdout.strip().splitlines()[-1])
    assert seen["type"] == "ImplicitActuatorCfg"
    assert seen["rot"] == seen["default_rot"] == [0.0, 0.0, 0.0, 1.0]
    assert seen["joint_effort_limit"] is not None and seen["effort_limit_sim"] is None
    # The recommended simulation settings build Isaac Lab 3's Newton MJWarp config (a welded arm: one substep).
    assert seen["sim"] == {
        "dt": 0.005,
        "num_substeps": 1,
        "cone": "elliptic",
        "impratio": 100.0,
        "integrator": "implicitfast",
    }


def test_python_is_the_projects() -> None:
    # The consumers run in their own interpreters; robodesc's own code stays on 3.11+.
    assert sys.version_info >= (3, 11)
