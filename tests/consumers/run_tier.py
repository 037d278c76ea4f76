"""The consumer tier: what robodesc writes, loaded in the engines users run.

    python tests/consumers/run_tier.py --envs ~/.cache/robodesc-consumers [--robots panda,a1] [--resume]

Run it through ``tests/consumers/run.sh``, which builds the engine environments first. For every
robot of the corpus (``robodesc.validation.corpora``) it compiles, with this checkout's robodesc,
``-t usd`` and ``--isaac-sim``, then:

- ``newton``: Newton 1.8 loads the USD (``add_usd``) and the source URDF (``add_urdf``) and
  newton_check.py compares them (structure, mass properties, FK, limits, drives, armature,
  damping, friction, velocity and effort limits, a 200-step SolverMuJoCo run);
- ``newton_isaac``: the same for the Isaac folder's USD against the folder's own URDF;
- ``isaac_importer``: Isaac Sim 6.2's URDF importer imports the folder's URDF with the folder's
  ``importer_settings.json``, and Newton compares the imported asset (``physx`` variant) with
  that URDF;
- ``physx``: ``compile -t usd`` and ``--isaac-sim`` with validation on, and what their PhysX check
  (validation/physx_usd.py: ovphysx's masses, inertias, limits, drives, armature, velocity and
  friction against the IR) says: ``physx``/``physx_isaac`` verdicts, ``*_loads``, ``*_masses``,
  ``*_drives``; ``physx_dynamics`` once ``validate --dynamics --engines physx`` exists;
- ``newton_mjcf`` (only with ``--kinds newton_mjcf``): ``-t mjcf`` with ``--stiffness 100 --damping
  1`` and the base flag, Newton 1.8's ``add_mjcf`` loads robot.xml and newton_check.py compares it
  with ``add_urdf`` of the source (masses, inertias, joints, limits, actuator gains and force
  ranges, armature, damping, friction, mimic, FK, a 200-step SolverMuJoCo run). Where the MJCF
  preset repaired an inertia, the reference is robodesc's URDF with the same repair.

Each engine has its own environment under ``--envs`` (``newton/``, ``isaacsim/``). Results:
``benchmarks/results/consumers.json`` (robot -> {"newton", "newton_isaac", "isaac_importer",
"newton_mjcf"}: "pass" or "fail: why") and ``consumers.md``; per-robot details in ``--work``.
A run with ``--kinds`` updates only those columns and keeps the rest of the JSON.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import re
import subprocess
import sys
import time
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from robodesc.validation.corpora import CorpusRobot

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HERE = os.path.dirname(os.path.abspath(__file__))
# The robots the issue found the defects on run first.
FIRST = ("ur5_robot", "panda", "solo12", "a1", "go1", "talos_reduced", "baxter", "allegro_right_hand", "spirit")
# Legged robots, humanoids and mobile bases float; the rest are fixed to the world.
FLOATING = re.compile(
    r"(a1|go1|go2|b1|aliengo|laikago|anymal|solo|bolt|spirit|hyq|mini_cheetah|talos|romeo|valkyrie|icub|ergocub|"
    r"atlas|g1|h1|upkie|cassie|tiago|pepper|nao|simple_humanoid|human|stretch|centauro|ur5_gripper_on_base)",
    re.IGNORECASE,
)
KINDS = ("newton", "newton_isaac", "isaac_importer")
# newton_mjcf: robodesc's robot.xml through Newton's add_mjcf (--kinds newton_mjcf; docs/mjcf.md).
# physx: the -t usd output and the Isaac folder's USD in PhysX (ovphysx), robodesc's own check
# (validation/physx_usd.py) run by the compile a user runs; physx_isaac rides along with it.
ALL_KINDS = (*KINDS, "newton_mjcf", "physx")
# The physx check's rows, grouped into the tier's two questions.
PHYSX_MASSES = ("physx-mass", "physx-massless", "physx-com", "physx-inertia", "physx-total-mass")
PHYSX_DRIVES = (
    "physx-dofs",
    "physx-limits",
    "physx-drive",
    "physx-max-force",
    "physx-armature",
    "physx-max-velocity",
    "physx-friction",
)
# The MJCF is compiled with the gains the reference URDF is given (newton_check.py's defaults),
# so actuator kp/kv are compared with what was asked, in SI per radian.
MJCF_GAINS = ["--stiffness", "100", "--damping", "1"]
# NVIDIA's SimReady physics rules that run on CPU (usd_validation_nvidia, from isacsim's env).
SIMREADY_RULES = ("MassChecker", "RigidBodyChecker", "PhysicsJointChecker", "ArticulationChecker")


def _run(cmd: list[str], timeout: float, log: str) -> subprocess.CompletedProcess[str]:
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, check=False)
    except subprocess.TimeoutExpired:
        proc = subprocess.CompletedProcess(cmd, 124, "", f"timed out after {timeout:g} s")
    with open(log, "a", encoding="utf-8") as f:
        f.write("$ " + " ".join(cmd) + f"\n[rc {proc.returncode}]\n{proc.stdout[-4000:]}\n{proc.stderr[-4000:]}\n")
    return proc


def _last_error(proc: subprocess.CompletedProcess[str]) -> str:
    lines = [x for x in (proc.stderr or proc.stdout).splitlines() if x.strip() and not x.startswith("#")]
    return (lines[0] if lines else f"exit {proc.returncode}")[:300]


def _newton_check(
    cases: list[dict[str, Any]], cases_path: str, result_path: str, envs: str, log: str
) -> tuple[subprocess.CompletedProcess[str], dict[str, Any]]:
    """Run newton_check.py in Newton's environment on ``cases``: (the process, its results by case)."""
    with open(cases_path, "w", encoding="utf-8") as f:
        json.dump(cases, f, indent=1)
    newton = _run(
        [
            os.path.join(envs, "newton", "bin", "python"),
            os.path.join(HERE, "newton_check.py"),
            "--cases",
            cases_path,
            "--out",
            result_path,
        ],
        1800,
        log,
    )
    return newton, _read_json(result_path) or {}


