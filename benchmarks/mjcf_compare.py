"""URDF -> MJCF tools side by side on the same robots (issue 24): what each keeps, and how fast.

Tools, each through its command line, one process per robot as a user runs them:

- ``mujoco``: MuJoCo's own URDF loader with ``<mujoco><compiler discardvisual="false"
  fusestatic="false" strippath="false"/></mujoco>`` (what every menagerie README starts from), then
  ``mj_saveLastXML`` (this script's ``--mujoco-convert IN OUT``);
- ``urdf2mjcf``: ``urdf2mjcf IN --output OUT/robot.xml`` (PyPI ``urdf2mjcf``);
- ``urdf-to-mjcf``: ``urdf-to-mjcf IN -o OUT/robot.xml`` (PyPI ``urdf-to-mjcf``);
- ``robodesc``: ``robodesc compile SOURCE -t mjcf -o OUT/robot.xml --no-validate``, when the
  ``mjcf`` target is registered (otherwise its row says it is not there yet). ``--no-validate``
  because the peers check nothing either: the checks below are what judge every tool's output.

The peers read neither xacro nor ``package://``, so they get the same plain URDF: the source
expanded by robodesc with absolute mesh paths (``robodesc compile SOURCE -t urdf --mesh-paths
absolute --no-validate``, not timed). robodesc reads the source itself. Every tool runs with its
default flags (urdf-to-mjcf and urdf2mjcf make actuators only from a metadata JSON).

Each output is then checked against the source's IR with robodesc's MJCF validator
(:func:`robodesc.validation.mujoco_mjcf.validate_mjcf`) at engineering tolerances (``TOL``:
MuJoCo's ``mj_saveLastXML`` keeps 6 significant digits and urdf-to-mjcf writes 4-digit
quaternions, which tighter bounds would count as losses). Counted per tool: the model loads (no
MuJoCo error); an actuator drives every movable, non-mimic joint; mimic joints keep their coupling
(of the robots that have one); no link's mass is lost or changed; FK of every link matches; the
mujoco_menagerie model test passes (scene.xml where the tool writes one, else robot.xml).
Speed: wall time of each CLI per robot; the median ratio of urdf-to-mjcf's time to each tool's,
and of each tool's time to MuJoCo's C++ URDF compile in a warm process (the floor).

    PYTHONPATH=src python benchmarks/mjcf_compare.py --limit 30
    PYTHONPATH=src python benchmarks/mjcf_compare.py --robots 'ur5|panda|solo'

Writes benchmarks/results/mjcf_compare.json and .md.

``--speed-only`` times robodesc's and urdf-to-mjcf's CLIs and MuJoCo's C++ compile floor, and checks
nothing (benchmarks/results/mjcf_speed.json and .md). ``--base-src DIR`` adds another robodesc
source tree (e.g. a detached worktree of main) as ``robodesc-base``, for a before/after in one run.
On a shared, loaded machine the tools take turns on each robot (the order rotating from robot to
robot), so load drifts hit them alike and the per-robot ratios stay fair:

    PYTHONPATH=src python benchmarks/mjcf_compare.py --speed-only --base-src /tmp/base/src
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from typing import Any

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SRC = os.path.join(ROOT, "src")
SHARED_CORPUS = os.path.join(ROOT, "..", "shared", "corpus")
TOOLS = ("mujoco", "urdf2mjcf", "urdf-to-mjcf", "robodesc")
SPEED_TOOLS = ("robodesc-base", "urdf-to-mjcf", "robodesc")  # --speed-only; the base with --base-src
DEFAULT_OUT = os.path.join(HERE, "results", "mjcf_compare")
BASELINE = "urdf-to-mjcf"
CRITERIA = ("loads", "actuators", "mimic", "masses", "fk", "fk_1e-3", "menagerie")
LOOSE_FK = 1e-3  # m and rad: a second FK bar, to tell rounding (4-digit quaternions) from wrong frames
TOL = 1e-4  # relative for masses and gains; m and rad for FK; see the docstring
MUJOCO_BLOCK = '<mujoco><compiler discardvisual="false" fusestatic="false" strippath="false"/></mujoco>'


# ---- the MuJoCo "tool": its URDF loader + mj_saveLastXML ----------------------------------------
def mujoco_convert(urdf: str, out: str) -> int:
    """What a menagerie README's first step does; the compiler block goes in as its last child."""
    import mujoco

    with open(urdf, encoding="utf-8") as handle:
        text = handle.read()
    text = re.sub(r"<mujoco>.*?</mujoco>", "", text, flags=re.S)
    text = text.replace("</robot>", MUJOCO_BLOCK + "</robot>")
    model = mujoco.MjModel.from_xml_string(text)
    os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
    mujoco.mj_saveLastXML(out, model)
    return 0


