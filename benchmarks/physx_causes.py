"""Why a robot that stands in Gazebo saturates in Isaac: Quad-SDK's ranked causes, one at a time, in
PhysX (issue 38; the causes: ../shared/docs/quad-sdk-prep.md), with MuJoCo, Drake and Newton beside.

    python benchmarks/physx_causes.py [--robot spirit|go2|a1|go1|anymal_c ...] [--cause NAME ...]
        [--physx-from JSON] [--json F] [--md F]

a1, go1 and anymal_c come from example-robot-data (the test extra), in PhysX only and without the
armature row (there is no motor table for them).

Each robot is compiled from its xacro with ``--isaac-sim`` and default flags (it floats: docs/isaac.md,
"The base"), then once per variant with one cause changed. Every variant drives the joints with the
baseline's gains (the Isaac folder's derived ones, pinned as tables: armature would otherwise change
the derived damping too) towards the baseline's stance, and spawns the robot where the baseline's
Isaac Lab module does (its lowest collider 5 mm above the ground).

PhysX: ovphysx 0.7 on CPU, in its own interpreter (``benchmarks/physx_stand.py``): the folder's USD as
written, over a floor plane of friction 1 (Gazebo's default surface), 2 s at 1 kHz (Quad-SDK's rate),
TGS (PhysX's default). Reported: the base's final height and tilt, the largest final joint error
|q - target|, and the peak drive torque over the run (|kp e - kd qd| clamped to the effort limit)
with its share of that limit: the saturation users report.

MuJoCo (MJCF), Drake (SDF) and Newton (USD, SolverMuJoCo) run the same drop through ``robodesc.check(...,
dynamics=...)`` (``validate --dynamics``) for the variants their files carry (the baseline, armature,
damping defaults, ``--preset gazebo_parity``): same stance, same gains, 2 s, from 5 mm. The other causes
are PhysX attributes (iterations, offsets, combine mode, the PhysX mesh approximations) none of them
reads; a dash says so. Results: benchmarks/results/physx_causes.{json,md}.

Two causes beyond flat ground, for Spirit and Go2: ``quad-sdk gains`` (Quad-SDK's own joint gains
replace the derived ones in every engine: QUADSDK_GAINS) and ``terrain`` (Quad-SDK's worlds through
``--world``: MuJoCo on the MJCF's heightfield, PhysX on the ``-t usd --world`` stage's terrain with the
Isaac folder's robot; heights over the ground under the root; Drake and Newton have no column).
``--physx-only`` runs no other engine (rows kept by ``--physx-from`` keep theirs).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import runpy
import subprocess
import sys
import tempfile
import time
from typing import Any

from results_io import publish

import robodesc
from robodesc.check_dynamics import default_stance
from robodesc.passes.options import parse_armature
from robodesc.validation.corpora import example_robot_data_robots
from robodesc.validation.dynamics import DynamicsOptions
from robodesc.validation.dynamics.run import folder_files
from robodesc.validation.physx_python import physx_python

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.join(HERE, "..", "..", "shared", "corpus", "quadsdk")
ROBOTS = {
    "spirit": os.path.join(SHARED, "spirit_description/models/spirit/urdf/spirit.urdf.xacro"),
    "go2": os.path.join(SHARED, "go2_description/models/go2/urdf/go2.urdf.xacro"),
}
# The corpus's other legged robots (example-robot-data), PhysX only, without the armature row
# (no motor table for them): --robot a1 ...
CORPUS = {
    "a1": "a1_description/urdf/a1",
    "go1": "go1_description/urdf/go1",
    "anymal_c": "anymal_c_simple_description/urdf/anymal",
}


def source_of(robot: str) -> tuple[str, dict[str, Any]]:
    """The robot's file and the input options it needs (package paths)."""
    if robot in ROBOTS:
        return ROBOTS[robot], {}
    found = next(r for r in example_robot_data_robots() if r.name == CORPUS[robot])
    return found.path, {"package_paths": dict(found.packages)}