def _read_json(path: str) -> dict[str, Any] | None:
    if not os.path.isfile(path):
        return None
    with open(path, encoding="utf-8") as f:
        data: dict[str, Any] = json.load(f)
    return data


def _compile_flags(robot: CorpusRobot) -> list[str]:
    flags: list[str] = []
    for name, path in robot.packages.items():
        flags += ["--package", f"{name}={path}"]
    for name, value in robot.xacro_args.items():
        flags += ["--arg", f"{name}={value}"]
    return flags


def _workdir(robot: CorpusRobot, work: str, log_name: str) -> tuple[str, str, str]:
    """(slug, the robot's folder under ``work``, a fresh log file in it named ``log_name``)."""
    slug = re.sub(r"[^A-Za-z0-9_.-]+", "_", str(robot.name))
    wdir = os.path.join(work, slug)
    os.makedirs(wdir, exist_ok=True)
    log = os.path.join(wdir, log_name)
    open(log, "w").close()
    return slug, wdir, log


def run_robot(robot: CorpusRobot, envs: str, work: str) -> dict[str, object]:
    name = str(robot.name)
    slug, wdir, log = _workdir(robot, work, "log.txt")
    source = str(robot.path)
    floating = bool(FLOATING.search(name))
    py = [sys.executable, "-m", "robodesc"]
    flags = _compile_flags(robot) + (["--no-fix-base"] if floating else [])
    out: dict[str, object] = {"floating": floating}
    usd = os.path.join(wdir, f"{slug}.usda")
    extra: list[str] = []
    proc = _run([*py, "compile", source, "-t", "usd", "-o", usd, "-q", "--no-validate", *flags], 300, log)
    if proc.returncode != 0 and "--invalid-inertia repair" in (proc.stderr + proc.stdout):
        # A physically invalid source: convert it the way the hint says, and compare with the
        # URDF robodesc writes with the same repair (the source itself is what was refused).
        extra = ["--invalid-inertia", "repair"]
        out["repaired"] = True
        proc = _run([*py, "compile", source, "-t", "usd", "-o", usd, "-q", "--no-validate", *flags, *extra], 300, log)
    if proc.returncode != 0:
        reason = f"not converted: {_last_error(proc)}"
        return {**out, **{k: reason for k in KINDS}}
    own_urdf = os.path.join(wdir, f"{slug}.robodesc.urdf")
    _run([*py, "compile", source, "-t", "urdf", "-o", own_urdf, "-q", "--no-validate", *flags, *extra], 300, log)
    reference = source
    if extra:
        reference = own_urdf
    elif not source.endswith(".urdf"):
        reference = os.path.join(wdir, f"{slug}.source.urdf")
        exp = _run([*py, "expand", source, *_compile_flags(robot)], 300, log)
        with open(reference, "w", encoding="utf-8") as f:
            f.write(exp.stdout)
    isaac = os.path.join(wdir, "isaac")
    proc = _run([*py, "compile", source, "--isaac-sim", "-o", isaac, "-q", "--no-validate", *flags, *extra], 300, log)
    cases: list[dict[str, object]] = []
    # Newton resolves package:// from the folder that holds each package.
    package_dirs = sorted({os.path.dirname(os.path.abspath(p)) for p in robot.packages.values()})
    common = {"floating": floating, "package_dir": package_dirs, "fallback_urdf": own_urdf}
    cases.append({"name": "newton", "urdf": reference, "usd": usd, **common})
    if proc.returncode != 0:
        out["newton_isaac"] = out["isaac_importer"] = f"not converted: {_last_error(proc)}"
    else:
        names = [n for n in os.listdir(isaac) if n.endswith(".usda")]
        isaac_usd = os.path.join(isaac, names[0])
        isaac_urdf = isaac_usd[: -len(".usda")] + ".urdf"
        cases.append({"name": "newton_isaac", "urdf": isaac_urdf, "usd": isaac_usd, **common, "fallback_urdf": None})
        imp_json = os.path.join(wdir, "isaac_import.json")
        imp = _run(
            [
                os.path.join(envs, "isaacsim", "bin", "python"),
                os.path.join(HERE, "isaac_import.py"),
                "--urdf",
                isaac_urdf,
                "--settings",
                os.path.join(isaac, "importer_settings.json"),
                "--out-dir",
                os.path.join(wdir, "imported"),
                "--out",
                imp_json,
            ],
            900,
            log,
        )
        imported = _read_json(imp_json)
        if imported is None or imported.get("status") != "pass":
            why = imported["status"] if imported else f"fail: importer crashed ({_last_error(imp)})"
            out["isaac_importer"] = why
        else:
            cases.append(
                {
                    "name": "isaac_importer",
                    "urdf": isaac_urdf,
                    "usd": imported["usd"],
                    "variant": "physx",
                    **common,
                    "fallback_urdf": None,
                }
            )
    newton, results = _newton_check(
        cases, os.path.join(wdir, "cases.json"), os.path.join(wdir, "newton.json"), envs, log
    )
    for case in cases:
        kind = str(case["name"])
        res = results.get(kind)
        out[kind] = res["status"] if res else f"fail: Newton crashed ({_last_error(newton)})"
        if res and res.get("reference", "source URDF") != "source URDF":
            out[f"{kind}_reference"] = res["reference"]
    out["simready"] = simready(usd, envs, log)
    return out


