"""Every menagerie model through every target, read by the engines users run (issue 36), beside
mujoco-usd-converter's USD of the same model.

MuJoCo on the source MJCF is the reference. Per model (every ``scene*.xml`` under ``--menagerie``):

- ``ir``: robodesc's IR of the MJCF against MuJoCo's compile of the source (validation/mujoco_mjcf:
  bodies, masses, centres, inertias, joint types, axes, limits, armature, FK at random
  configurations, actuators with the source's gains). Every consumer below is compared with the IR,
  so a consumer that matches the IR matches MuJoCo on the source.
- ``urdf``: robodesc's URDF in MuJoCo (its validation), in urdfdom (``check_urdf``) and in Pinocchio
  (total mass, joint limits and every body's place relative to the root at five random
  configurations, against MuJoCo on the source);
- ``sdf``: robodesc's SDF in Drake (its validation);
- ``usd``: robodesc's USD in usd-core's UsdPhysics parser and in PhysX (ovphysx; its validation,
  rows ``physx-*``), and in Newton (``tests/consumers/newton_check.py``: Newton's ``add_usd``
  against its ``add_urdf`` of robodesc's URDF given the source's gains);
- ``conv``: mujoco-usd-converter's USD of the same scene (in its own venv, ``--converter``), read by
  the same usd-core parser, PhysX and Newton checks against the same IR.
- with ``--dynamics``: ``validate --dynamics`` (hold; drop for floating robots) in MuJoCo, Drake,
  Newton and PhysX on robodesc's files, and Newton and PhysX on the converter's USD, from the
  same stance and gains.

    PYTHONPATH=src python benchmarks/menagerie_engines.py --menagerie /work/menagerie [--models 'go1|spot']
        [--dynamics] [--out benchmarks/results/menagerie_engines]

Meshes in /work/menagerie are placeholder boxes (benchmarks/menagerie_placeholders.py): mass and
inertia MuJoCo takes from a mesh are the box's on every side, and contacts on mesh colliders are boxes.
"""

from __future__ import annotations

import argparse
import glob
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from typing import Any

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)  # tests.mjcf_in.compare
ENVS = os.environ.get("ROBODESC_CONSUMERS_DIR", os.path.expanduser("~/.cache/robodesc-consumers"))
CONVERTER = os.path.join(ENVS, "mujoco-usd", "bin", "mujoco_usd_converter")
NEWTON = os.path.join(ENVS, "newton", "bin", "python")
NEWTON_CHECK = os.path.join(ROOT, "tests", "consumers", "newton_check.py")
# newton_check.py's rows, grouped into the table's two questions.
NEWTON_STRUCTURE = {"bodies", "base joint", "joints", "dof", "joint types", "mass", "com", "inertia", "fk"}
NEWTON_STRUCTURE |= {"limits lower", "limits upper"}
# The drives only: the reference is a URDF, which carries no armature (Newton's add_urdf reads 0) and a
# placeholder effort and velocity where the source gives none (1000, 100; the USD writes none). Those
# are compared against the IR by the PhysX check instead.
NEWTON_DRIVES = {"drive stiffness", "drive damping", "drive modes"}
STAND_SHARE = 0.7  # of MuJoCo's settled height on robodesc's URDF, for "stands"
FK_TOL = 1e-6  # m, Pinocchio's body places against MuJoCo's (both float64)
MASS_TOL = 1e-6  # relative


def models(menagerie: str, pattern: str | None, every_scene: bool) -> list[str]:
    """Each model folder's ``scene.xml`` (else its first ``scene*.xml``, Shadow's ``scene_right``);
    ``every_scene`` adds the variants (``scene_cube.xml``: a robot beside objects robodesc leaves out)."""
    found = []
    for folder in sorted(glob.glob(os.path.join(menagerie, "*", ""))):
        scenes = sorted(glob.glob(os.path.join(folder, "scene*.xml")))
        main = os.path.join(folder, "scene.xml")
        found += scenes if every_scene else ([main] if main in scenes else scenes[-1:])
    return [f for f in found if pattern is None or re.search(pattern, f)]


def failing(report: Any, prefix: str | None = None, exclude: str | None = None) -> list[str]:
    """The names of a validation report's failing rows (``prefix``: only those rows)."""
    rows = []
    for c in report.checks:
        if prefix is not None and not c.name.startswith(prefix):
            continue
        if exclude is not None and c.name.startswith(exclude):
            continue
        if c.status.value == "fail":
            rows.append(f"{c.name} ({c.element})")
    return rows