# Quad-SDK's Spirit armature (J_rotor 1.231e-4 kg·m², gear 6 abad/hip, 12 knee). Go2 has no entry in
# Quad-SDK; both name their joints alike (abduction 8-11, hip 0/2/4/6, knee 1/3/5/7), so Spirit's
# rotor stands in for Go2's: the question is whether armature moves a standing robot at all.
ARMATURE = ("8|9|10|11=4.4316e-3", "0|2|4|6=4.4316e-3", "1|3|5|7=1.77264e-2")
# cause -> [(variant, compile options)]; the first row of all is the baseline.
CAUSES: dict[str, list[tuple[str, dict[str, Any]]]] = {
    "baseline": [("--isaac-sim, default flags", {})],
    "collider approximation": [
        (f"--collision-approximation {m}", {"collision_approximation": m})
        for m in ("none", "convexDecomposition", "sdf")  # convexHull is the baseline's
    ],
    "armature": [("Quad-SDK armature on", {"armature": ARMATURE})],  # rules as --armature takes them
    "solver iterations": [
        ("64 / 16", {"solver_position_iterations": 64, "solver_velocity_iterations": 16}),
        ("255 / 16", {"solver_position_iterations": 255, "solver_velocity_iterations": 16}),
    ],
    "contact and rest offsets": [("contact 1 mm, rest 0", {"contact_offset": 0.001, "rest_offset": 0.0})],
    "damping defaults": [("explicit_damping (URDF's unsaid damping = 0)", {"explicit_damping": True})],
    "friction combine": [(f"--friction-combine {m}", {"friction_combine": m}) for m in ("min", "multiply", "max")],
    "gazebo_parity": [("--preset gazebo_parity", {"preset": "gazebo_parity"})],
}
# Quad-SDK's own joint gains (N·m/rad, N·m·s/rad; the same for every joint), replacing the
# baseline's derived ones in every engine: Spirit's stand gains (robomechanics/quad-sdk,
# quad_utils/config/spirit.yaml: stand_kp 35, stand_kd 1); Go2 at its hardware kp 60
# (../shared/docs/quad-sdk-prep.md: the gains PhysX saturates at) with go2.yaml's stand_kd 2, and
# go2.yaml's stand gains (stand_kp 35, stand_kd 2).
QUADSDK_GAINS: dict[str, list[tuple[str, dict[str, Any]]]] = {
    "spirit": [("stand kp 35, kd 1 (spirit.yaml)", {"stiffness": 35.0, "damping": 1.0})],
    "go2": [
        ("kp 60, kd 2 (hardware kp)", {"stiffness": 60.0, "damping": 2.0}),
        ("stand kp 35, kd 2 (go2.yaml)", {"stiffness": 35.0, "damping": 2.0}),
    ],
}
CAUSES["quad-sdk gains"] = []  # per robot: QUADSDK_GAINS
# Quad-SDK's worlds (--world): flat is the reference the others are measured against, from the
# spawn robodesc's world placement gives the stance (the MJCF's home keyframe: 1 cm above the
# highest foot's ground). MuJoCo reads the MJCF's heightfield, PhysX the USD world stage's triangle
# mesh (-t usd --world: physics:approximation none, friction combined by min). Drake hulls meshes and
# Newton's reading of the USD terrain is not measured yet (docs/worlds.md): no column.
WORLDS_DIR = os.path.join(HERE, "..", "..", "shared", "corpus", "quadsdk", "worlds")
TERRAINS = ("flat", "step_20cm", "rough_25cm")
CAUSES["terrain"] = [(f"--world {w}", {"world": os.path.join(WORLDS_DIR, w, f"{w}.world")}) for w in TERRAINS]
# The causes whose change reaches a file MuJoCo, Drake or Newton reads.
OTHER_ENGINES = {"baseline", "armature", "damping defaults", "gazebo_parity", "quad-sdk gains"}
ENGINES = ("mujoco", "drake", "newton")
DURATION, TIMESTEP, CLEARANCE, FLOOR_MU = 2.0, 0.001, 0.005, 1.0


