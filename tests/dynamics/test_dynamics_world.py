"""``validate --dynamics`` on a world (docs/dynamics.md, "On a world"): the stand scenario.

Fast (MuJoCo): the example quadruped stands on examples/worlds/steps.world from scene.xml's home
keyframe: upright, its soles on the ground, the root's height over the ground under each foot as
the stance gives it, the feet's touch sensors reading its weight. The engine tier
(tests/dynamics/run.sh) adds PhysX and Newton on the same world, and the proof that Newton, given the
terrain as a heightfield, lets a box fall into gap_40cm's gap where the triangle mesh (collided as
its convex hull) held it up."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

import robodesc
from robodesc.validation.dynamics.newton_run import newton_python
from robodesc.validation.physx_python import physx_python
from robodesc.validation.report import Status

from ..conftest import EXAMPLES, WORLDS

QUADRUPED = str(EXAMPLES / "quadruped.yaml")
STEPS = str(EXAMPLES / "worlds" / "steps.world")
TIER = pytest.mark.skipif(os.environ.get("ROBODESC_DYNAMICS_TIER") != "1", reason="engine tier: tests/dynamics/run.sh")


def _rows(dyn: robodesc.validation.dynamics.DynamicsReport, name: str) -> list[robodesc.validation.report.Check]:
    return [c for c in dyn.checks if c.name == name]


def test_mujoco_stands_on_the_world() -> None:
    result = robodesc.check(QUADRUPED, "mjcf", world=STEPS, dynamics={"engines": ("mujoco",)})
    dyn = result.dynamics
    assert dyn is not None and dyn.ok, dyn.to_text()
    (run,) = [r for r in dyn.runs if r.scenario == "stand"]
    assert run.tilt is not None and run.tilt < 0.02  # rad
    assert run.sole_gap is not None and run.sole_gap < 0.005
    assert run.slip is not None and run.slip < 0.01
    # The stance holds the root 0.34 m over the ground under each foot (the drop on a plane: 0.340 m).
    assert len(run.feet_height) == 4 and all(v == pytest.approx(0.34, abs=0.01) for v in run.feet_height.values())
    assert run.contact_sum is not None and run.weight is not None
    assert run.contact_sum == pytest.approx(run.weight, rel=0.02)
    assert [c.status for c in _rows(dyn, "stand") + _rows(dyn, "contact")] == [Status.PASS, Status.PASS]
    assert "on the world" in dyn.to_text()


@TIER
@pytest.mark.skipif(physx_python() is None, reason="no PhysX interpreter (tests/consumers/run.sh builds one)")
@pytest.mark.skipif(newton_python() is None, reason="no Newton interpreter (tests/consumers/run.sh builds one)")
def test_the_engines_agree_on_the_world() -> None:
    engines = ("mujoco", "drake", "newton", "physx")
    result = robodesc.check(QUADRUPED, "usd", world=STEPS, dynamics={"engines": engines})
    dyn = result.dynamics
    assert dyn is not None and dyn.ok, dyn.to_text()
    assert {r.engine for r in dyn.runs if r.scenario == "stand"} == {"mujoco", "newton", "physx"}
    agree = _rows(dyn, "agree:stand")
    assert len(agree) == 3 and all(c.status is Status.PASS for c in agree), dyn.to_text()
    (drake,) = [c for c in _rows(dyn, "stand") if c.element == "drake"]
    assert drake.status is Status.SKIP and "no heightfield" in drake.message


NEWTON_GAP = """
import json, sys, warnings
sys.path.insert(0, sys.argv[3])
import newton, warp as wp
from newton_worker import _terrain_heightfields
out = {}
for swap in (False, True):
    builder = newton.ModelBuilder()
    if swap:
        builder.rigid_gap = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        builder.add_usd(sys.argv[1], floating=True, enable_self_collisions=False, load_visual_shapes=False)
    if swap:
        _terrain_heightfields(builder, [{"npz": sys.argv[2], "label": "terrain"}])
    for x in (3.2, 1.0):  # over the gap (x 3.0 to 3.4), and over the slab
        body = builder.add_body(xform=wp.transform((x, 1.5, 0.3), wp.quat_identity()))
        builder.add_shape_box(body, hx=0.1, hy=0.1, hz=0.1)
    model = builder.finalize(device="cpu")
    s0, s1, control = model.state(), model.state(), model.control()
    newton.eval_fk(model, s0.joint_q, s0.joint_qd, s0)
    solver = newton.solvers.SolverMuJoCo(model, use_mujoco_cpu=True)
    for _ in range(1000):
        s0.clear_forces()
        solver.step(s0, s1, control, None, 0.001)
        s0, s1 = s1, s0
    out["heightfield" if swap else "mesh"] = [float(z) for z in s0.body_q.numpy()[-2:, 2]]