def verdict(rows: list[str]) -> str:
    return "match" if not rows else "differs: " + "; ".join(rows[:3])


def source_gains(robot: Any) -> dict[str, tuple[float, float]]:
    from robodesc.emit.common.source_drives import source_gains as gains

    return {n: (kp or 0.0, kv or 0.0) for n, (kp, kv) in gains(robot).items()}


# validate_mjcf's actuator rows hold robodesc's own MJCF to its conventions (ctrlrange = the joint's
# range, one actuator per movable joint); a menagerie source need not follow them (anymal's
# ctrlrange is +-2 pi, Panda's finger is driven through a tendon), so they are not this column's.
ACTUATOR_ROWS = ("actuators", "gains", "actuator-range", "menagerie")


def ir_against_mujoco(robot: Any, path: str) -> str:
    """The IR against MuJoCo's compile of the source: structure, masses, inertias, joints, limits, FK."""
    import mujoco

    from robodesc.validation.mujoco_mjcf import validate_mjcf

    report = validate_mjcf(robot, path, None)
    source = mujoco.MjModel.from_xml_path(path)
    rows = []
    for c in report.checks:
        if c.status.value != "fail" or c.name.startswith(ACTUATOR_ROWS):
            continue
        if c.name == "limits" and _limit_is_ref_shifted(robot, source, c.element):
            continue
        if c.name == "fk" and any(source.qpos0[source.jnt_qposadr[j]] != 0.0 for j in _one_dof(source)):
            continue  # sampled as MuJoCo qpos = IR q, which a ref moves: the round trip column compares FK
        if c.name == "bodies" and _documented_body(source, c.element, robot):
            continue
        if c.name == "mimic" and _chained(source, c.element, robot):
            continue  # a mimic of a mimic made one of the chain's leader (info mjcf-mimic-chain)
        if c.name == "total mass" and _scene_objects(source, robot):
            continue  # the scene's objects weigh in MuJoCo's total, not in the robot's
        rows.append(f"{c.name} ({c.element})")
    return verdict(rows)


def _one_dof(source: Any) -> list[int]:
    import mujoco

    # int(): numpy's integers and pybind's enum do not compare equal inside "in".
    kinds = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))
    return [j for j in range(source.njnt) if int(source.jnt_type[j]) in kinds]


def _scene_objects(source: Any, robot: Any) -> list[str]:
    links = {link.name for link in robot.links}
    return [source.body(b).name for b in range(1, source.nbody) if source.body(b).name not in links]


def round_trip(path: str, written: str) -> str:
    """The source and robodesc's MJCF of it in MuJoCo (tests/mjcf_in/compare.py): total mass, centre
    and inertia, every joint's world anchor and axis at random configurations, mesh geoms' places."""
    import mujoco
    from tests.mjcf_in.compare import _root_shift, compare, unmatched_meshes

    source, model = mujoco.MjModel.from_xml_path(path), mujoco.MjModel.from_xml_path(written)
    problems = compare(source, model)
    meshes = unmatched_meshes(source, model, _root_shift(source, model))
    return "same" if not problems and not meshes else "; ".join(problems[:2]) + (f" {meshes} meshes" if meshes else "")


def _chained(source: Any, element: str, robot: Any) -> bool:
    import mujoco

    name = element.split("'")[1] if "'" in element else element
    joints = robot.joint_map()
    for e in range(source.neq):
        if (
            int(source.eq_type[e]) != int(mujoco.mjtEq.mjEQ_JOINT)
            or source.joint(int(source.eq_obj1id[e])).name != name
        ):
            continue
        leader = source.joint(int(source.eq_obj2id[e])).name
        mimic = joints[name].mimic if name in joints else None
        return (
            mimic is not None
            and mimic.joint != leader
            and joints.get(leader) is not None
            and joints[leader].mimic is not None
        )
    return False


def _documented_body(source: Any, element: str, robot: Any) -> bool:
    """A body the mapping adds or leaves out on purpose (docs/mjcf-input.md): the massless
    ``<joint>_link`` of a body with several joints, and a scene's object (warning mjcf-scene-object)."""
    import mujoco

    name = element.split("'")[1] if "'" in element else element
    if name.endswith("_link") and mujoco.mj_name2id(source, mujoco.mjtObj.mjOBJ_JOINT, name[: -len("_link")]) >= 0:
        return True
    return element.startswith("body ") and name not in {link.name for link in robot.links}