# ---- running the tools ------------------------------------------------------------------------
def run(cmd: list[str], timeout: float, cwd: str, env: dict[str, str] | None = None) -> tuple[bool, float, str]:
    """Run in ``cwd`` (a scratch folder): MuJoCo appends what it warns about to MUJOCO_LOG.TXT there."""
    start = time.perf_counter()
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env, cwd=cwd)
    except subprocess.TimeoutExpired:
        return False, time.perf_counter() - start, f"timeout after {timeout:.0f} s"
    seconds = time.perf_counter() - start
    lines = [ln.strip() for ln in (done.stderr + done.stdout).strip().splitlines() if ln.strip()]
    # The line that says what went wrong, not the traceback's or MuJoCo's "Element ..." tail.
    errors = [ln for ln in lines if "rror" in ln]
    return done.returncode == 0, seconds, ((errors or lines or [""])[-1][:160])


def robodesc_env() -> dict[str, str]:
    return dict(os.environ, PYTHONPATH=SRC + os.pathsep + os.environ.get("PYTHONPATH", ""))


def robodesc_has_mjcf() -> bool:
    sys.path.insert(0, SRC)
    from robodesc.targets import TARGETS

    return "mjcf" in TARGETS


def prepare(entry: Any, work: str, timeout: float) -> tuple[str | None, str]:
    """The plain URDF the peers get (xacro expanded, absolute mesh paths)."""
    out = os.path.join(work, "source.urdf")
    cmd = [
        sys.executable,
        "-m",
        "robodesc",
        "compile",
        entry.path,
        "-t",
        "urdf",
        "-o",
        out,
    ]
    cmd += ["--mesh-paths", "absolute", "--no-validate", "-q", *package_args(entry)]
    ok, _, err = run(cmd, timeout, work, robodesc_env())
    return (out if ok else None), err


def package_args(entry: Any) -> list[str]:
    return [a for name, path in entry.packages.items() for a in ("--package", f"{name}={path}")]


def tool_command(tool: str, args: argparse.Namespace, entry: Any, urdf: str, out_dir: str) -> list[str]:
    robot_xml = os.path.join(out_dir, "robot.xml")
    if tool == "mujoco":
        return [
            sys.executable,
            os.path.abspath(__file__),
            "--mujoco-convert",
            urdf,
            robot_xml,
        ]
    if tool == "urdf2mjcf":
        return [args.urdf2mjcf, urdf, "--output", robot_xml]
    if tool == "urdf-to-mjcf":
        return [args.urdf_to_mjcf, urdf, "-o", robot_xml]
    robodesc = [
        sys.executable,
        "-m",
        "robodesc",
        "compile",
        entry.path,
        "-t",
        "mjcf",
        "-o",
        robot_xml,
    ]
    return [*robodesc, "--no-validate", "-q", *package_args(entry)]