def run_robot_mjcf(robot: CorpusRobot, envs: str, work: str) -> dict[str, object]:
    """The ``newton_mjcf`` column: robot.xml through Newton's add_mjcf against the reference URDF."""
    name = str(robot.name)
    slug, wdir, log = _workdir(robot, work, "log_mjcf.txt")
    source = str(robot.path)
    floating = bool(FLOATING.search(name))
    py = [sys.executable, "-m", "robodesc"]
    flags = _compile_flags(robot) + (["--no-fix-base"] if floating else ["--fix-base"])
    xml = os.path.join(wdir, "mjcf", "robot.xml")
    proc = _run(
        # --no-merge-fixed: compared body by body with add_urdf (-t mjcf fuses fixed links by default).
        [
            *py,
            "compile",
            source,
            "-t",
            "mjcf",
            "-o",
            xml,
            "--no-validate",
            "--json",
            "--no-merge-fixed",
            *flags,
            *MJCF_GAINS,
        ],
        300,
        log,
    )
    try:
        summary = json.loads(proc.stdout)
    except json.JSONDecodeError:
        summary = {}
    if proc.returncode != 0:
        errors = [e.get("message", "") for e in summary.get("errors", []) if isinstance(e, dict)]
        return {"newton_mjcf": f"not converted: {errors[0][:300] if errors else _last_error(proc)}"}
    codes = {str(f.get("code", "")) for f in summary.get("findings", []) if isinstance(f, dict)}
    # The mjcf preset's repairs (inertia-repaired, mass-repaired, ...) change the robot: the
    # reference is then robodesc's URDF through the same preset (the same passes, URDF written).
    repaired = any(c.endswith("-repaired") or c == "inertia-from-geometry" for c in codes)
    own_urdf = os.path.join(wdir, f"{slug}.robodesc-mjcf-preset.urdf")
    preset = ["--preset", "mjcf"]
    _run([*py, "compile", source, "-t", "urdf", "-o", own_urdf, "-q", "--no-validate", *flags, *preset], 300, log)
    if repaired:
        reference = own_urdf
    elif source.endswith(".urdf"):
        reference = source
    else:
        reference = os.path.join(wdir, f"{slug}.source.urdf")
        exp = _run([*py, "expand", source, *_compile_flags(robot)], 300, log)
        with open(reference, "w", encoding="utf-8") as f:
            f.write(exp.stdout)
    package_dirs = sorted({os.path.dirname(os.path.abspath(p)) for p in robot.packages.values()})
    case = {
        "name": "newton_mjcf",
        "urdf": reference,
        "mjcf": xml,
        "floating": floating,
        "package_dir": package_dirs,
        "fallback_urdf": own_urdf,
    }
    newton, results = _newton_check(
        [case], os.path.join(wdir, "cases_mjcf.json"), os.path.join(wdir, "newton_mjcf.json"), envs, log
    )
    res = results.get("newton_mjcf")
    out: dict[str, object] = {"newton_mjcf": res["status"] if res else f"fail: Newton crashed ({_last_error(newton)})"}
    if res and res.get("checks"):
        out["newton_mjcf_loads"] = any(c["name"] == "loads" and c["ok"] for c in res["checks"])
        # Numbers alone (the run, and SolverMuJoCo's build of Newton's model for it, compare two
        # importers' dynamics, not what was written).
        bad = [c for c in res["checks"] if not c["ok"] and not c["name"].startswith(("trajectory", "mujoco build"))]
        out["newton_mjcf_numbers"] = (
            "pass"
            if not bad
            else "fail: " + "; ".join(c["name"] + (f" ({c['where']})" if c["where"] else "") for c in bad[:3])
        )
    if res and res.get("reference", "source URDF") != "source URDF":
        out["newton_mjcf_reference"] = res["reference"]
    elif repaired:
        out["newton_mjcf_reference"] = "robodesc's URDF through the mjcf preset (it repaired the source's inertia)"
    return out