def _limit_is_ref_shifted(robot: Any, source: Any, element: str) -> bool:
    """IR positions are MuJoCo's qpos - ref (docs/mjcf-input.md): a joint with a ref has its range
    moved by it, which validate_mjcf (written for robodesc's own MJCF, whose refs are 0) counts."""
    import mujoco

    name = element.split("'")[1] if "'" in element else element
    j = mujoco.mj_name2id(source, mujoco.mjtObj.mjOBJ_JOINT, name)
    joint = robot.joint_map().get(name)
    if j < 0 or joint is None or joint.limit is None:
        return False
    ref = source.qpos0[source.jnt_qposadr[j]]
    lo, hi = source.jnt_range[j]
    return bool(ref != 0.0 and abs(joint.limit.lower + ref - lo) < 1e-9 and abs(joint.limit.upper + ref - hi) < 1e-9)


def pinocchio_check(urdf: str, source: Any, robot: Any) -> str:
    """robodesc's URDF in Pinocchio against MuJoCo's compile of the source: total mass, limits, and
    each body's place relative to the root body at five random configurations."""
    import mujoco
    import pinocchio as pin

    floating = not robot.fixed_base
    try:
        model = pin.buildModelFromUrdf(urdf, pin.JointModelFreeFlyer()) if floating else pin.buildModelFromUrdf(urdf)
    except (ValueError, RuntimeError) as exc:
        return f"refused: {str(exc).splitlines()[0][:120]}"
    data = model.createData()
    problems = []
    mass = sum(model.inertias[i].mass for i in range(model.njoints))
    # The robot's bodies only: a scene's table and objects are left out of the IR (mjcf-scene-object).
    links = {link.name for link in robot.links}
    want = float(sum(source.body_mass[b] for b in range(1, source.nbody) if source.body(b).name in links))
    if abs(mass - want) > MASS_TOL * max(want, 1.0):
        problems.append(f"mass {mass:.6g} vs {want:.6g}")
    # Limits and the random configurations, by joint name (1-DOF joints; IR positions are qpos - ref).
    joints = _one_dof(source)
    pin_ids = {model.names[i]: i for i in range(model.njoints)}
    for j in joints:
        name = mujoco.mj_id2name(source, mujoco.mjtObj.mjOBJ_JOINT, j)
        if name not in pin_ids or not source.jnt_limited[j]:
            continue
        q = model.joints[pin_ids[name]].idx_q
        lo, hi = source.jnt_range[j] - source.qpos0[source.jnt_qposadr[j]]
        if abs(model.lowerPositionLimit[q] - lo) > 1e-6 or abs(model.upperPositionLimit[q] - hi) > 1e-6:
            problems.append(f"limit {name}")
    data_mj = mujoco.MjData(source)
    rng = np.random.default_rng(0)
    bodies = [mujoco.mj_id2name(source, mujoco.mjtObj.mjOBJ_BODY, b) for b in range(1, source.nbody)]
    frames = {n: model.getFrameId(n, pin.FrameType.BODY) for n in bodies if model.existFrame(n, pin.FrameType.BODY)}
    root = next((b for b in range(1, source.nbody) if source.body_parentid[b] == 0), 1)
    root_name = bodies[root - 1]
    worst, where = 0.0, ""
    for _ in range(5):
        data_mj.qpos[:] = source.qpos0
        q = pin.neutral(model)
        for j in joints:
            name = mujoco.mj_id2name(source, mujoco.mjtObj.mjOBJ_JOINT, j)
            lo, hi = source.jnt_range[j] if source.jnt_limited[j] else (-np.pi, np.pi)
            value = rng.uniform(lo, hi)
            adr = source.jnt_qposadr[j]
            data_mj.qpos[adr] = value
            if name in pin_ids:
                joint = model.joints[pin_ids[name]]
                angle = value - source.qpos0[adr]
                if joint.nq == 2:  # a continuous joint is (cos, sin) in Pinocchio
                    q[joint.idx_q], q[joint.idx_q + 1] = np.cos(angle), np.sin(angle)
                else:
                    q[joint.idx_q] = angle
        mujoco.mj_kinematics(source, data_mj)
        pin.framesForwardKinematics(model, data, q)
        if root_name not in frames:
            return "root body not a frame"
        r_mj, p_mj = data_mj.xmat[root].reshape(3, 3), data_mj.xpos[root]
        pose_root = data.oMf[frames[root_name]]
        for n, f in frames.items():
            b = bodies.index(n) + 1
            want_rel = r_mj.T @ (data_mj.xpos[b] - p_mj)
            got_rel = pose_root.rotation.T @ (data.oMf[f].translation - pose_root.translation)
            err = float(np.abs(want_rel - got_rel).max())
            if err > worst:
                worst, where = err, n
    if worst > FK_TOL:
        problems.append(f"fk {worst:.3g} m at {where}")
    missing = [n for n in bodies if n not in frames and n in links]
    if missing:
        problems.append(f"{len(missing)} bodies not frames ({missing[0]})")
    return verdict(problems)