def convert_all(
    entry: Any,
    urdf: str,
    work: str,
    args: argparse.Namespace,
    available: dict[str, str],
) -> dict[str, Any]:
    """Run every available tool once; returns tool -> {ok, seconds, error, robot_xml, scene_xml}."""
    out: dict[str, Any] = {}
    for tool in TOOLS:
        if available.get(tool):
            out[tool] = {
                "ok": False,
                "seconds": None,
                "error": available[tool],
                "skipped": True,
            }
            continue
        out_dir = os.path.join(work, tool)
        os.makedirs(out_dir, exist_ok=True)
        env = robodesc_env() if tool == "robodesc" else None
        ok, seconds, err = run(tool_command(tool, args, entry, urdf, out_dir), args.timeout, out_dir, env)
        robot_xml = os.path.join(out_dir, "robot.xml")
        scene = os.path.join(out_dir, "scene.xml")
        ok = ok and os.path.isfile(robot_xml)
        out[tool] = {
            "ok": ok,
            "seconds": seconds,
            "error": "" if ok else err,
            "robot_xml": robot_xml,
            "scene_xml": scene if os.path.isfile(scene) else None,
        }
    return out


# ---- checking the outputs (in a child process: a bad model may crash MuJoCo) --------------------
def check_worker(job_path: str) -> int:
    """Validate every tool's output for one robot; print one JSON line."""
    sys.path.insert(0, SRC)
    with open(job_path, encoding="utf-8") as handle:
        job = json.load(handle)
    robot = load_ir(job["source"], job["packages"])
    result: dict[str, Any] = {
        "floor_s": floor_seconds(job["urdf"]),
        "tools": {},
        "mimic_joints": 0,
    }
    if robot is None:
        result["error"] = "robodesc cannot read the source"
        print(json.dumps(result))
        return 0
    result["mimic_joints"] = sum(1 for j in robot.joints if j.mimic is not None)
    for tool, conv in job["outputs"].items():
        if conv.get("ok"):
            result["tools"][tool] = criteria(robot, conv["robot_xml"], conv.get("scene_xml"))
    print(json.dumps(result))
    return 0


def load_ir(source: str, packages: dict[str, str]) -> Any:
    from robodesc.frontends.load import load_path
    from robodesc.frontends.options import LoadOptions, MissingMesh
    from robodesc.ir.diagnostics import RobodescError

    try:
        return load_path(source, LoadOptions(package_paths=packages, missing_mesh=MissingMesh.WARN)).robot
    except RobodescError:
        return None


def floor_seconds(urdf: str) -> float | None:
    """MuJoCo's C++ URDF compile in a warm process, best of 3 (visuals discarded: no DAE to refuse)."""
    import mujoco

    from robodesc.validation.mujoco_load import with_compiler_options

    with open(urdf, encoding="utf-8") as handle:
        text = with_compiler_options(handle.read())
    best = None
    for _ in range(3):
        start = time.perf_counter()
        try:
            mujoco.MjModel.from_xml_string(text)
        except ValueError:
            return None
        elapsed = time.perf_counter() - start
        best = elapsed if best is None else min(best, elapsed)
    return best


def criteria(robot: Any, robot_xml: str, scene_xml: str | None) -> dict[str, Any]:
    from robodesc.validation.mujoco_mjcf import validate_mjcf
    from robodesc.validation.options import ValidateOptions
    from robodesc.validation.report import Status

    opts = ValidateOptions(
        fk_samples=4,
        mass_rel_tol=TOL,
        inertia_rel_tol=TOL,
        position_tol=TOL,
        rotation_tol=TOL,
        axis_tol=TOL,
        limit_tol=TOL,
        gain_rel_tol=TOL,
    )
    report = validate_mjcf(robot, robot_xml, scene_xml, opts)

    def failed(*names: str, element_prefix: str = "") -> list[str]:
        return [
            f"{c.name} {c.element}: {c.message}"[:200]
            for c in report.checks
            if c.name in names and c.status is Status.FAIL and c.element.startswith(element_prefix)
        ]

    def passed(name: str) -> bool:
        return any(c.name == name and c.status is Status.PASS for c in report.checks)

    loads = passed("mjcf-load")
    has_mimic = any(j.mimic is not None for j in robot.joints)
    verdict = {
        "loads": (loads, failed("mjcf-load")),
        "actuators": (loads and not failed("actuators"), failed("actuators")),
        "mimic": (loads and not failed("mimic"), failed("mimic")) if has_mimic else (None, []),
        "masses": (
            loads and not failed("mass") and not failed("bodies", element_prefix="link "),
            failed("mass", "bodies"),
        ),
        "fk": (passed("fk"), failed("fk")),
        "fk_1e-3": (loads and _fk_within(report.max_errors, LOOSE_FK), []),
        "menagerie": (
            passed("menagerie"),
            failed("menagerie", "scene-load", "mujoco-warning"),
        ),
    }
    return {
        "criteria": {k: v[0] for k, v in verdict.items()},
        "why": {k: v[1][:3] for k, v in verdict.items() if v[1]},
        "max_errors": report.max_errors,
    }