def baseline(source: str, folder: str, given: dict[str, Any]) -> dict[str, Any]:
    """The baseline folder's gains (SI, by the folder's joint names) and spawn; the same stance and
    gains in the source's joint names, for the other engines."""
    out = os.path.join(folder, "baseline")
    robodesc.compile_for_isaac_sim(source, out, validate=False, **given)
    module = runpy.run_path(next(os.path.join(out, f) for f in os.listdir(out) if f.endswith("_isaaclab.py")))["ROBOT"]
    stiffness: dict[str, float] = {}
    damping: dict[str, float] = {}
    for group in module["actuators"].values():
        for expr in group["joint_names_expr"]:
            stiffness[expr], damping[expr] = group["stiffness"], group["damping"]
    src = default_stance(robodesc.load(source, **given), DynamicsOptions())
    assert isinstance(src.stiffness, dict) and isinstance(src.damping, dict)
    return {
        "stiffness": stiffness,
        "damping": damping,
        "spawn": list(module["init_state"]["pos"]),
        "source": {"pose": src.pose, "stiffness": _both(src.stiffness), "damping": _both(src.damping)},
    }


def _both(table: dict[str, float]) -> dict[str, float]:
    """A gain table by source joint name that also matches the USD's names: USD names cannot start with
    a digit, so Spirit's and Go2's joint ``0`` is written ``a0``, and gain rules match written names
    (Newton reads the gains from the USD)."""
    return {(f"a?{k}" if k[:1].isdigit() else k): v for k, v in table.items()}


def _api(options: dict[str, Any]) -> dict[str, Any]:
    """The API's spelling of the options (armature rules parsed, as the CLI parses --armature)."""
    return {k: tuple(parse_armature(r) for r in v) if k == "armature" else v for k, v in options.items()}


def _gains(options: dict[str, Any], table: dict[str, Any]) -> dict[str, Any]:
    """The baseline's gains ``table`` ({"stiffness", "damping"}) unless the cause gives its own."""
    return {k: options.pop(k) if k in options else table[k] for k in ("stiffness", "damping")}


def physx_row(
    source: str, options: dict[str, Any], base: dict[str, Any], folder: str, terrain: dict[str, Any] | None = None
) -> dict[str, Any]:
    """``terrain``: {"stage": the world stage, "spawn": [x, y, z]} for the terrain rows."""
    options = _api(options)
    options.pop("world", None)  # the Isaac folder takes no world: the terrain comes as a stage
    gains = _gains(options, base)
    out = os.path.join(folder, "isaac")
    robodesc.compile_for_isaac_sim(source, out, validate=False, **gains, **options)
    usd = folder_files(out)["usd"]  # the robot's stage, not the folder's physics layer (<robot>_physics.usda)
    request = {"usd": usd, "spawn": base["spawn"], "duration": DURATION, "timestep": TIMESTEP, "floor_mu": FLOOR_MU}
    if terrain is not None:
        request.update(spawn=terrain["spawn"], terrain=terrain["stage"])
    python = physx_python()
    if python is None:
        return {"error": "no interpreter with ovphysx (robodesc.validation.physx_python)"}
    started = time.perf_counter()
    run = subprocess.run(
        [python, os.path.join(HERE, "physx_stand.py")],
        input=json.dumps(request),
        capture_output=True,
        text=True,
        check=False,
    )
    lines = [line for line in run.stdout.splitlines() if line.startswith("{")]
    if not lines:
        return {"error": (run.stderr.strip().splitlines() or ["no answer"])[-1][:300]}
    row: dict[str, Any] = json.loads(lines[-1])
    row["seconds"] = round(time.perf_counter() - started, 1)
    return row