print(json.dumps(out))
"""


@TIER
@pytest.mark.skipif(newton_python() is None, reason="no Newton interpreter (tests/consumers/run.sh builds one)")
def test_newton_drops_a_box_into_the_gap(tmp_path: Path) -> None:
    """gap_40cm's terrain as the USD world stage writes it (a static triangle mesh): Newton's MuJoCo
    solver collides its convex hull, so a 20 cm box dropped over the 40 cm gap rests on the hull at
    the slab's top; given the heightfield the validate stand gives it, the box falls in."""
    from robodesc.check_world import _heightfields
    from robodesc.emit.common.world import place_world
    from robodesc.frontends.load import load_source
    from robodesc.frontends.world import load_world
    from robodesc.ir.diagnostics import Findings
    from robodesc.options import build_options

    world_file = str(WORLDS / "gap_40cm" / "gap_40cm.world")
    robodesc.compile_to_usd(QUADRUPED, str(tmp_path / "quadruped.usda"), world=world_file)
    opts = build_options({"world": world_file})
    robot = load_source(QUADRUPED, opts.load, Findings())
    world = load_world(opts.world, Findings())
    assert world is not None
    (field,) = _heightfields(place_world(robot, world, Findings()), str(tmp_path))
    python = newton_python()
    assert python is not None
    workers = str(Path(robodesc.__file__).parent / "validation" / "dynamics")
    done = subprocess.run(
        [python, "-c", NEWTON_GAP, str(tmp_path / "quadruped_world.usda"), field["npz"], workers],
        capture_output=True, text=True, timeout=900, check=False,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    boxes = json.loads(done.stdout.strip().splitlines()[-1])
    gap_on_mesh, slab_on_mesh = boxes["mesh"]
    gap_on_field, slab_on_field = boxes["heightfield"]
    assert gap_on_mesh == pytest.approx(0.095, abs=0.01)  # held up by the hull
    assert gap_on_field < -0.5  # in the gap
    assert slab_on_mesh == pytest.approx(0.1, abs=0.01) and slab_on_field == pytest.approx(0.1, abs=0.01)


def test_a_sole_in_the_world_and_the_measures() -> None:
    """measure_stand on a hand-made run: a foot link turned 90° about z at (1, 2, 0.3), its sole 0.3 m
    below and 0.1 m ahead in its own frame, over ground at z = 0.05 (0.05 m up: the sole's gap)."""
    import math

    import numpy as np

    from robodesc.validation.dynamics.result import Run
    from robodesc.validation.dynamics.run import _sole, measure_stand
    from robodesc.validation.dynamics.scenarios import Setup, WorldStand

    c = math.cos(math.pi / 4)
    assert _sole((0.1, 0.0, -0.3), [1.0, 2.0, 0.3, c, 0.0, 0.0, c]) == pytest.approx((1.0, 2.1, 0.0))
    world = WorldStand({}, (0.0, 0.0, 0.4, 0.0), {"foot": (0.1, 0.0, -0.3)}, lambda x, y: np.full(np.shape(x), -0.05))
    setup = Setup(pose={}, gains={}, floating=True, stand_height=0.4, friction=None, world=world)
    run = Run("mujoco", "mjcf", "stand", height=0.5, mass=10.0)
    run.feet_start = {"foot": [1.0, 2.0, 0.3, 1.0, 0.0, 0.0, 0.0]}
    run.feet_end = {"foot": [1.0, 2.0, 0.3, c, 0.0, 0.0, c]}
    measure_stand(run, setup)
    assert run.feet_height == {"foot": pytest.approx(0.55)}
    assert run.sole_gap == pytest.approx(0.05)
    assert run.slip == pytest.approx(math.hypot(0.1, 0.1))  # (1.1, 2.0) -> (1.0, 2.1)
    assert run.weight == pytest.approx(98.1)


def test_drake_is_a_skip_row() -> None:
    import numpy as np

    from robodesc.frontends.load import load_source
    from robodesc.ir.diagnostics import Findings
    from robodesc.options import build_options
    from robodesc.validation.dynamics import DynamicsOptions
    from robodesc.validation.dynamics.result import DynamicsReport
    from robodesc.validation.dynamics.run import _stand
    from robodesc.validation.dynamics.scenarios import WorldStand, make_setup

    robot = load_source(QUADRUPED, build_options({}).load, Findings())
    opts = DynamicsOptions(engines=("drake",))
    opts.world = WorldStand({}, (0.0, 0.0, 0.4, 0.0), {}, lambda x, y: np.zeros(np.shape(x)))
    report = DynamicsReport(robot=robot.name)
    _stand(robot, make_setup(robot, opts), opts, report, {"drake"})
    (row,) = report.checks
    assert (row.name, row.status, row.element) == ("stand", Status.SKIP, "drake") and "no heightfield" in row.message
    assert not report.runs


@TIER
def test_an_sdf_world_checked_with_drake() -> None:
    """-t sdf --world: Drake's hold, drop and slide take the robot compiled alone (the world's static
    terrain link weighed 1 kg in its total mass), MuJoCo stands on the world all the same."""
    result = robodesc.check(QUADRUPED, "sdf", world=STEPS, dynamics={"engines": ("mujoco", "drake")})
    dyn = result.dynamics
    assert dyn is not None and dyn.ok, dyn.to_text()
    assert all(c.status is Status.PASS for c in _rows(dyn, "mass")), dyn.to_text()
    (run,) = [r for r in dyn.runs if r.scenario == "stand"]
    assert all(v == pytest.approx(0.35, abs=0.01) for v in run.feet_height.values()), dyn.to_text()
