"""Spawn a robodesc Isaac folder in Isaac Lab 3.0 (kit-less, Newton MJWarp backend, CPU).

Runs inside the Isaac Lab consumer environment (Python 3.12, ``isaaclab`` with torch). The folder's
``<robot>_isaaclab.py`` builds a real ``ArticulationCfg``; the robot spawns above a local ground box
(the stock ground plane is downloaded from the internet; fixed robots get none), steps 100 times, and must stay upright
(a floating robot: up·z >= 0.9 at every step) or hold its pose (a fixed robot: no joint leaves its
start by more than 0.1 rad, or 0.02 m); its stiffness, damping, armature and joint limits must read
back as the module wrote them. Writes one JSON object to ``--out``: ``{"status": "pass" | "fail:
why", "checks": {...}}``; with ``--cases`` (a JSON list of ``{"name", "folder"}``, the corpus tier
``isaaclab_tier.py``), one object per case name, rewritten after every case.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import runpy
import traceback
import warnings
from typing import Any

# Joint drift a fixed robot may show and still "hold its pose" (rad, or m for a prismatic joint).
HOLD_DRIFT = 0.1
THROUGH_GROUND = -0.25  # m: a floating robot's root below this fell through the ground
_LAUNCHED: list[object] = []


def _sim_cfg(sim: str = "check", module: dict[str, Any] | None = None) -> Any:
    """``check``: MJWarp ``implicitfast``, Isaac Lab's defaults otherwise (pyramidal cone, impratio 1,
    one substep); ``lab``: Isaac Lab 3's defaults alone (Euler); ``module``: the module's
    ``make_sim_cfg`` (its recommended settings). Contact buffers as large in each."""
    from isaaclab.sim import SimulationCfg
    from isaaclab_newton.physics import MJWarpSolverCfg, NewtonCfg

    if sim == "module":
        assert module is not None
        cfg = module["make_sim_cfg"]("cpu")
        cfg.physics.solver_cfg.njmax, cfg.physics.solver_cfg.nconmax = 600, 300
        return cfg
    extra = {"integrator": "implicitfast"} if sim == "check" else {}
    return SimulationCfg(
        dt=1 / 200,
        device="cpu",
        physics=NewtonCfg(solver_cfg=MJWarpSolverCfg(njmax=600, nconmax=300, **extra)),
    )


def run(folder: str, steps: int, module_spawn: bool = False, sim: str = "check") -> dict[str, object]:
    from isaaclab.test.utils import launch_test_simulation

    module_path = next(os.path.join(folder, n) for n in os.listdir(folder) if n.endswith("_isaaclab.py"))
    sim_cfg = _sim_cfg(sim, runpy.run_path(module_path) if sim == "module" else None)
    if not _LAUNCHED:  # once per process: the corpus tier runs many robots in one
        # A Newton physics config selects the kit-less runtime (no Isaac Sim, no GPU).
        launch_test_simulation(sim_cfg, device="cpu")
        _LAUNCHED.append(True)

    import isaaclab.sim as sim_utils
    import torch
    from isaaclab.assets import Articulation, AssetBaseCfg
    from isaaclab.cloner import CloneCfg, clone_plan_from_env_0, replicate
    from isaaclab.sim import build_simulation_context
    from isaaclab.utils import replace

    module = runpy.run_path(module_path)
    cfg = module["ROBOT_CFG"]
    data = module["ROBOT"]
    if cfg is None:
        return {"status": "fail: the module did not build an ArticulationCfg", "checks": {}}
    floating = not data["fix_base"]
    cfg = replace(cfg, prim_path="/World/Env_[^/]*/Robot")
    if not module_spawn:
        # Spawn high enough that a floating robot falls onto the box rather than into it (modules
        # before the default pose spawned at the origin).
        cfg.init_state.pos = (0.0, 0.0, 0.6 if floating else 0.0)
    checks: dict[str, object] = {}
    with build_simulation_context(sim_cfg=sim_cfg, device="cpu", add_ground_plane=False) as sim:
        # The ground is a static box declared like any asset, so the clone plan puts it in the model.
        ground = AssetBaseCfg(
            prim_path="/World/Ground",
            spawn=sim_utils.CuboidCfg(size=(20.0, 20.0, 0.1), collision_props=sim_utils.CollisionPropertiesCfg()),
            init_state=AssetBaseCfg.InitialStateCfg(pos=(0.0, 0.0, -0.05)),
        )
        # Only a floating robot stands on it: a fixed robot's base is welded where its module puts
        # it (the origin), and hands, Baxter's pedestal or a flying arm's frame reach below that
        # into the box, which pushed their joints 0.1-2 rad off the pose they were asked to hold.
        assets = [cfg]
        if floating:
            ground.spawn.func("/World/Ground", ground.spawn, translation=(0.0, 0.0, -0.05))
            assets.append(ground)
        # One environment, cloned the way Isaac Lab's own articulation tests do it.
        sim_utils.create_prim("/World/Env_0", "Xform", translation=(0.0, 0.0, 0.0))
        clone_plan_from_env_0(CloneCfg(clone_template="/World/Env_{}"), assets, 1, 2.5)
        robot = Articulation(cfg)
        replicate(sim.get_clone_plan())
        sim.reset()
        # A robot with no controller holds its default pose: Isaac Lab's position targets start
        # at 0 whatever init_state says (an environment's actions set them), so the check sets
        # them to the default joint positions, as a "hold" action does.
        default = robot.data.default_joint_pos
        default = default.torch if hasattr(default, "torch") else default
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DeprecationWarning)
            robot.set_joint_position_target_index(target=default)
        start_q = _torch(robot.data.joint_pos)[0].clone()
        start_xy = [float(v) for v in _torch(robot.data.root_pos_w)[0][:2]]
        lowest_up, drift = 1.0, 0.0
        for _ in range(steps):
            robot.write_data_to_sim()
            sim.step()
            robot.update(sim.get_physics_dt())
            quat = _torch(robot.data.root_quat_w)[0]  # (x, y, z, w) in 3.0
            # The body's up axis in the world: z of R(q) e_z; upright = close to +1.
            x, y = float(quat[0]), float(quat[1])
            up = 1.0 - 2.0 * (x * x + y * y)
            lowest_up = min(lowest_up, up)
            moved = (_torch(robot.data.joint_pos)[0] - start_q).abs()
            drift = max(drift, float(moved.max()) if moved.numel() else 0.0)
        checks["root_up_z"] = up
        checks["lowest_up_z"] = lowest_up
        checks["joint_drift"] = drift
        checks["root_pos"] = [float(v) for v in _torch(robot.data.root_pos_w)[0]]
        # How far the root crept on the ground standing still (m).
        checks["creep"] = math.hypot(checks["root_pos"][0] - start_xy[0], checks["root_pos"][1] - start_xy[1])
        checks["sim"] = sim
        checks["finite"] = bool(torch.isfinite(_torch(robot.data.joint_pos)).all())
        names = list(robot.joint_names)
        stiffness = _torch(robot.data.joint_stiffness)[0]
        damping = _torch(robot.data.joint_damping)[0]
        armature = _torch(robot.data.joint_armature)[0]
        limits = _torch(robot.data.joint_pos_limits)[0]
        worst = {"stiffness": 0.0, "damping": 0.0, "armature": 0.0}
        for group in data["actuators"].values():
            for expr in group["joint_names_expr"]:
                name = expr.replace("\\", "")
                if name not in names:
                    continue
                i = names.index(name)
                for key, values in (("stiffness", stiffness), ("damping", damping), ("armature", armature)):
                    want = group.get(key) or 0.0
                    worst[key] = max(worst[key], abs(float(values[i]) - want) / max(1.0, abs(want)))
        checks["gain_errors"] = worst
        checks["limits_finite"] = int(torch.isfinite(limits).all(dim=-1).sum())
    checks["floating"] = floating
    problems = []
    if not checks["finite"]:
        problems.append("joint state not finite")
    if floating and lowest_up < 0.9:
        problems.append(f"root not upright (lowest up·z = {lowest_up:.3f}, at the end {up:.3f})")
    if not floating and drift > HOLD_DRIFT:
        problems.append(f"did not hold its pose (joint drift {drift:.3f})")
    # A mobile base's root (base_footprint) sits at the ground: only a fall through it fails
    # (stand_check.py's rule).
    if floating and checks["root_pos"][2] < THROUGH_GROUND:
        problems.append(f"fell through the ground (root z = {checks['root_pos'][2]:.3f} m)")
    bad = {k: v for k, v in worst.items() if v > 1e-4}
    if bad:
        problems.append(f"read back differs: {bad}")
    return {"status": "pass" if not problems else "fail: " + "; ".join(problems), "checks": checks}


def _torch(value: object) -> Any:  # torch.Tensor; a warp array is converted
    import torch

    if isinstance(value, torch.Tensor):
        return value
    import warp as wp

    return wp.to_torch(value)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--folder", help="robodesc's --isaac-sim folder")
    ap.add_argument("--cases", help='a JSON list of {"name", "folder"}: one process, many robots')
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument(
        "--module-spawn", action="store_true", help="spawn at the module's init_state.pos (the default spawn)"
    )
    ap.add_argument("--sim", choices=("check", "lab", "module"), default="check", help="the simulation settings")
    ap.add_argument("--out", required=True)
    args = ap.parse_args(argv)
    cases = [{"name": "robot", "folder": args.folder}]
    if args.cases:
        with open(args.cases, encoding="utf-8") as f:
            cases = json.load(f)
    results: dict[str, Any] = {}
    for case in cases:
        try:
            result = run(os.path.abspath(case["folder"]), args.steps, args.module_spawn, args.sim)
        except Exception as exc:  # the failure is the result
            result = {
                "status": f"fail: {type(exc).__name__}: {str(exc)[:300]}",
                "traceback": traceback.format_exc()[-3000:],
            }
        results[case["name"]] = result
        print(case["name"], result["status"], flush=True)
        with open(args.out, "w", encoding="utf-8") as f:
            f.write(json.dumps(results if args.cases else result, default=str) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