def urdfdom(urdf: str) -> str:
    proc = subprocess.run(["check_urdf", urdf], capture_output=True, text=True, timeout=120)
    if proc.returncode != 0:
        return f"refused: {(proc.stderr or proc.stdout).strip()[:120]}"
    # urdfdom goes on past an element it cannot parse (a <capsule> in URDF 1.0): the link loses it.
    dropped = (proc.stdout + proc.stderr).count("Could not parse")
    return "loads" if not dropped else f"loads, drops {dropped} elements"


def convert(path: str, out: str) -> tuple[str | None, float, list[str]]:
    """mujoco-usd-converter on the source scene: its top USD, its time, and its warning lines."""
    start = time.perf_counter()
    proc = subprocess.run([CONVERTER, path, out], capture_output=True, text=True, timeout=600)
    seconds = time.perf_counter() - start
    warnings = sorted(
        {m.group(1).strip() for m in re.finditer(r"\[Warning\] \[[^\]]*\] (.*)", proc.stdout + proc.stderr)}
    )
    top = sorted(glob.glob(os.path.join(out, "*.usda")) + glob.glob(os.path.join(out, "*.usdc")))
    if proc.returncode != 0 or not top:
        return None, seconds, [f"failed: {(proc.stderr or proc.stdout).strip().splitlines()[-1:]}"]
    return top[0], seconds, warnings


def usd_checks(robot: Any, usd: str, classes: dict[str, Any] | None = None) -> tuple[str, str, str]:
    """usd-core's parser and PhysX against the IR: (parser, PhysX masses, PhysX joints and drives).
    ``classes`` receives every failing row name with how many elements it names."""
    from robodesc.validation.physx_usd import validate_usd_physx
    from robodesc.validation.usd_physics import validate_usd_physics

    parsed = validate_usd_physics(robot, usd)
    physx = validate_usd_physx(robot, usd)
    if classes is not None:
        for report in (parsed, physx):
            for c in report.checks:
                if c.status.value == "fail":
                    classes[c.name] = classes.get(c.name, 0) + 1
    masses = [
        r
        for r in failing(physx)
        if r.split(" ")[0] in ("physx-mass", "physx-com", "physx-inertia", "physx-total-mass", "physx-massless")
    ]
    rest = [r for r in failing(physx) if r not in masses]
    return verdict(failing(parsed)), verdict(masses), verdict(rest)


def newton_cases(cases: list[dict[str, Any]], work: str) -> dict[str, Any]:
    if not cases or not os.path.exists(NEWTON):
        return {}
    path = os.path.join(work, "newton_cases.json")
    with open(path, "w") as handle:
        json.dump(cases, handle)
    out = os.path.join(work, "newton_out.json")
    subprocess.run([NEWTON, NEWTON_CHECK, "--cases", path, "--out", out], capture_output=True, text=True, timeout=3600)
    if not os.path.exists(out):
        return {}
    with open(out) as handle:
        return dict(json.load(handle))


def newton_verdict(result: dict[str, Any] | None) -> tuple[str, str]:
    if not result:
        return "not run", "not run"
    checks = result.get("checks", [])
    if not checks:
        return result.get("status", "fail")[:120], "-"
    if not next((c["ok"] for c in checks if c["name"] == "loads"), True):
        return "refused", "-"
    structure = [
        f"{c['name']} ({c['where'] or c['detail']})"[:90]
        for c in checks
        if c["name"] in NEWTON_STRUCTURE and not c["ok"]
    ]
    drives = [
        f"{c['name']} ({c['where'] or c['detail']})"[:90] for c in checks if c["name"] in NEWTON_DRIVES and not c["ok"]
    ]
    return verdict(structure), verdict(drives)