def other_rows(source: str, options: dict[str, Any], base: dict[str, Any]) -> dict[str, Any]:
    """The drop in MuJoCo, Drake and Newton through validate --dynamics, from the same stance and gains."""
    options = _api(options)
    src = base["source"]
    dynamics = DynamicsOptions(
        engines=ENGINES, pose=src["pose"], duration=DURATION, timestep=TIMESTEP, drop_clearance=CLEARANCE
    )
    result = robodesc.check(source, "mjcf", dynamics=dynamics, **_gains(options, src), **options)
    rows: dict[str, Any] = {}
    for r in result.dynamics.runs if result.dynamics is not None else []:
        if r.scenario == "drop" and r.file != "source":
            worst = r.worst_saturation()
            rows[r.engine] = {
                "height": r.height,
                "tilt": r.tilt,
                "joint_error": r.drift,
                "worst_joint": r.worst_joint,
                "peak_torque": max(r.peak_effort.values(), default=None),
                "peak_share": worst[1] if worst else None,
                "peak_joint": worst[0] if worst else "",
                "error": r.error or None,
            }
    return rows


def _ground(model: Any, data: Any, x: float, y: float) -> float:
    """The terrain's height under (x, y) in a MuJoCo scene (a ray down onto geom group 0 and 1)."""
    import mujoco
    import numpy as np

    geomid = np.array([-1], dtype=np.int32)
    groups = np.array([1, 1, 0, 0, 0, 0], dtype=np.uint8)
    dist = mujoco.mj_ray(model, data, np.array([x, y, 10.0]), np.array([0.0, 0.0, -1.0]), groups, 1, -1, geomid)
    return 10.0 - dist if dist >= 0 else math.nan


def terrain_rows(source: str, options: dict[str, Any], base: dict[str, Any], folder: str) -> dict[str, Any]:
    """The drop on a world in MuJoCo (the MJCF's scene.xml, its heightfield) and PhysX (the Isaac
    folder's robot over the USD world stage's terrain), from the spawn the world placement gives
    the MJCF's home keyframe, with the baseline's stance and gains. Heights are over the ground
    under the root's final x, y (MuJoCo's ray on the heightfield: exact on step_20cm, within
    12.8 mm of the mesh on rough_25cm, docs/worlds.md)."""
    import mujoco
    import numpy as np

    options = _api(options)
    src = base["source"]
    mjcf = os.path.join(folder, "mjcf", "robot.xml")
    robodesc.compile_to_mjcf(
        source, mjcf, validate=False, init_joint_pos=src["pose"], **_gains(dict(options), src), **options
    )
    stage_out = os.path.join(folder, "usd", "robot.usda")
    robodesc.compile_to(source, "usd", stage_out, validate=False, **options)
    model = mujoco.MjModel.from_xml_path(os.path.join(folder, "mjcf", "scene.xml"))
    model.opt.timestep = TIMESTEP
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home"))
    spawn = [float(v) for v in data.qpos[:3]]
    # Position actuators: ctrl is the target; the force is bounded by forcerange (the effort limit).
    acts = [
        (i, int(model.jnt_qposadr[model.actuator_trnid[i, 0]]), float(model.actuator_forcerange[i, 1]))
        for i in range(model.nu)
    ]
    names = [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, i) or str(i) for i in range(model.nu)]
    peak, share, at = 0.0, 0.0, ""
    for _ in range(round(DURATION / TIMESTEP)):
        mujoco.mj_step(model, data)
        for i, _adr, limit in acts:
            tau = abs(float(data.actuator_force[i]))
            if tau > peak:
                peak = tau
            if limit > 0 and tau / limit > share:
                share, at = tau / limit, names[i]
    finite = bool(np.all(np.isfinite(data.qpos)))
    x, y, z = (float(v) for v in data.qpos[:3])
    errors = {names[i]: abs(float(data.qpos[adr] - data.ctrl[i])) for i, adr, _ in acts}
    worst = max(errors, key=lambda k: errors[k])
    up = float(data.xmat[1].reshape(3, 3)[2, 2])
    rows: dict[str, Any] = {
        "mujoco": {
            "height": z - _ground(model, data, x, y) if finite else None,
            "tilt": math.acos(max(-1.0, min(1.0, up))),
            "joint_error": errors[worst],
            "worst_joint": worst,
            "peak_torque": peak,
            "peak_share": share,
            "peak_joint": at,
            "spawn": spawn,
            "error": None if finite else "state not finite",
        }
    }
    stage = next(
        os.path.join(folder, "usd", f) for f in os.listdir(os.path.join(folder, "usd")) if f.endswith("_world.usda")
    )
    physx = physx_row(source, options, base, os.path.join(folder, "physx"), {"stage": stage, "spawn": spawn})
    if "height" in physx:
        px, py = physx["xy"]
        physx["z"] = physx["height"]
        physx["height"] = physx["height"] - _ground(model, data, px, py)
    physx["spawn"] = spawn
    rows["physx"] = physx
    return rows