def run_robot_physx(robot: CorpusRobot, work: str, dynamics: bool = True) -> dict[str, object]:
    """The ``physx`` columns: ``compile -t usd`` and ``--isaac-sim`` as a user runs them (validation
    on, with the tier's base flag), and what their PhysX check says. ``physx`` is the compile's
    verdict on the PhysX rows; ``physx_loads``, ``physx_masses`` and ``physx_drives`` split it (a
    known mismatch still listed in physx_usd.PENDING_FIXES counts as a difference here)."""
    name = str(robot.name)
    slug, wdir, log = _workdir(robot, work, "log_physx.txt")
    floating = bool(FLOATING.search(name))
    flags = _compile_flags(robot) + (["--no-fix-base"] if floating else [])
    py = [sys.executable, "-m", "robodesc"]
    out: dict[str, object] = {}
    for kind, target, dest in (
        ("physx", ["-t", "usd"], os.path.join(wdir, "physx", f"{slug}.usda")),
        ("physx_isaac", ["--isaac-sim"], os.path.join(wdir, "physx_isaac")),
    ):
        start = time.perf_counter()
        proc = _run([*py, "compile", str(robot.path), *target, "-o", dest, "--json", *flags], 900, log)
        out[f"{kind}_seconds"] = round(time.perf_counter() - start, 1)
        out.update({f"{kind}{k}": v for k, v in physx_verdict(proc).items()})
    hook = physx_dynamics(robot, flags, log) if dynamics else None
    if hook is not None:
        out["physx_dynamics"] = hook
    return out