def behaviour(report: Any) -> dict[str, str]:
    """Per engine/file: 'holds' or 'drifts X', and for a dropped robot 'stands' or 'falls'."""
    from robodesc.validation.dynamics.scenarios import Thresholds

    th = Thresholds()
    out: dict[str, str] = {}
    for r in report.runs:
        key = f"{r.engine}/{r.file}"
        if not r.ok:
            out[f"{key} {r.scenario}"] = f"error: {r.error[:60]}"
        elif r.scenario == "hold-fixed":
            drift = r.drift or 0.0
            out[f"{key} hold"] = "holds" if drift <= th.hold_drift else f"drifts {drift:.3g}"
        elif r.scenario == "drop":
            up = r.tilt is not None and r.tilt <= th.upright_tilt
            out[f"{key} drop"] = (
                f"{'stands' if up else 'falls'} (h {r.height:.3f} m, tilt {np.degrees(r.tilt or 0):.0f}°)"
            )
    return out


def run_model(
    path: str, work: str, dynamics: bool, only_dynamics: bool = False
) -> tuple[dict[str, Any], list[dict[str, Any]]]:
    import mujoco

    import robodesc
    from robodesc.frontends.load import load_path

    name = os.path.basename(os.path.dirname(path)) + (
        "" if os.path.basename(path) == "scene.xml" else "/" + os.path.basename(path)
    )
    row: dict[str, Any] = {"model": name}
    start = time.perf_counter()
    try:
        loaded = load_path(path)
    except Exception as exc:  # a refused model is a result of this table
        row["read"] = f"refused: {str(exc).splitlines()[0][:160]}"
        return row, []
    robot = loaded.robot
    row["read_s"] = round(time.perf_counter() - start, 3)
    row["links"], row["joints"] = len(robot.links), len(robot.actuated_joints())
    row["floating"] = not robot.fixed_base
    row["warnings"] = sorted({f.code for f in loaded.findings if f.severity.value == "warning"})
    folder = os.path.join(work, re.sub(r"[^A-Za-z0-9_]+", "_", name))
    os.makedirs(folder, exist_ok=True)
    if only_dynamics:  # the behaviour columns alone (a second run beside the structural one)
        conv, _, _ = convert(path, os.path.join(folder, "converter"))
        row.update(dynamics_rows(path, robot, conv, folder))
        return row, []
    source = mujoco.MjModel.from_xml_path(path)
    row["ir"] = ir_against_mujoco(robot, path)
    files: dict[str, str] = {}
    for target, file in (("mjcf", "robot.xml"), ("urdf", "robot.urdf"), ("sdf", "robot.sdf"), ("usd", "robot.usda")):
        out = os.path.join(folder, file)
        start = time.perf_counter()
        try:
            result = robodesc.compile_to(path, target, out)
            report = result.validation
            files[target] = out
            if target == "usd" and report is not None:
                row["usd_parser"] = verdict(failing(report, exclude="physx"))
                physx = failing(report, prefix="physx")
                masses = [
                    r
                    for r in physx
                    if r.split(" ")[0]
                    in ("physx-mass", "physx-com", "physx-inertia", "physx-total-mass", "physx-massless")
                ]
                row["usd_physx_masses"] = verdict(masses)
                row["usd_physx_joints"] = verdict([r for r in physx if r not in masses])
            elif report is not None:
                row[target] = verdict(failing(report))
        except Exception as exc:
            row[target if target != "usd" else "usd_parser"] = f"failed: {str(exc).splitlines()[0][:160]}"
        row[f"{target}_s"] = round(time.perf_counter() - start, 2)
    if "mjcf" in files:
        try:
            row["round_trip"] = round_trip(path, files["mjcf"])
        except ValueError as exc:  # MuJoCo refuses one of them
            row["round_trip"] = f"does not load: {str(exc).splitlines()[0][:100]}"
    if "urdf" in files:
        row["urdfdom"] = urdfdom(files["urdf"])
        row["pinocchio"] = pinocchio_check(files["urdf"], source, robot)
    conv, seconds, conv_warnings = convert(path, os.path.join(folder, "converter"))
    row["conv_s"] = round(seconds, 2)
    row["conv_warnings"] = conv_warnings
    if conv is not None:
        row["conv_parser"], row["conv_physx_masses"], row["conv_physx_joints"] = usd_checks(robot, conv)
    else:
        row["conv_parser"] = conv_warnings[0] if conv_warnings else "failed"
    cases = []
    gains = {n: list(g) for n, g in source_gains(robot).items()}
    for kind, usd in (("usd", files.get("usd")), ("conv", conv)):
        if usd and "urdf" in files:
            cases.append(
                {
                    "name": f"{name}|{kind}",
                    "urdf": files["urdf"],
                    "usd": usd,
                    "floating": row["floating"],
                    "gains": gains,
                    # The numbers only: the 200-step run compares against a URDF without armature.
                    "steps": 0,
                }
            )
    if dynamics:
        row.update(dynamics_rows(path, robot, conv, folder))
    return row, cases