def _fk_within(max_errors: dict[str, float], bound: float) -> bool:
    """False when FK was not compared, or a NaN (which fails every comparison)."""
    errors = [max_errors.get("fk_position"), max_errors.get("fk_rotation")]
    return all(e is not None and e <= bound for e in errors)


def speed_only_robot(entry: Any, args: argparse.Namespace, index: int) -> dict[str, Any]:
    """One robot: each CLI once (taking turns, the order rotated by ``index``), and the floor."""
    work = tempfile.mkdtemp(prefix="mjcf-speed-")
    name = f"{entry.corpus}/{entry.name}"
    try:
        urdf, err = prepare(entry, work, args.timeout)
        if urdf is None:
            print(f"{name}: robodesc cannot prepare the plain URDF ({err}); left out", flush=True)
            return {"name": name, "prepare_error": err}
        tools = [t for t in SPEED_TOOLS if t != "robodesc-base" or args.base_src]
        shift = index % len(tools)
        row: dict[str, Any] = {"name": name, "tools": {}}
        for tool in tools[shift:] + tools[:shift]:
            out_dir = os.path.join(work, tool)
            os.makedirs(out_dir, exist_ok=True)
            src = args.base_src if tool == "robodesc-base" else SRC
            cmd = tool_command("robodesc" if tool.startswith("robodesc") else tool, args, entry, urdf, out_dir)
            env = dict(os.environ, PYTHONPATH=src) if tool.startswith("robodesc") else None
            ok, seconds, error = run(cmd, args.timeout, out_dir, env)
            ok = ok and os.path.isfile(os.path.join(out_dir, "robot.xml"))
            row["tools"][tool] = {"ok": ok, "seconds": seconds, "error": "" if ok else error}
        ok, _, text = run(
            [sys.executable, os.path.abspath(__file__), "--floor-worker", urdf], args.timeout, work, robodesc_env()
        )
        row["floor_s"] = float(text) if ok and text and text != "None" else None
        cells = "  ".join(f"{t} {c['seconds']:.2f}s" if c["ok"] else f"{t} FAIL" for t, c in row["tools"].items())
        print(f"{name}: {cells}  floor {_num(row['floor_s'], '.4f')}s", flush=True)
        return row
    finally:
        shutil.rmtree(work, ignore_errors=True)