def physx_verdict(proc: subprocess.CompletedProcess[str]) -> dict[str, object]:
    """{"": verdict, "_loads": bool, "_masses": .., "_drives": ..} from a compile's --json."""
    try:
        summary = json.loads(proc.stdout)
    except json.JSONDecodeError:
        return {"": f"not converted: {_last_error(proc)}"}
    checks = [c for c in (summary.get("validation") or {}).get("checks", []) if c["name"].startswith("physx")]
    if not checks:
        errors = [e.get("message", "") for e in summary.get("errors", []) if isinstance(e, dict)]
        return {"": f"not converted: {errors[0][:300] if errors else _last_error(proc)}"}
    if any(c["name"] == "physx" and c["status"] == "skip" for c in checks):
        return {"": "skip: no PhysX interpreter"}
    loads = any(c["name"] == "physx-load" and c["status"] == "pass" for c in checks)

    def differs(c: dict[str, Any]) -> bool:
        return c["status"] == "fail" or (c["status"] == "warn" and "known mismatch" in c["message"])

    def group(names: tuple[str, ...]) -> str:
        bad = [c for c in checks if c["name"] in names and differs(c)]
        source = [c for c in checks if c["name"] in names and c["status"] == "warn" and "of the source" in c["message"]]
        if not bad:
            return "equal" + (f" (source defects: {len(source)} rows)" if source else "")
        kinds = sorted({c["name"] for c in bad})
        shown = "; ".join(f"{c['name']} {c['element']}" for c in bad[:3])
        return f"differ: {len(bad)} ({', '.join(kinds)}): {shown}"

    failed = [c for c in checks if c["status"] == "fail"]
    verdict = "pass" if not failed else "fail: " + "; ".join(f"{c['name']} {c['element']}" for c in failed[:3])
    return {"": verdict, "_loads": loads, "_masses": group(PHYSX_MASSES), "_drives": group(PHYSX_DRIVES)}


def physx_dynamics(robot: CorpusRobot, flags: list[str], log: str) -> str | None:
    """Hold and drop in PhysX through ``validate --dynamics --engines physx``, once robodesc's
    dynamics runner has a PhysX engine (None until then: the column is left out)."""
    from robodesc.validation.dynamics import run as dynamics

    engines = set(getattr(dynamics, "ENGINES", ())) | set(dynamics.READERS.values())
    if "physx" not in engines:
        return None
    cmd = [sys.executable, "-m", "robodesc", "validate", str(robot.path), "-t", "usd", "--dynamics"]
    proc = _run([*cmd, "--engines", "physx", "--json", *_compile_flags(robot)], 1800, log)
    try:
        report = json.loads(proc.stdout).get("dynamics") or {}
    except json.JSONDecodeError:
        return f"fail: {_last_error(proc)}"
    runs = [c for c in report.get("checks", []) if c.get("status") in ("fail", "warn")]
    return "pass" if not runs else "; ".join(f"{c['status']} {c['name']} {c['element']}" for c in runs[:3])