def run(robot: str, causes: list[str], done: list[dict[str, Any]], physx_only: bool = False) -> list[dict[str, Any]]:
    """``done``: rows of an earlier run whose PhysX results are kept (``--physx-from``)."""
    source, given = source_of(robot)
    rows = []
    with tempfile.TemporaryDirectory(prefix="physx-causes-") as folder:
        base = baseline(source, folder, given)
        for cause in causes:
            if robot in CORPUS and cause in ("armature", "quad-sdk gains", "terrain"):
                continue
            variants = QUADSDK_GAINS.get(robot, []) if cause == "quad-sdk gains" else CAUSES[cause]
            for variant, cause_options in variants:
                options = {**given, **cause_options}
                print(f"{robot}: {cause}: {variant}", file=sys.stderr, flush=True)
                shown = {k: os.path.basename(v) if k == "world" else v for k, v in cause_options.items()}
                row = {"robot": robot, "cause": cause, "variant": variant, "options": shown}
                kept = next((r for r in done if (r["robot"], r["variant"]) == (robot, variant)), None)
                where = os.path.join(folder, re.sub(r"\W+", "_", variant))
                physx_ok = kept is not None and not kept["physx"].get("error")
                if cause == "terrain":
                    row.update(kept if kept and physx_ok else terrain_rows(source, options, base, where))
                    rows.append(row)
                    continue
                row["physx"] = kept["physx"] if kept and physx_ok else physx_row(source, options, base, where)
                if cause in OTHER_ENGINES and robot not in CORPUS:
                    others = {e: kept[e] for e in ENGINES if kept and e in kept}
                    row.update(others if others or physx_only else other_rows(source, options, base))
                rows.append(row)
    return rows


def _f(value: float | None, fmt: str, scale: float = 1.0) -> str:
    return "–" if value is None else format(value * scale, fmt)


def markdown(rows: list[dict[str, Any]]) -> str:
    lines = [
        "# Gazebo-versus-Isaac causes, one at a time, in PhysX (with MuJoCo, Drake, Newton beside)",
        "",
        "`python benchmarks/physx_causes.py --robot ROBOT --json ...` per robot (spirit, go2; a1, anymal_c, go1"
        " from example-robot-data in PhysX only), merged here (method: the script's docstring). Flat ground, floor μ 1,"
        " 2 s at 1 kHz from the Isaac Lab module's spawn (lowest collider 5 mm up), the baseline's stance and"
        " derived gains in every row. Height: the base's final z; tilt: from upright; joint error: the largest"
        " final |q − target|; peak: the largest drive torque over the run and its share of the effort limit."
        " Δ: against the baseline in the same engine. MuJoCo / Drake / Newton: final height (Δ) for the causes"
        " their files carry; – where the cause is a PhysX attribute they do not read.",
        "",
    ]
    for robot in dict.fromkeys(r["robot"] for r in rows):
        mine = [r for r in rows if r["robot"] == robot]
        ref = next((r for r in mine if r["cause"] == "baseline"), None)
        lines += [
            f"## {robot}",
            "",
            "| cause | variant | PhysX height m | Δ mm | tilt ° | joint error rad | peak N·m (share, joint) | MuJoCo m (Δ mm) | Drake m (Δ mm) | Newton m (Δ mm) |",
            "|---|---|---|---|---|---|---|---|---|---|",
        ]
        for r in mine:
            if r["cause"] == "terrain":  # heights over the terrain: the table below
                continue
            p = r["physx"]
            if "error" in p:
                lines.append(f"| {r['cause']} | {r['variant']} | failed: {p['error']} | | | | | | | |")
                continue
            dz = None if ref is None or "height" not in ref["physx"] else p["height"] - ref["physx"]["height"]
            cells = []
            for engine in ENGINES:
                e = r.get(engine)
                if not e or e.get("height") is None:
                    cells.append("–" if not e else f"failed: {e.get('error')}")
                    continue
                b = (ref or {}).get(engine) or {}
                d = None if b.get("height") is None else e["height"] - b["height"]
                cells.append(f"{e['height']:.4f} ({_f(d, '+.1f', 1e3)})")
            lines.append(
                f"| {r['cause']} | {r['variant']} | {p['height']:.4f} | {_f(dz, '+.1f', 1e3)} | "
                f"{math.degrees(p['tilt']):.2f} | {p['joint_error']:.3f} | {p['peak_torque']:.1f} "
                f"({p['peak_share']:.0%}, {p['peak_joint']}) | " + " | ".join(cells) + " |"
            )
        lines.append("")
        lines += every_engine(robot, mine)
    return "\n".join(lines)