def speed_summary(rows: list[dict[str, Any]]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for tool in SPEED_TOOLS:
        have = [r for r in rows if tool in r["tools"]]
        if have:
            out[tool] = {"robots": len(have), "converted": sum(1 for r in have if r["tools"][tool]["ok"])}
            out[tool].update(speed(have, tool))
    return out


def speed_markdown(
    summary: dict[str, Any], rows: list[dict[str, Any]], left_out: list[dict[str, Any]], selected: int, compiled: bool
) -> str:
    tools = list(summary)
    lines = [
        "# URDF -> MJCF speed: robodesc and urdf-to-mjcf CLIs (issue 24)",
        "",
        "`python benchmarks/mjcf_compare.py --speed-only` (no output checks; see `mjcf_compare.md` for those).",
        f"{len(rows)} of {selected} robots timed ({len(left_out)} left out: robodesc could not prepare their plain",
        "URDF); one process per robot and tool, the tools taking turns on each robot, so machine load hits them alike.",
        "robodesc's source trees "
        + (
            "were byte-compiled first, as pip does at install."
            if compiled
            else "were not byte-compiled (--no-byte-compile)."
        )
        + " robodesc-base: the tree given by --base-src.",
        "Speed-up: urdf-to-mjcf's wall time over the tool's, per robot, median. x floor: the tool's wall time",
        "over MuJoCo's C++ compile of the same URDF in a warm process (best of 3), median.",
        f"Machine load at the end: {os.getloadavg()[0]:.1f} (1 min) on {os.cpu_count()} CPUs.",
        "",
        "| tool | converted | median s | speed-up vs urdf-to-mjcf | x floor |",
        "|---|---|---|---|---|",
    ]
    for tool in tools:
        s = summary[tool]
        lines.append(
            f"| {tool} | {s['converted']}/{s['robots']} | {_num(s['median_s'], '.3f')} "
            f"| {_num(s['median_speedup_vs_urdf_to_mjcf'], '.2f')} | {_num(s['median_x_floor'], '.1f')} |"
        )
    lines += [
        "",
        "## Per robot (seconds)",
        "",
        "| robot | " + " | ".join(tools) + " | floor |",
        "|---" * (len(tools) + 2) + "|",
    ]
    for r in rows:
        cells = [
            (f"{r['tools'][t]['seconds']:.3f}" if r["tools"][t]["ok"] else "FAIL") if t in r["tools"] else "–"
            for t in tools
        ]
        lines.append(f"| {r['name']} | " + " | ".join(cells) + f" | {_num(r.get('floor_s'), '.4f')} |")
    return "\n".join(lines) + "\n"


def byte_compile(src: str) -> None:
    """Write robodesc's .pyc files, as pip does when it installs a package. Without them (a source
    tree under PYTHONDONTWRITEBYTECODE=1, as on the shared machine) every run compiles every module
    again, ~0.5 s that no installed tool pays."""
    import compileall

    compileall.compile_dir(src, quiet=1)


def speed_main(args: argparse.Namespace) -> int:
    robots = select_robots(args.robots, args.limit)
    trees = [SRC] + ([args.base_src] if args.base_src else [])
    if not args.no_byte_compile:
        for src in trees:
            byte_compile(src)
    out = args.out if args.out != DEFAULT_OUT else os.path.join(HERE, "results", "mjcf_speed")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    rows: list[dict[str, Any]] = []
    text = ""
    for i, entry in enumerate(robots):
        rows.append(speed_only_robot(entry, args, i))
        # Written after every robot: a long run stopped early still leaves its numbers.
        kept = [r for r in rows if "prepare_error" not in r]
        left_out = [r for r in rows if "prepare_error" in r]
        summary = speed_summary(kept)
        with open(out + ".json", "w", encoding="utf-8") as handle:
            meta = {
                "byte_compiled": not args.no_byte_compile,
                "robots_selected": len(robots),
                "base_src": args.base_src,
            }
            json.dump({**meta, "summary": summary, "left_out": left_out, "rows": kept}, handle, indent=1)
        text = speed_markdown(summary, kept, left_out, len(robots), not args.no_byte_compile)
        with open(out + ".md", "w", encoding="utf-8") as handle:
            handle.write(text)
    print(text.split("\n## Per robot")[0])
    return 0


def check(entry: Any, urdf: str, conversions: dict[str, Any], work: str, timeout: float) -> dict[str, Any]:
    job = {
        "source": entry.path,
        "packages": entry.packages,
        "urdf": urdf,
        "outputs": conversions,
    }
    job_path = os.path.join(work, "job.json")
    with open(job_path, "w", encoding="utf-8") as handle:
        json.dump(job, handle)
    cmd = [sys.executable, os.path.abspath(__file__), "--check-worker", job_path]
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=robodesc_env(), cwd=work)
        parsed: dict[str, Any] = json.loads(done.stdout.strip().splitlines()[-1])
        return parsed
    except (subprocess.TimeoutExpired, json.JSONDecodeError, IndexError) as exc:
        return {
            "error": f"checker failed: {type(exc).__name__}",
            "tools": {},
            "floor_s": None,
            "mimic_joints": 0,
        }