def dynamics_rows(path: str, robot: Any, conv: str | None, folder: str) -> dict[str, Any]:
    import robodesc
    from robodesc.api import compile_to
    from robodesc.check_dynamics import run_for
    from robodesc.validation.dynamics import DynamicsOptions

    out: dict[str, Any] = {}
    start = time.perf_counter()
    result = robodesc.check(path, "usd", dynamics={"engines": ("mujoco", "drake", "newton", "physx")})
    if result.dynamics is not None:
        out["behaviour"] = behaviour(result.dynamics)
        out["stance"] = result.dynamics.info.get("pose_note", "")
    if conv is not None:
        opts = DynamicsOptions(engines=("newton", "physx"))
        report = run_for(path, robot, "usd", conv, os.path.join(folder, "conv_dyn"), opts, {}, compile_to)
        out["conv_behaviour"] = behaviour(report)
    out["dynamics_s"] = round(time.perf_counter() - start, 1)
    return out


def behaviour_section(rows: list[dict[str, Any]]) -> list[str]:
    lines: list[str] = []
    dyn = [r for r in rows if "behaviour" in r]
    if dyn:
        lines += [
            "",
            "## Behaviour (`validate --dynamics`)",
            "",
            "| model | robodesc | mujoco-usd-converter | s |",
            "|---|---|---|---|",
        ]
        for r in dyn:
            ours = "; ".join(f"{k}: {v}" for k, v in sorted(r.get("behaviour", {}).items()))
            theirs = "; ".join(f"{k}: {v}" for k, v in sorted(r.get("conv_behaviour", {}).items()))
            lines.append(f"| {r['model']} | {ours} | {theirs} | {r.get('dynamics_s', '-')} |")
        lines += ["", "| engine and file | hold | stand |", "|---|---|---|"]
        for key, (holds, stands, runs) in sorted(tally_behaviour(dyn).items()):
            lines.append(f"| {key} | {holds}/{runs['hold']} | {stands}/{runs['drop']} |")
    return lines


def class_section(rows: list[dict[str, Any]]) -> list[str]:
    """Every failing check class of each USD against the IR (usd-core's parser and PhysX), with the
    models it affects and how many elements it names there."""
    lines: list[str] = []
    # robodesc's own USD is checked at compile time against the robot its passes lowered (a massless
    # link's 1 g placeholder, docs/usd.md): its columns above; the raw IR would count that rule.
    for kind, title in (("conv", "mujoco-usd-converter's USD"),):
        by: dict[str, list[str]] = defaultdict(list)
        for r in rows:
            for name, count in r.get(f"{kind}_classes", {}).items():
                by[name].append(f"{r['model'].split('/')[0]} ({count})")
        if not any(f"{kind}_classes" in r for r in rows):
            continue
        lines += ["", f"## {title}: failing checks against the IR (usd-core's parser and PhysX)", ""]
        if not by:
            lines.append("None.")
            continue
        lines += ["| check | models (failing elements) |", "|---|---|"]
        lines += [f"| `{n}` | {', '.join(sorted(m))} |" for n, m in sorted(by.items(), key=lambda kv: -len(kv[1]))]
    return lines


def _height(text: str) -> float | None:
    found = re.search(r"h (-?[0-9.]+) m", text)
    return float(found.group(1)) if found else None


def tally_behaviour(rows: list[dict[str, Any]]) -> dict[str, tuple[int, int, dict[str, int]]]:
    """Per engine and file: how many robots hold, and how many dropped robots stand: upright
    (tilt at most 30 degrees) and at least STAND_SHARE of the height MuJoCo on robodesc's URDF
    settles at, so a robot that folds to the floor upright is not counted as standing."""
    out: dict[str, tuple[int, int, dict[str, int]]] = {}
    for r in rows:
        reference = _height(r.get("behaviour", {}).get("mujoco/urdf drop", ""))
        for side, prefix in (("behaviour", ""), ("conv_behaviour", "converter ")):
            for key, text in r.get(side, {}).items():
                engine, scenario = key.rsplit(" ", 1)
                if scenario not in ("hold", "drop"):
                    continue
                holds, stands, runs = out.get(prefix + engine, (0, 0, {"hold": 0, "drop": 0}))
                runs[scenario] += 1
                if scenario == "hold" and text == "holds":
                    holds += 1
                height = _height(text)
                tall = reference is not None and height is not None and height >= STAND_SHARE * reference
                if scenario == "drop" and text.startswith("stands") and tall:
                    stands += 1
                out[prefix + engine] = (holds, stands, runs)
    return out