def every_engine(robot: str, mine: list[dict[str, Any]]) -> list[str]:
    """The causes every engine reads, engine by engine: height, tilt, joint error and peak torque
    (share of the effort limit). Δ: against the baseline in the same engine; for the terrain rows,
    against the flat world's row (their heights are over the ground under the root)."""
    shown = [r for r in mine if r["cause"] in OTHER_ENGINES or r["cause"] == "terrain"]
    if not shown:
        return []
    lines = [
        f"### {robot}: every engine",
        "",
        "| cause | variant | engine | height m | Δ mm | tilt ° | joint error rad | peak N·m (share, joint) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    base = next((r for r in mine if r["cause"] == "baseline"), {})
    flat = next((r for r in mine if r["cause"] == "terrain" and r["options"].get("world") == "flat.world"), {})
    for r in shown:
        ref = flat if r["cause"] == "terrain" else base
        for engine in ("physx", *ENGINES):
            e = r.get(engine)
            if not e:
                continue
            if e.get("height") is None:
                lines.append(f"| {r['cause']} | {r['variant']} | {engine} | failed: {e.get('error')} | | | | |")
                continue
            b = (ref.get(engine) or {}).get("height")
            peak = "–"
            if e.get("peak_torque") is not None:
                share = e.get("peak_share")
                peak = f"{e['peak_torque']:.1f} ({'–' if share is None else format(share, '.0%')}, {e.get('peak_joint', '')})"
            lines.append(
                f"| {r['cause']} | {r['variant']} | {engine} | {e['height']:.4f} | "
                f"{_f(None if b is None else e['height'] - b, '+.1f', 1e3)} | {math.degrees(e['tilt']):.2f} | "
                f"{e['joint_error']:.3f} | {peak} |"
            )
    lines.append("")
    return lines


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--robot", action="append", choices=sorted({*ROBOTS, *CORPUS}))
    parser.add_argument("--cause", action="append", choices=[c for c in CAUSES if c != "baseline"])
    parser.add_argument(
        "--physx-from",
        metavar="JSON",
        help="keep the rows of an earlier run's JSON whose PhysX run did not fail (with their other engines)",
    )
    parser.add_argument("--physx-only", action="store_true", help="no MuJoCo, Drake or Newton runs (kept rows stay)")
    parser.add_argument("--json")
    parser.add_argument("--md")
    args = parser.parse_args()
    causes = ["baseline", *(args.cause or [c for c in CAUSES if c != "baseline"])]
    done = []
    if args.physx_from:
        with open(args.physx_from, encoding="utf-8") as handle:
            done = json.load(handle)
    rows = [row for robot in (args.robot or ["spirit"]) for row in run(robot, causes, done, args.physx_only)]
    publish(markdown(rows), rows, args.json, args.md)
    return 0


if __name__ == "__main__":
    sys.exit(main())