# ---- the report -------------------------------------------------------------------------------
def summarise(rows: list[dict[str, Any]], available: dict[str, str]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    with_mimic = sum(1 for r in rows if r.get("mimic_joints"))
    for tool in TOOLS:
        if available.get(tool):
            out[tool] = {"skipped": available[tool]}
            continue
        counts = {c: 0 for c in CRITERIA}
        for r in rows:
            crit = r["checks"].get(tool, {}).get("criteria", {})
            for c in CRITERIA:
                counts[c] += bool(crit.get(c))
        out[tool] = {
            "robots": len(rows),
            "converted": sum(1 for r in rows if r["tools"][tool]["ok"]),
            "counts": counts,
            "robots_with_mimic": with_mimic,
            **speed(rows, tool),
        }
    return out


def speed(rows: list[dict[str, Any]], tool: str) -> dict[str, float | None]:
    mine = [r for r in rows if r["tools"][tool]["ok"]]
    times = [r["tools"][tool]["seconds"] for r in mine]
    vs_base = [
        r["tools"][BASELINE]["seconds"] / r["tools"][tool]["seconds"] for r in mine if r["tools"][BASELINE]["ok"]
    ]
    vs_floor = [r["tools"][tool]["seconds"] / r["floor_s"] for r in mine if r.get("floor_s")]
    return {
        "median_s": statistics.median(times) if times else None,
        "median_speedup_vs_urdf_to_mjcf": statistics.median(vs_base) if vs_base else None,
        "median_x_floor": statistics.median(vs_floor) if vs_floor else None,
    }


def markdown(summary: dict[str, Any], rows: list[dict[str, Any]], args: argparse.Namespace) -> str:
    n = len(rows)
    floors = [r["floor_s"] for r in rows if r.get("floor_s")]
    lines = [
        "# URDF -> MJCF: MuJoCo's loader, urdf2mjcf, urdf-to-mjcf and robodesc",
        "",
        f"`python benchmarks/mjcf_compare.py {' '.join(sys.argv[1:])}` — {n} robots of the corpus "
        f"(`robodesc.validation.corpora`), MuJoCo {mujoco_version()}, tools at their default flags; "
        f"checks by robodesc's MJCF validator at {TOL:g} (see the script's docstring).",
        "",
        "| tool | converted | loads | actuator on every movable joint | keeps mimic | keeps masses | keeps FK "
        f"| keeps FK to {LOOSE_FK:g} | menagerie test | median s/robot | urdf-to-mjcf time / tool time (median) | tool time / MuJoCo C++ compile (median) |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for tool in TOOLS:
        s = summary[tool]
        if "skipped" in s:
            lines.append(f"| {tool} | – | – | – | – | – | – | – | – | – | – | {s['skipped']} |")
            continue
        c = s["counts"]
        lines.append(
            f"| {tool} | {s['converted']}/{n} | {c['loads']}/{n} | {c['actuators']}/{n} | "
            f"{c['mimic']}/{s['robots_with_mimic']} | {c['masses']}/{n} | {c['fk']}/{n} | {c['fk_1e-3']}/{n} | {c['menagerie']}/{n} | "
            f"{_num(s['median_s'], '.2f')} | x{_num(s['median_speedup_vs_urdf_to_mjcf'], '.2f')} | "
            f"x{_num(s['median_x_floor'], '.0f')} |"
        )
    if floors:
        lines += [
            "",
            f"MuJoCo's C++ URDF compile (the floor): median {statistics.median(floors) * 1000:.1f} ms per robot.",
        ]
    lines += reasons(rows, summary)
    lines += [
        "",
        "## Per robot",
        "",
        "| robot | " + " | ".join(TOOLS) + " |",
        "|---|" + "---|" * len(TOOLS),
    ]
    for r in rows:
        cells = [_cell(r, tool, summary) for tool in TOOLS]
        lines.append(f"| {r['name']} | " + " | ".join(cells) + " |")
    lines += [
        "",
        "Cell: seconds, then the criteria it fails (L loads, A actuators, M mimic, m masses, F FK, "
        f"f FK to {LOOSE_FK:g}, T menagerie test).",
    ]
    return "\n".join(lines) + "\n"


_BLANKS = (re.compile(r"'[^']*'"), re.compile(r"/\S+"), re.compile(r"-?\d+(\.\d+)?(e[-+]?\d+)?"))


def reasons(rows: list[dict[str, Any]], summary: dict[str, Any], top: int = 3) -> list[str]:
    """The commonest failure of each tool and criterion, names and numbers blanked out."""
    out = ["", "## Why they fail (commonest reasons, with the number of robots)", ""]
    for tool in TOOLS:
        if "skipped" in summary[tool]:
            continue
        counts: dict[str, int] = {}
        for r in rows:
            conv = r["tools"][tool]
            whys = {"converts": [conv["error"]]} if not conv["ok"] else r["checks"].get(tool, {}).get("why", {})
            for crit, messages in whys.items():
                key = f"{crit}: {_blank(messages[0]) if messages else '?'}"
                counts[key] = counts.get(key, 0) + 1
        ranked = sorted(counts.items(), key=lambda kv: -kv[1])[: top * 3]
        out += [f"- **{tool}**: " + "; ".join(f"{n}× {k}" for k, n in ranked)]
    return out


def _blank(text: str) -> str:
    text = text.splitlines()[0] if text else ""
    for pattern in _BLANKS:
        text = pattern.sub("…", text)
    return text[:140].replace("|", "/")


def _cell(row: dict[str, Any], tool: str, summary: dict[str, Any]) -> str:
    if "skipped" in summary[tool]:
        return "–"
    conv = row["tools"][tool]
    if not conv["ok"]:
        return f"fails: {conv['error'][:60]}".replace("|", "/")
    crit = row["checks"].get(tool, {}).get("criteria", {})
    letters = {
        "loads": "L",
        "actuators": "A",
        "mimic": "M",
        "masses": "m",
        "fk": "F",
        "fk_1e-3": "f",
        "menagerie": "T",
    }
    lost = "".join(letters[c] for c in CRITERIA if crit.get(c) is False)
    return f"{conv['seconds']:.2f}" + (f" ✗{lost}" if lost else " ✓")


def _num(value: float | None, fmt: str) -> str:
    return "–" if value is None else format(value, fmt)


def mujoco_version() -> str:
    import mujoco

    return str(mujoco.__version__)


# ---- driver -----------------------------------------------------------------------------------
def select_robots(patterns: list[str], limit: int) -> list[Any]:
    sys.path.insert(0, SRC)
    from robodesc.validation.corpora import all_robots

    robots = all_robots(SHARED_CORPUS)
    if patterns:
        rx = re.compile("|".join(f"(?:{p})" for p in patterns))
        robots = [r for r in robots if rx.search(f"{r.corpus}/{r.name}")]
    return robots[:limit] if limit else robots


def availability(args: argparse.Namespace) -> dict[str, str]:
    """Tool -> why it is skipped ('' when it runs)."""
    out = {"mujoco": "", "urdf2mjcf": "", "urdf-to-mjcf": "", "robodesc": ""}
    for tool, exe in (
        ("urdf2mjcf", args.urdf2mjcf),
        ("urdf-to-mjcf", args.urdf_to_mjcf),
    ):
        if not os.path.isfile(exe):
            out[tool] = f"not installed at {exe}"
    if not robodesc_has_mjcf():
        out["robodesc"] = "the mjcf target is not registered in this tree (robodesc.pipeline.TARGETS) yet"
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument(
        "--robots",
        action="append",
        default=[],
        help="regex on CORPUS/NAME (repeatable)",
    )
    parser.add_argument("--limit", type=int, default=0, help="at most this many robots")
    parser.add_argument("--urdf2mjcf", default="/tmp/venv-urdf2mjcf/bin/urdf2mjcf")
    parser.add_argument(
        "--urdf-to-mjcf",
        dest="urdf_to_mjcf",
        default="/tmp/venv-urdf-to-mjcf/bin/urdf-to-mjcf",
    )
    parser.add_argument("--timeout", type=float, default=300.0, help="seconds per tool and robot")
    parser.add_argument("--out", default=DEFAULT_OUT, help="results path without extension")
    parser.add_argument(
        "--speed-only",
        action="store_true",
        help="time robodesc and urdf-to-mjcf (and the floor) only, no checks: results/mjcf_speed.*",
    )
    parser.add_argument("--base-src", help="with --speed-only: another robodesc src/ to time as robodesc-base")
    parser.add_argument(
        "--no-byte-compile",
        action="store_true",
        help="with --speed-only: time robodesc's trees without writing their .pyc files first",
    )
    parser.add_argument("--floor-worker", help=argparse.SUPPRESS)
    parser.add_argument("--mujoco-convert", nargs=2, metavar=("URDF", "OUT"), help=argparse.SUPPRESS)
    parser.add_argument("--check-worker", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.mujoco_convert:
        return mujoco_convert(*args.mujoco_convert)
    if args.check_worker:
        return check_worker(args.check_worker)
    if args.floor_worker:
        print(floor_seconds(args.floor_worker))
        return 0
    if args.speed_only:
        return speed_main(args)

    available = availability(args)
    robots = select_robots(args.robots, args.limit)
    rows = [one_robot(entry, args, available) for entry in robots]
    summary = summarise([r for r in rows if "prepare_error" not in r], available)
    write_results(args.out, summary, rows, args)
    return 0


def one_robot(entry: Any, args: argparse.Namespace, available: dict[str, str]) -> dict[str, Any]:
    work = tempfile.mkdtemp(prefix="mjcf-compare-")
    name = f"{entry.corpus}/{entry.name}"
    try:
        urdf, err = prepare(entry, work, args.timeout)
        if urdf is None:
            print(
                f"{name}: robodesc cannot prepare the plain URDF ({err}); left out",
                flush=True,
            )
            return {"name": name, "prepare_error": err}
        conversions = convert_all(entry, urdf, work, args, available)
        checked = check(entry, urdf, conversions, work, args.timeout)
        row = {
            "name": name,
            "tools": {
                t: {k: v for k, v in c.items() if k not in ("robot_xml", "scene_xml")} for t, c in conversions.items()
            },
            "checks": checked.get("tools", {}),
            "floor_s": checked.get("floor_s"),
            "mimic_joints": checked.get("mimic_joints", 0),
        }
        print(
            f"{name}: " + "  ".join(f"{t} {_progress(row, t)}" for t in TOOLS),
            flush=True,
        )
        return row
    finally:
        shutil.rmtree(work, ignore_errors=True)


def _progress(row: dict[str, Any], tool: str) -> str:
    conv = row["tools"][tool]
    if conv.get("skipped"):
        return "-"
    if not conv["ok"]:
        return "FAIL"
    crit = row["checks"].get(tool, {}).get("criteria", {})
    return f"{conv['seconds']:.2f}s " + "".join(
        "+" if crit.get(c) else ("." if crit.get(c) is None else "x") for c in CRITERIA
    )


def write_results(
    out: str,
    summary: dict[str, Any],
    rows: list[dict[str, Any]],
    args: argparse.Namespace,
) -> None:
    os.makedirs(os.path.dirname(out), exist_ok=True)
    kept = [r for r in rows if "prepare_error" not in r]
    with open(out + ".json", "w", encoding="utf-8") as handle:
        json.dump(
            {
                "tolerance": TOL,
                "summary": summary,
                "left_out": [r for r in rows if "prepare_error" in r],
                "rows": kept,
            },
            handle,
            indent=1,
        )
    text = markdown(summary, kept, args)
    with open(out + ".md", "w", encoding="utf-8") as handle:
        handle.write(text)
    print(text.split("\n## Per robot")[0])


if __name__ == "__main__":
    sys.exit(main())
