"""robodesc's default MJCF against mujoco_menagerie's hand-tuned models (issue 35).

Each robot is compiled from its own URDF (example-robot-data) with ``-t mjcf`` and default flags, and
its ``scene.xml`` simulated in MuJoCo; with ``--menagerie DIR`` (a checkout of
google-deepmind/mujoco_menagerie) menagerie's scene of the same robot is simulated the same way.
Measured per model:

- ``hold``: from the ``home`` keyframe (else ``qpos0``), the actuators holding it, 5 s: the largest
  joint error over the run (rad, actuated hinge joints) and at its end (``sag``); for a floating
  robot also whether it stands (the root's up axis at least 0.9 upright and its height at least
  half the start's, at the end) and how far its root crept on the floor (``drift``, m);
- ``random``: from home, 2 s of uniform random control within each ``ctrlrange`` (redrawn every
  0.1 s, seed 0): finite or not, the fastest joint and its speed over its URDF velocity limit;
- ``steps/s``: steps per second of CPU time over 2,000 steps holding home, the best of five runs
  (one process, warm; CPU time because the machines this runs on are shared).

    PYTHONPATH=src python benchmarks/menagerie_compare.py [--robots panda,ur5] [--menagerie DIR]

Writes benchmarks/results/menagerie_compare.json and .md (docs/mjcf.md's table). Without
``--menagerie`` (or ``ROBODESC_MENAGERIE_DIR``) only robodesc's side is measured.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from typing import Any

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "results", "menagerie_compare")

# robot -> (example-robot-data URDF under robots/ or None, menagerie scene, compile options beyond the
# defaults). None: no URDF of that robot in the installed collections (example-robot-data, icub-models,
# hello-robot-stretch-urdf) or the corpus, so only menagerie's side is measured.
ROBOTS: dict[str, tuple[str | None, str, dict[str, Any]]] = {
    "panda": ("panda_description/urdf/panda.urdf", "franka_emika_panda/scene.xml", {}),
    "fr3": (None, "franka_fr3/scene.xml", {}),
    # example-robot-data has the UR5 (CB series); menagerie models the UR5e: same kinematics, other limits.
    "ur5": ("ur_description/urdf/ur5_robot.urdf", "universal_robots_ur5e/scene.xml", {}),
    "gen3": (None, "kinova_gen3/scene.xml", {}),
    "z1": ("z1_description/urdf/z1.urdf", "unitree_z1/scene.xml", {}),
    "go1": ("go1_description/urdf/go1.urdf", "unitree_go1/scene.xml", {}),
    "a1": ("a1_description/urdf/a1.urdf", "unitree_a1/scene.xml", {}),
    "go2": ("go2_description/urdf/go2.urdf", "unitree_go2/scene.xml", {}),
    "anymal_c": ("anymal_c_simple_description/urdf/anymal.urdf", "anybotics_anymal_c/scene.xml", {}),
    # menagerie's Talos floats (position actuators, keyframe walk_pose): both robodesc rows face it.
    "talos": ("talos_data/robots/talos_reduced.urdf", "pal_talos/scene_position.xml", {}),
    "talos_floating": ("talos_data/robots/talos_reduced.urdf", "pal_talos/scene_position.xml", {"fix_base": False}),
    "allegro": ("allegro_hand_description/urdf/allegro_right_hand.urdf", "wonik_allegro/scene_right.xml", {}),
}

# menagerie's joint names where they differ from the URDF's (velocity limits come from the URDF).
_ALLEGRO = {
    f"{finger}j{i}": f"joint_{4 * n + i}.0" for n, finger in enumerate(("ff", "mf", "rf", "th")) for i in range(4)
}
JOINT_NAMES: dict[str, dict[str, str]] = {
    "panda": {**{f"joint{i}": f"panda_joint{i}" for i in range(1, 8)}, "finger_joint1": "panda_finger_joint1"},
    "allegro": _ALLEGRO,
}

# menagerie keyframes other than ``home`` that a scene starts from.
MENAGERIE_KEYS = {"pal_talos/scene_position.xml": "walk_pose"}

HOLD_SECONDS = 5.0
RANDOM_SECONDS = 2.0
SPEED_STEPS = 2000


def velocity_limits(urdf: str) -> dict[str, float]:
    out: dict[str, float] = {}
    for joint in ET.parse(urdf).getroot().iter("joint"):
        limit = joint.find("limit")
        if limit is not None and limit.get("velocity") and float(limit.get("velocity", "0")) > 0:
            out[joint.get("name", "")] = float(limit.get("velocity", "0"))
    return out


def _hinges(model: Any) -> list[tuple[str, int, int]]:
    """(name, qpos address, dof address) of every hinge and slide joint."""
    import mujoco

    out = []
    for j in range(model.njnt):
        if int(model.jnt_type[j]) in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE)):
            out.append(
                (mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j), model.jnt_qposadr[j], model.jnt_dofadr[j])
            )
    return out


def _actuated(model: Any) -> set[int]:
    import mujoco

    return {
        int(model.actuator_trnid[a, 0])
        for a in range(model.nu)
        if int(model.actuator_trntype[a]) == int(mujoco.mjtTrn.mjTRN_JOINT)
    }


def _reset(model: Any, data: Any, key_name: str = "home") -> None:
    """Start from the keyframe; without one, from ``qpos0`` with each limited joint clipped into its range
    (Allegro's thumb base starts at 0, outside 0.263-1.396) and every position servo aimed at its joint's
    start, so that holding measures holding and not a first step to the range."""
    import mujoco
    import numpy as np

    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, key_name)
    if key >= 0:
        mujoco.mj_resetDataKeyframe(model, data, key)
        mujoco.mj_forward(model, data)
        return
    mujoco.mj_resetData(model, data)
    data.ctrl[:] = 0.0
    for j in range(model.njnt):
        if model.jnt_limited[j] and int(model.jnt_type[j]) in (
            int(mujoco.mjtJoint.mjJNT_HINGE),
            int(mujoco.mjtJoint.mjJNT_SLIDE),
        ):
            adr = model.jnt_qposadr[j]
            data.qpos[adr] = np.clip(data.qpos[adr], *model.jnt_range[j])
    for a in range(model.nu):
        # A position servo: force = kp*ctrl - kp*q (gainprm[0] = -biasprm[1] > 0).
        kp = float(model.actuator_gainprm[a, 0])
        if (
            int(model.actuator_trntype[a]) == int(mujoco.mjtTrn.mjTRN_JOINT)
            and kp > 0
            and abs(float(model.actuator_biasprm[a, 1]) + kp) < 1e-9 * max(kp, 1.0)
        ):
            target = float(data.qpos[model.jnt_qposadr[model.actuator_trnid[a, 0]]])
            if model.actuator_ctrllimited[a]:
                target = float(np.clip(target, *model.actuator_ctrlrange[a]))
            data.ctrl[a] = target
    mujoco.mj_forward(model, data)


def loads_copied(folder: str, scene: str, move_original: bool) -> str:
    """ "yes" when the scene loads from a copy of its folder in another place, else the loader's message.
    ``move_original``: the original is renamed meanwhile, so that a path back into it (or into the source
    package) fails; only for folders this run wrote (a shared menagerie checkout is never moved)."""
    import shutil

    import mujoco

    with tempfile.TemporaryDirectory() as tmp:
        moved = folder.rstrip(os.sep) + ".moved"
        copy = os.path.join(tmp, "copy")
        shutil.copytree(folder, copy)
        if move_original:
            os.rename(folder, moved)
        try:
            mujoco.MjModel.from_xml_path(os.path.join(copy, os.path.relpath(scene, folder)))
            return "yes"
        except Exception as exc:  # the message is the result
            return str(exc).splitlines()[0][:120]
        finally:
            if move_original:
                os.rename(moved, folder)


def measure(scene: str, vlimits: dict[str, float], key_name: str = "home") -> dict[str, Any]:
    import mujoco
    import numpy as np

    model = mujoco.MjModel.from_xml_path(scene)
    data = mujoco.MjData(model)
    hinges = _hinges(model)
    acted = _actuated(model)
    import mujoco as mj

    held = [(n, q) for n, q, _ in hinges if mj.mj_name2id(model, mj.mjtObj.mjOBJ_JOINT, n) in acted]
    floating = model.njnt > 0 and int(model.jnt_type[0]) == int(mujoco.mjtJoint.mjJNT_FREE)
    _reset(model, data, key_name)
    q0 = data.qpos.copy()
    ctrl0 = data.ctrl.copy()
    worst = 0.0
    worst_joint = ""
    steps = int(HOLD_SECONDS / model.opt.timestep)
    for _ in range(steps):
        mujoco.mj_step(model, data)
        for name, adr in held:
            err = abs(float(data.qpos[adr] - q0[adr]))
            if err > worst:
                worst, worst_joint = err, name
    finite = bool(np.all(np.isfinite(data.qpos)))
    sag = max((abs(float(data.qpos[adr] - q0[adr])) for _, adr in held), default=0.0)
    row: dict[str, Any] = {
        "hold_max": worst if finite else math.inf,
        "hold_joint": worst_joint,
        "sag": sag if finite else math.inf,
        "timestep": float(model.opt.timestep),
        "floating": bool(floating),
        "nu": int(model.nu),
    }
    if floating:
        quat = data.qpos[3:7]
        w, x, y, _z = (float(v) for v in quat)
        up_z = 1.0 - 2.0 * (x * x + y * y)
        row["up_z"] = up_z
        row["height"] = float(data.qpos[2])
        row["stands"] = bool(finite and up_z >= 0.9 and data.qpos[2] >= 0.5 * q0[2])
        row["drift"] = float(np.hypot(data.qpos[0] - q0[0], data.qpos[1] - q0[1]))
        del w
    # Random control.
    _reset(model, data, key_name)
    rng = np.random.default_rng(0)
    lo = model.actuator_ctrlrange[:, 0].copy()
    hi = model.actuator_ctrlrange[:, 1].copy()
    limited = model.actuator_ctrllimited.astype(bool)
    lo[~limited], hi[~limited] = -1.0, 1.0
    redraw = max(1, int(0.1 / model.opt.timestep))
    fastest, fastest_joint, ratio, ratio_joint = 0.0, "", 0.0, ""
    unstable = False
    for i in range(int(RANDOM_SECONDS / model.opt.timestep)):
        if i % redraw == 0:
            data.ctrl[:] = rng.uniform(lo, hi)
        mujoco.mj_step(model, data)
        if not np.all(np.isfinite(data.qvel)) or data.warning[mujoco.mjtWarning.mjWARN_BADQACC].number:
            unstable = True
            break
        for name, _, dof in hinges:
            speed = abs(float(data.qvel[dof]))
            limit = vlimits.get(name)
            if limit and speed / limit > ratio:
                ratio, ratio_joint = speed / limit, name
            if speed > fastest:
                fastest, fastest_joint = speed, name
    row.update(
        random_stable=not unstable,
        fastest=fastest,
        fastest_joint=fastest_joint,
        speed_over_limit=ratio,
        speed_over_limit_joint=ratio_joint,
    )
    row["steps_per_s"] = steps_per_second(model, data, ctrl0, key_name)
    return row


def steps_per_second(model: Any, data: Any, ctrl: Any, key_name: str = "home") -> float:
    """MuJoCo steps per second of CPU time over SPEED_STEPS steps from ``key_name`` holding ``ctrl``.

    The best of five runs of this process's CPU time: the machine is shared (load 19 on 2 cores
    while measured), and wall time measured the neighbours."""
    import mujoco

    best = math.inf
    for _ in range(5):
        _reset(model, data, key_name)
        data.ctrl[:] = ctrl
        started = time.process_time()
        for _ in range(SPEED_STEPS):
            mujoco.mj_step(model, data)
        best = min(best, time.process_time() - started)
    return SPEED_STEPS / best


def compile_robot(source: str, out_dir: str, options: dict[str, Any], erd: str) -> tuple[str, list[str]]:
    import robodesc

    out = os.path.join(out_dir, "robot.xml")
    result = robodesc.compile_to_mjcf(source, out, package_paths={"example-robot-data": erd}, **options)
    warnings = sorted({f.code for f in result.findings if f.severity.name.lower() in ("warning", "error")})
    return os.path.join(out_dir, "scene.xml"), warnings


def _fmt(row: dict[str, Any] | None, key: str, spec: str) -> str:
    if not row or key not in row:
        return "–"
    value = row[key]
    if isinstance(value, bool):
        return "yes" if value else "NO"
    return format(value, spec)


def table(results: dict[str, dict[str, Any]]) -> str:
    lines = [
        "| robot | model | hold max (rad) | sag (rad) | stands, drift | random: stable, fastest joint (rad/s), × URDF limit "
        "| steps/s | loads copied |",
        "|---|---|---:|---:|:-:|---|---:|:-:|",
    ]
    for robot, sides in results.items():
        for side in ("robodesc", "menagerie"):
            row = sides.get(side)
            if row is None:
                continue
            if "error" in row:
                lines.append(f"| {robot} | {side} | {row['error'][:80]} | | | | | |")
                continue
            stands = f"{_fmt(row, 'stands', '')}, {row['drift']:.3f} m" if row.get("floating") else "welded"
            over = (
                f"×{row['speed_over_limit']:.2f} ({row['speed_over_limit_joint']})"
                if row["speed_over_limit"]
                else "no URDF limit"
            )
            rnd = f"{'yes' if row['random_stable'] else 'NO'}, {row['fastest_joint']} {row['fastest']:.3g}, {over}"
            lines.append(
                f"| {robot} | {side} | {_fmt(row, 'hold_max', '.3g')} | {_fmt(row, 'sag', '.3g')} | {stands} | {rnd} "
                f"| {row['steps_per_s']:.0f} | {row.get('loads_copied', '–')} |"
            )
    return "\n".join(lines) + "\n" + verdicts(results)


def verdicts(results: dict[str, dict[str, Any]]) -> str:
    """Issue 35's criteria, robodesc against menagerie, where both sides were measured."""
    lines = [
        "",
        "| robot | hold ≤ 2× menagerie's | stands 5 s (floating) | random: stable, ≤ 2× URDF velocity "
        "| steps/s ≥ menagerie's | loads copied |",
        "|---|:-:|:-:|:-:|:-:|:-:|",
    ]
    for robot, sides in results.items():
        ours, theirs = sides.get("robodesc"), sides.get("menagerie")
        if not ours or not theirs or "error" in ours or "error" in theirs:
            continue

        def mark(ok: bool) -> str:
            return "yes" if ok else "**no**"

        hold = mark(ours["hold_max"] <= 2.0 * theirs["hold_max"])
        stands = mark(bool(ours.get("stands"))) if ours.get("floating") else "welded"
        rnd = mark(ours["random_stable"] and ours["speed_over_limit"] <= 2.0)
        speed = (
            f"{mark(ours['steps_per_s'] >= theirs['steps_per_s'])} (×{ours['steps_per_s'] / theirs['steps_per_s']:.2f})"
        )
        lines.append(f"| {robot} | {hold} | {stands} | {rnd} | {speed} | {mark(ours.get('loads_copied') == 'yes')} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    from robodesc.validation.corpora import example_robot_data_root

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--robots", default="", help="comma-separated names from: " + ", ".join(ROBOTS))
    parser.add_argument("--menagerie", default=os.environ.get("ROBODESC_MENAGERIE_DIR"))
    parser.add_argument("--out", default=OUT, help="results path without suffix (.json and .md are written)")
    parser.add_argument("--keep", default=None, help="write the compiled folders here (default: a temporary folder)")
    args = parser.parse_args(argv)
    erd = example_robot_data_root()
    if erd is None:
        print("example-robot-data is not installed (the test extra installs it)", file=sys.stderr)
        return 2
    names = [n for n in args.robots.split(",") if n] or list(ROBOTS)
    results: dict[str, dict[str, Any]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        base = args.keep or tmp
        measured: dict[str, dict[str, Any]] = {}  # menagerie scene -> its row (talos twice)
        for name in names:
            rel, menagerie_scene, options = ROBOTS[name]
            source = os.path.join(erd, "robots", rel) if rel else None
            vlimits = velocity_limits(source) if source else {}
            sides: dict[str, Any] = {}
            if source:
                try:
                    out_dir = os.path.join(base, name)
                    scene, warnings = compile_robot(source, out_dir, options, erd)
                    row = {**measure(scene, vlimits), "warnings": warnings}
                    row["loads_copied"] = loads_copied(out_dir, scene, move_original=True)
                    sides["robodesc"] = row
                except Exception as exc:  # a failed robot is a row, not the end of the run
                    sides["robodesc"] = {"error": f"{type(exc).__name__}: {exc}"}
            if args.menagerie:
                path = os.path.join(args.menagerie, menagerie_scene)
                renamed = {m: vlimits[u] for m, u in JOINT_NAMES.get(name, {}).items() if u in vlimits}
                try:
                    if menagerie_scene not in measured:
                        key = MENAGERIE_KEYS.get(menagerie_scene, "home")
                        row = measure(path, {**vlimits, **renamed}, key)
                        row["loads_copied"] = loads_copied(os.path.dirname(path), path, move_original=False)
                        measured[menagerie_scene] = row
                    sides["menagerie"] = measured[menagerie_scene]
                except Exception as exc:
                    sides["menagerie"] = {"error": f"{type(exc).__name__}: {exc}"}
            results[name] = sides
            print(name, json.dumps(sides, default=str)[:400], flush=True)
    write_results(args.out, results, table(results))
    return 0


def write_results(out: str, results: dict[str, Any], text: str) -> None:
    """``out``.json (the numbers) and ``out``.md (the table), and the table on standard output."""
    os.makedirs(os.path.dirname(out), exist_ok=True)
    with open(out + ".json", "w") as handle:
        json.dump(results, handle, indent=1, default=str)
    with open(out + ".md", "w") as handle:
        handle.write(text)
    print(text)


if __name__ == "__main__":
    raise SystemExit(main())
