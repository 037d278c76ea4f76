"""Spawn a robodesc Isaac folder from its defaults in Newton 1.8 and check that it stands.

Runs in the Newton consumer environment (``tests/consumers/run.sh`` builds it). The scenario is
Isaac Lab's (tests/consumers/isaaclab_check.py) without Isaac Lab: the folder's USD is loaded with
``add_usd`` above a ground plane at the module's ``init_state.pos``, the joints start at the
module's ``init_state.joint_pos`` (the default pose) with the drives' targets there too, and the
robot steps for 1 s at 200 Hz with SolverMuJoCo (MuJoCo's C engine with its own contacts,
``implicitfast``, the integrator Isaac Lab's kit-less backend uses). Checks:

- floating robot: the root's up axis stays upright, up·z >= 0.9, at every step, and the root does
  not fall through the ground (stays above -0.25 m: a mobile base's root is at ground level);
- fixed robot: no joint leaves its start by more than 0.1 rad (0.02 m);
- the drives' stiffness and damping Newton read from the USD equal the module's SI gains
  (relative 1e-4: the USD stores float32 per-degree values), and the USD's initial joint state
  equals the module's pose.

Writes one JSON object to ``--out``: ``{"status": "pass" | "fail: why", "checks": {...}}``.
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

DT = 1.0 / 200.0


def run(folder: str, seconds: float, spawn_z: float | None = None) -> dict[str, Any]:
    import newton
    import numpy as np
    import warp as wp

    module_path = next(os.path.join(folder, n) for n in os.listdir(folder) if n.endswith("_isaaclab.py"))
    data = runpy.run_path(module_path)["ROBOT"]
    usd = next(os.path.join(folder, n) for n in os.listdir(folder) if n.endswith(".usda"))
    floating = not data["fix_base"]
    pos = tuple(float(v) for v in data["init_state"]["pos"])
    if spawn_z is not None:  # the old modules spawned at the origin: the caller drops them from a height
        pos = (pos[0], pos[1], spawn_z)
    builder = newton.ModelBuilder()
    builder.add_ground_plane()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        builder.add_usd(
            usd,
            xform=wp.transform(wp.vec3(*pos), wp.quat_identity()),
            enable_self_collisions=False,
            load_visual_shapes=False,
        )
        model = builder.finalize(device="cpu")
    corrected = [str(w.message) for w in caught if "nertia" in str(w.message)]
    names = [label.rsplit("/", 1)[-1] for label in model.joint_label]
    q_start = model.joint_q_start.numpy()
    qd_start = model.joint_qd_start.numpy()
    types = model.joint_type.numpy()
    one_dof = {
        n: (int(q_start[j]), int(qd_start[j]))
        for j, n in enumerate(names)
        if types[j] in (int(newton.JointType.REVOLUTE), int(newton.JointType.PRISMATIC))
    }
    checks: dict[str, Any] = {"floating": floating, "inertia_warnings": corrected}
    # The pose: the module's. Newton reads the USD's drive targets (it leaves the joint state
    # attributes to the caller): they are the USD's initial pose and must be the module's.
    q = model.joint_q.numpy().copy()
    usd_targets = model.joint_target_q.numpy()
    pose = data["init_state"]["joint_pos"]
    state_error = 0.0
    for name, value in pose.items():
        if name in one_dof:
            state_error = max(state_error, abs(float(usd_targets[one_dof[name][0]]) - value))
    checks["usd_pose_error"] = state_error
    for name, (qi, _) in one_dof.items():
        q[qi] = float(pose.get(name, 0.0))
    # Targets are indexed by coordinate, like joint_q.
    target_q = usd_targets.copy()
    for qi, _ in one_dof.values():
        target_q[qi] = q[qi]
    # Gains read back, SI on both sides.
    ke, kd = model.joint_target_ke.numpy(), model.joint_target_kd.numpy()
    worst = {"stiffness": 0.0, "damping": 0.0}
    for group in data["actuators"].values():
        for expr in group["joint_names_expr"]:
            name = expr.replace("\\", "")
            if name not in one_dof:
                continue
            di = one_dof[name][1]
            for key, values in (("stiffness", ke), ("damping", kd)):
                want = group.get(key) or 0.0
                worst[key] = max(
                    worst[key], abs(float(values[di]) - want) / max(1e-9, abs(want)) if want else abs(float(values[di]))
                )
    checks["gain_errors"] = worst
    state, after = model.state(), model.state()
    control = model.control()
    state.joint_q.assign(q)
    control.joint_target_q.assign(target_q)
    newton.eval_fk(model, state.joint_q, state.joint_qd, state)
    solver = newton.solvers.SolverMuJoCo(model, use_mujoco_cpu=True, integrator="implicitfast", njmax=600, nconmax=300)
    root = int(model.joint_child.numpy()[0])
    lowest_up, lowest_z, drift = 1.0, math.inf, 0.0
    q0 = q.copy()
    steps = round(seconds / DT)
    finite = True
    for _ in range(steps):
        state.clear_forces()
        solver.step(state, after, control, None, DT)
        state, after = after, state
        body_q = state.body_q.numpy()
        if not np.all(np.isfinite(body_q)):
            finite = False
            break
        x, y = float(body_q[root][3]), float(body_q[root][4])
        lowest_up = min(lowest_up, 1.0 - 2.0 * (x * x + y * y))
        lowest_z = min(lowest_z, float(body_q[root][2]))
        if not floating:
            qn = state.joint_q.numpy()
            for qi, _ in one_dof.values():
                drift = max(drift, abs(float(qn[qi]) - float(q0[qi])))
    checks.update(lowest_up_z=lowest_up, lowest_root_z=lowest_z, start_z=pos[2], joint_drift=drift, finite=finite)
    problems = []
    if not finite:
        problems.append("state not finite")
    if floating and lowest_up < 0.9:
        problems.append(f"tipped over (lowest up·z {lowest_up:.3f})")
    # A mobile base's root (base_footprint) sits at the ground: only a fall through it fails.
    if floating and lowest_z < -0.25:
        problems.append(f"fell through the ground (root at {lowest_z:.3f} m)")
    if not floating and drift > 0.1:
        problems.append(f"did not hold its pose (drift {drift:.3f})")
    bad = {k: v for k, v in worst.items() if v > 1e-4}
    if bad:
        problems.append(f"gains read back differ: {bad}")
    if state_error > 1e-4:
        problems.append(f"the USD's initial targets differ from the module's pose by {state_error:.3g}")
    return {"status": "pass" if not problems else "fail: " + "; ".join(problems), "checks": checks}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--folder", help="robodesc's --isaac-sim folder")
    ap.add_argument("--cases", help='a JSON list of {"name", "folder", "spawn_z"?}: one process, many robots')
    ap.add_argument("--seconds", type=float, default=1.0)
    ap.add_argument("--spawn-z", type=float, default=None, help="root height instead of the module's")
    ap.add_argument("--out", required=True)
    args = ap.parse_args(argv)
    cases = [{"name": "robot", "folder": args.folder, "spawn_z": args.spawn_z}]
    if args.cases:
        with open(args.cases, encoding="utf-8") as f:
            cases = json.load(f)
    results: dict[str, Any] = {}
    for case in cases:
        try:
            results[case["name"]] = run(os.path.abspath(case["folder"]), args.seconds, case.get("spawn_z"))
        except Exception as exc:  # the failure is the result
            why = f"fail: {type(exc).__name__}: {str(exc)[:300]}"
            results[case["name"]] = {"status": why, "traceback": traceback.format_exc()[-3000:]}
        print(case["name"], results[case["name"]]["status"], flush=True)
        with open(args.out, "w", encoding="utf-8") as f:
            json.dump(results if args.cases else results["robot"], f, default=str)
            f.write("\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