def markdown(rows: list[dict[str, Any]]) -> str:
    if rows and all("ir" not in r for r in rows):  # --only-dynamics
        head = [
            "# menagerie models: behaviour in each engine",
            "",
            "`benchmarks/menagerie_engines.py --only-dynamics` (docs/mjcf-input.md). Meshes are placeholder boxes: "
            "mesh contacts are boxes.",
        ]
        return "\n".join(head + behaviour_section(rows)) + "\n"

    def short(cell: Any) -> str:
        text = str(cell if cell is not None else "-")
        return text if len(text) <= 80 else text[:77] + "..."

    lines = [
        "# menagerie models through every target, in the engines users run",
        "",
        "`PYTHONPATH=src python benchmarks/menagerie_engines.py --menagerie /work/menagerie` (docs/mjcf-input.md). "
        "MuJoCo on the source MJCF is the reference: `IR` is robodesc's IR against MuJoCo's compile of the source; "
        "every other column is a consumer against that IR (URDF: MuJoCo, urdfdom, Pinocchio against MuJoCo directly; "
        "SDF: Drake; USD: usd-core's parser, PhysX, Newton against its add_urdf of robodesc's URDF with the source's "
        "gains). `conv`: mujoco-usd-converter 0.8's USD of the same scene, same checks. **Meshes are placeholder "
        "boxes** (benchmarks/menagerie_placeholders.py): mass MuJoCo takes from a mesh is the box's on every side; "
        "mesh contacts are boxes.",
        "",
        "| model | IR = MuJoCo | MJCF: MuJoCo | MJCF round trip | URDF: MuJoCo | urdfdom | Pinocchio | SDF: Drake | USD: parser | "
        "PhysX masses | PhysX joints | "
        "Newton structure | Newton drives | conv: parser | conv PhysX masses | conv PhysX joints | conv Newton structure | "
        "conv Newton drives |",
        "|" + "---|" * 18,
    ]
    for r in rows:
        cells = [
            r.get(k)
            for k in (
                "ir",
                "mjcf",
                "round_trip",
                "urdf",
                "urdfdom",
                "pinocchio",
                "sdf",
                "usd_parser",
                "usd_physx_masses",
                "usd_physx_joints",
            )
        ]
        cells += [r.get("newton_structure"), r.get("newton_drives"), r.get("conv_parser"), r.get("conv_physx_masses")]
        cells += [r.get("conv_physx_joints"), r.get("conv_newton_structure"), r.get("conv_newton_drives")]
        lines.append(f"| {r['model']} | " + " | ".join(short(c) for c in cells) + " |")
    lines += ["", "## Counts", ""]
    n = len(rows)
    for label, key in (
        ("IR = MuJoCo", "ir"),
        ("MJCF in MuJoCo", "mjcf"),
        ("URDF in MuJoCo", "urdf"),
        ("URDF in Pinocchio", "pinocchio"),
        ("SDF in Drake", "sdf"),
        ("USD in usd-core", "usd_parser"),
        ("USD masses in PhysX", "usd_physx_masses"),
        ("USD joints and drives in PhysX", "usd_physx_joints"),
        ("USD structure in Newton", "newton_structure"),
        ("USD drives in Newton", "newton_drives"),
        ("converter USD in usd-core", "conv_parser"),
        ("converter USD masses in PhysX", "conv_physx_masses"),
        ("converter USD joints and drives in PhysX", "conv_physx_joints"),
        ("converter USD structure in Newton", "conv_newton_structure"),
        ("converter USD drives in Newton", "conv_newton_drives"),
    ):
        match = sum(1 for r in rows if r.get(key) == "match")
        lines.append(f"- {label}: {match}/{n} match")
    loads = sum(1 for r in rows if r.get("urdfdom") == "loads")
    lines.append(f"- URDF in urdfdom: {loads}/{n} load with every element")
    same = sum(1 for r in rows if r.get("round_trip") == "same")
    lines.append(f"- MJCF -> IR -> MJCF the same model in MuJoCo: {same}/{n}")
    lines += behaviour_section(rows)
    lines += [
        "",
        "## Time per model (s)",
        "",
        "| model | read | urdf | sdf | usd | converter |",
        "|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['model']} | {r.get('read_s', '-')} | {r.get('mjcf_s', '-')} | {r.get('urdf_s', '-')} | {r.get('sdf_s', '-')} | {r.get('usd_s', '-')} | {r.get('conv_s', '-')} |"
        )
    by_code: dict[str, list[str]] = defaultdict(list)
    conv_by: dict[str, list[str]] = defaultdict(list)
    for r in rows:
        for code in r.get("warnings", []):
            by_code[code].append(r["model"])
        for text in r.get("conv_warnings", []):
            conv_by[text].append(r["model"])
    lines += ["", "## robodesc's warning classes", "", "| warning class | models |", "|---|---|"]
    lines += [f"| `{c}` | {', '.join(sorted(set(m)))} |" for c, m in sorted(by_code.items())]
    lines += class_section(rows)
    lines += ["", "## mujoco-usd-converter's warnings", "", "| warning | models |", "|---|---|"]
    lines += [f"| {c} | {', '.join(sorted(set(m)))} |" for c, m in sorted(conv_by.items())]
    return "\n".join(lines) + "\n"