def simready(usd: str, envs: str, log: str) -> str:
    """``nvidia_usd_validate`` with the physics rules: "pass" or "fail: <rule> at <prims>"."""
    csv_path = usd + ".simready.csv"
    tool = os.path.join(envs, "isaacsim", "bin", "nvidia_usd_validate")
    rules = [x for rule in SIMREADY_RULES for x in ("-r", rule)]
    proc = _run([tool, *rules, "--csv-output", csv_path, usd], 600, log)
    if not os.path.isfile(csv_path):
        return f"fail: validator did not run ({_last_error(proc)})"
    with open(csv_path, encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    bad = [r for r in rows if r.get("Severity") in ("Failure", "Error")]
    if not bad:
        return "pass"
    where = ", ".join(sorted({r["Location"].removeprefix("Prim ") for r in bad})[:3])
    return f"fail: {len(bad)} ({', '.join(sorted({r['Rule'] for r in bad}))}) at {where}"


def add_simready(results: dict[str, dict[str, object]], envs: str, work: str) -> None:
    """The SimReady column for robots already run (their files are in ``work``)."""
    for name, result in results.items():
        wdir = os.path.join(work, re.sub(r"[^A-Za-z0-9_.-]+", "_", name))
        usd = os.path.join(wdir, os.path.basename(wdir) + ".usda")
        if os.path.isfile(usd) and "simready" not in result:
            result["simready"] = simready(usd, envs, os.path.join(wdir, "log.txt"))


def markdown(results: dict[str, dict[str, object]]) -> str:
    lines = [
        "# Consumer tier: robodesc's USD and MJCF in Newton 1.8 and Isaac Sim 6.2's URDF importer",
        "",
        "Written by `tests/consumers/run_tier.py` (see docs/usd.md, 'Consumer tier'). `newton`: the",
        "`-t usd` output against the source URDF, both loaded by Newton; `newton_isaac`: the `--isaac-sim`",
        "folder's USD against the folder's URDF; `isaac_importer`: Isaac Sim 6.2's importer on the",
        "folder's URDF, its `physx` variant loaded by Newton and compared with that URDF. `newton_mjcf`",
        "(`--kinds newton_mjcf`): `-t mjcf` loaded by Newton's `add_mjcf` and compared with `add_urdf` of the",
        "source (`newton_mjcf_numbers`: the same without the 200-step trajectory; docs/mjcf.md, Consumers).",
        "`physx` / `physx_isaac` (`--kinds physx`): the `-t usd` output and the Isaac folder's USD loaded in PhysX",
        "(ovphysx) by robodesc's own check, compiled as a user compiles (validation on); `_masses` and `_drives` in",
        "the JSON split the verdict (docs/validation.md, PhysX).",
        "",
    ]
    counts = {k: sum(1 for r in results.values() if r.get(k) == "pass") for k in ALL_KINDS}
    lines.append(f"{len(results)} robots; pass: " + ", ".join(f"{k} {counts[k]}" for k in KINDS) + ".")
    ran = [r for r in results.values() if "newton_mjcf" in r]
    if ran:
        loads = sum(1 for r in ran if r.get("newton_mjcf_loads"))
        numbers = sum(1 for r in ran if r.get("newton_mjcf_numbers") == "pass")
        lines.append(
            f"`newton_mjcf` (robodesc's MJCF through Newton's `add_mjcf`): {len(ran)} robots run, {loads} load, "
            f"{numbers} with every number equal, {counts['newton_mjcf']} of them also within tolerance over the "
            "200-step run."
        )
    for kind, what in (("physx", "`-t usd`"), ("physx_isaac", "the `--isaac-sim` folder's USD")):
        ran = [r for r in results.values() if kind in r and not str(r[kind]).startswith("skip")]
        if ran:
            loads = sum(1 for r in ran if r.get(f"{kind}_loads"))
            masses = sum(1 for r in ran if str(r.get(f"{kind}_masses", "")).startswith("equal"))
            drives = sum(1 for r in ran if str(r.get(f"{kind}_drives", "")).startswith("equal"))
            passed = sum(1 for r in ran if r.get(kind) == "pass")
            lines.append(
                f"`{kind}` ({what} in PhysX, robodesc's own check): {len(ran)} robots, {loads} load, {masses} with "
                f"every mass equal, {drives} with every joint number equal; the compile passes for {passed}."
            )
    simready_pass = sum(1 for r in results.values() if r.get("simready") == "pass")
    lines.append(f"SimReady physics rules ({', '.join(SIMREADY_RULES)}) on the `-t usd` output: {simready_pass} pass.")
    lines += [
        "",
        "| robot | base | newton | newton_isaac | isaac_importer | simready | newton_mjcf | physx | physx_isaac |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for name, r in results.items():
        cells = [
            str(_physx_cell(r, k) if k.startswith("physx") else r.get(k, "not run"))
            .replace("|", "\\|")
            .replace("\n", " ")
            for k in (*KINDS, "simready", "newton_mjcf", "physx", "physx_isaac")
        ]
        base = "floating" if r.get("floating") else "fixed"
        if r.get("repaired"):
            base += ", inertia repaired"
        lines.append(f"| {name} | {base} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def _physx_cell(row: dict[str, object], kind: str) -> str:
    """The compile's verdict, then masses and drives in short ("differ: 3 (physx-massless)")."""
    if kind not in row:
        return "not run"
    parts = [str(row[kind])]
    for what in ("masses", "drives"):
        value = row.get(f"{kind}_{what}")
        if value is not None:
            parts.append(f"{what} {str(value).split('):')[0] + ')' if '):' in str(value) else value}")
    return "; ".join(parts)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--envs", required=True, help="the folder run.sh built the engine environments in")
    ap.add_argument("--work", default=None, help="scratch folder (default: ENVS/work)")
    ap.add_argument("--robots", default=None, help="comma list of robot names (substring match); default all")
    ap.add_argument("--resume", action="store_true", help="keep results already in the JSON")
    ap.add_argument("--reverse", action="store_true", help="last robot first (a second worker)")
    ap.add_argument("--shard", default=None, help="K/N: only every N-th robot from the K-th (parallel workers)")
    ap.add_argument("--simready-only", action="store_true", help="only add the SimReady column to --out")
    ap.add_argument("--merge", action="append", default=[], help="also take robots from this results JSON")
    ap.add_argument(
        "--kinds",
        default=None,
        help=f"comma list of columns to (re)run, of {', '.join(ALL_KINDS)}; the others are kept from --out "
        "(default: the USD columns, robots already in --out skipped with --resume)",
    )
    ap.add_argument(
        "--no-physx-dynamics",
        action="store_true",
        help="physx: only the structural columns (hold and drop in PhysX are benchmarks/dynamics_corpus.py's, "
        "which runs them beside the other engines; the hook doubles the tier's time)",
    )
    ap.add_argument("--out", default=os.path.join(ROOT, "benchmarks", "results", "consumers.json"))
    args = ap.parse_args(argv)
    sys.path.insert(0, os.path.join(ROOT, "src"))
    from robodesc.validation.corpora import all_robots

    work = args.work or os.path.join(args.envs, "work")
    robots = all_robots(os.path.join(os.path.dirname(ROOT), "shared", "corpus"))
    robots.sort(key=lambda r: (0, FIRST.index(r.name.split("/")[-1])) if r.name.split("/")[-1] in FIRST else (1, 0))
    if args.robots:
        wanted = args.robots.split(",")
        robots = [r for r in robots if any(w in r.name for w in wanted)]
    if args.reverse:
        robots.reverse()
    if args.shard:
        k, n = (int(x) for x in args.shard.split("/"))
        robots = robots[k::n]
    results: dict[str, dict[str, object]] = {}
    if (args.resume or args.simready_only) and os.path.isfile(args.out):
        with open(args.out, encoding="utf-8") as f:
            results = json.load(f)
    for extra in args.merge:
        with open(extra, encoding="utf-8") as f:
            for name, result in json.load(f).items():
                results.setdefault(name, result)
    if args.simready_only or args.merge:
        if args.simready_only:
            add_simready(results, args.envs, work)
        _write(results, args.out)
        return 0
    if args.kinds:
        kinds = args.kinds.split(",")
        unknown = sorted(set(kinds) - set(ALL_KINDS))
        if unknown:
            ap.error(f"unknown kinds {unknown}; known: {', '.join(ALL_KINDS)}")
        if os.path.isfile(args.out):  # the other columns are kept
            with open(args.out, encoding="utf-8") as f:
                results = {**json.load(f), **results}
        for robot in robots:
            row = results.setdefault(robot.name, {"floating": bool(FLOATING.search(robot.name))})
            if args.resume and all(k in row for k in kinds):
                continue
            start = time.perf_counter()
            if "newton_mjcf" in kinds:
                row.update(run_robot_mjcf(robot, args.envs, work))
            if "physx" in kinds:
                row.update(run_robot_physx(robot, work, not args.no_physx_dynamics))
            if set(kinds) & set(KINDS):
                row.update({k: v for k, v in run_robot(robot, args.envs, work).items() if k in kinds or k not in KINDS})
            print(f"{robot.name}: {time.perf_counter() - start:.0f} s  " + json.dumps(row), flush=True)
            _write(results, args.out)
        return 0
    for robot in robots:
        if robot.name in results:
            continue
        start = time.perf_counter()
        results[robot.name] = {
            **run_robot(robot, args.envs, work),
            **run_robot_physx(robot, work, not args.no_physx_dynamics),
        }
        print(f"{robot.name}: {time.perf_counter() - start:.0f} s  " + json.dumps(results[robot.name]), flush=True)
        _write(results, args.out)
    return 0


def _write(results: dict[str, dict[str, object]], out: str) -> None:
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    with open(out, "w", encoding="utf-8") as f:
        json.dump(results, f, indent=1, sort_keys=False)
        f.write("\n")
    with open(out[: -len(".json")] + ".md", "w", encoding="utf-8") as f:
        f.write(markdown(results))


if __name__ == "__main__":
    raise SystemExit(main())