def recheck(menagerie: str, work: str, out: str) -> None:
    """The MuJoCo- and Pinocchio-side columns again, from a finished run's files (fast: no engine)."""
    import mujoco

    from robodesc.frontends.load import load_path

    with open(out + ".json") as handle:
        saved = json.load(handle)
    for row in saved["rows"]:
        name = row["model"]
        path = os.path.join(menagerie, name) if name.endswith(".xml") else os.path.join(menagerie, name, "scene.xml")
        if not os.path.exists(path):
            path = sorted(glob.glob(os.path.join(menagerie, name, "scene*.xml")))[-1]
        robot = load_path(path).robot
        row["ir"] = ir_against_mujoco(robot, path)
        folder = os.path.join(work, re.sub(r"[^A-Za-z0-9_]+", "_", name))
        urdf = os.path.join(folder, "robot.urdf")
        if os.path.exists(urdf):
            row["pinocchio"] = pinocchio_check(urdf, mujoco.MjModel.from_xml_path(path), robot)
        for kind, found in (("conv", glob.glob(os.path.join(folder, "converter", "*.usda"))),):
            usd = next((f for f in found if os.path.exists(f)), None)
            if usd is not None:
                classes: dict[str, Any] = {}
                usd_checks(robot, usd, classes)
                row[f"{kind}_classes"] = classes
    with open(out + ".json", "w") as handle:
        json.dump(saved, handle, indent=1, default=str)
    with open(out + ".md", "w") as handle:
        handle.write(markdown(saved["rows"]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--menagerie", required=True)
    parser.add_argument("--models")
    parser.add_argument("--dynamics", action="store_true")
    parser.add_argument("--only-dynamics", action="store_true", help="the behaviour columns alone")
    parser.add_argument(
        "--recheck",
        action="store_true",
        help="recompute the IR and Pinocchio columns from --out's JSON and --work's files",
    )
    parser.add_argument("--every-scene", action="store_true", help="also scene variants (scene_cube.xml, ...)")
    parser.add_argument("--work", default=None, help="keep every output here (default: a temporary folder)")
    parser.add_argument("--out", default=os.path.join(HERE, "results", "menagerie_engines"))
    args = parser.parse_args()
    work = args.work or tempfile.mkdtemp(prefix="menagerie-engines-")
    if args.recheck:
        recheck(args.menagerie, work, args.out)
        return
    rows, cases = [], []
    for path in models(args.menagerie, args.models, args.every_scene):
        try:
            row, more = run_model(path, work, args.dynamics or args.only_dynamics, args.only_dynamics)
        except Exception as exc:  # one model's crash is its row, the run goes on
            row, more = {"model": path, "read": f"benchmark error: {type(exc).__name__}: {exc}"[:300]}, []
        rows.append(row)
        cases += more
        print(json.dumps(row), flush=True)
    results = newton_cases(cases, work)
    for row in rows:
        row["newton_structure"], row["newton_drives"] = newton_verdict(results.get(f"{row['model']}|usd"))
        row["conv_newton_structure"], row["conv_newton_drives"] = newton_verdict(results.get(f"{row['model']}|conv"))
    with open(args.out + ".json", "w") as handle:
        json.dump({"rows": rows, "newton": results}, handle, indent=1, default=str)
    with open(args.out + ".md", "w") as handle:
        handle.write(markdown(rows))


if __name__ == "__main__":
    main()
