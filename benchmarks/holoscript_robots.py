"""Compile HoloScript's robot files to every target and load each URDF written for ROS in urdfdom.

    PYTHONPATH=src python benchmarks/holoscript_robots.py FOLDER [--json OUT.json] [--label before]

FOLDER holds HoloScript ``.holo`` robot files (how to get them: ``tests/urdfdom/run.sh --help`` and
``benchmarks/results/holoscript_robots.md``; they are not part of robodesc). Every file is compiled
through the CLI, with default flags (validation on), to ``-t urdf``, ``--ros2``, ``--isaac-sim``,
``-t mjcf`` and ``-t usd``. Each outcome is ``ok`` (exit 0), ``refused`` (exit 2, a message about
the source) or ``crashed`` (any other exit: robodesc's fault). Every URDF written for ROS (the
``-t urdf`` file, the ROS 2 folder's URDF, the Isaac folder's URDF) is then loaded by urdfdom
through Pinocchio (``pin.buildModelFromXML``) and by every ``check_urdf`` found (the one on PATH,
Debian's ``/usr/bin/check_urdf`` from ``liburdfdom-tools``).

Prints one line per output and a summary; ``--json`` writes the outcomes. Exit 1 when a compile
crashed or urdfdom refused a URDF that robodesc wrote.

``--joints`` prints instead what the HoloScript frontend reads from each file (no compile): every
movable joint with its limits (radians as the IR holds them, and degrees), and every link's mass and
inertia diagonal, so that two robodesc versions can be compared file by file.
"""

from __future__ import annotations

import argparse
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import asdict, dataclass, field

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# target name, CLI arguments, output name (a folder when it has no suffix)
TARGETS = (
    ("urdf", ["-t", "urdf"], "robot.urdf"),
    ("ros2", ["--ros2"], "ros2"),
    ("isaac", ["--isaac-sim"], "isaac"),
    ("mjcf", ["-t", "mjcf"], "robot.xml"),
    ("usd", ["-t", "usd"], "robot.usda"),
)
ROS_TARGETS = ("urdf", "ros2", "isaac")


@dataclass
class Compiled:
    target: str
    outcome: str  # ok | refused | crashed
    message: str = ""
    # urdfdom's verdict per URDF written for ROS: checker name -> "ok" or the refusal
    urdfdom: dict[str, str] = field(default_factory=dict)


@dataclass
class FileResult:
    path: str
    compiled: list[Compiled] = field(default_factory=list)


def robot_files(folder: str) -> list[str]:
    return sorted(glob.glob(os.path.join(folder, "**", "*.holo"), recursive=True))


def checkers() -> dict[str, str]:
    """Every check_urdf binary on this machine, by a short name (the same path once)."""
    found: dict[str, str] = {}
    on_path = shutil.which("check_urdf")
    if on_path:
        found["check_urdf"] = os.path.realpath(on_path)
    debian = "/usr/bin/check_urdf"
    if os.path.isfile(debian) and os.path.realpath(debian) not in found.values():
        found["debian check_urdf"] = debian
    return found


def check_urdf(binary: str, urdf: str) -> str:
    """``ok`` or urdfdom's first error line (an ``Error`` line is a refusal even with exit 0:
    urdfdom logs some refusals and loads the rest without the element)."""
    proc = subprocess.run([binary, urdf], capture_output=True, text=True, timeout=120)
    lines = (proc.stdout + proc.stderr).strip().splitlines()
    errors = [line.strip() for line in lines if line.lstrip().startswith("Error")]
    if proc.returncode == 0 and not errors:
        return "ok"
    return errors[0] if errors else (lines[-1] if lines else f"exit {proc.returncode}")


def pinocchio_loads(urdf: str) -> str:
    try:
        import pinocchio as pin
    except ImportError:
        return "pinocchio not installed"
    with open(urdf, encoding="utf-8") as handle:
        text = handle.read()
    try:
        pin.buildModelFromXML(text)
    except (ValueError, RuntimeError) as exc:  # urdfdom's refusal
        return str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    return "ok"


def ros_urdfs(target: str, out: str) -> list[str]:
    """The URDF files a target wrote for ROS."""
    if target == "urdf":
        return [out]
    if target in ("ros2", "isaac"):
        return sorted(glob.glob(os.path.join(out, "**", "*.urdf"), recursive=True))
    return []


def compile_one(path: str, args: list[str], out: str) -> tuple[int, str]:
    cmd = [sys.executable, "-m", "robodesc", "compile", path, *args, "-o", out, "-q"]
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=900)
    except subprocess.TimeoutExpired:
        return -1, "timeout after 900 s"
    last = [line for line in proc.stderr.splitlines() if line.strip()]
    return proc.returncode, (last[-1].strip() if last else "")


def survey(folder: str, targets: tuple[str, ...] = tuple(t for t, _, _ in TARGETS)) -> list[FileResult]:
    found = checkers()
    results = []
    for path in robot_files(folder):
        result = FileResult(os.path.relpath(path, folder))
        with tempfile.TemporaryDirectory() as tmp:
            for target, args, name in TARGETS:
                if target not in targets:
                    continue
                out = os.path.join(tmp, target, name)
                os.makedirs(os.path.dirname(out))
                code, message = compile_one(path, args, out)
                outcome = "ok" if code == 0 else "refused" if code == 2 else "crashed"
                compiled = Compiled(target, outcome, "" if code == 0 else f"exit {code}: {message}")
                if code == 0:
                    for urdf in ros_urdfs(target, out):
                        key = "" if target == "urdf" else os.path.relpath(urdf, out) + " "
                        compiled.urdfdom[key + "pinocchio"] = pinocchio_loads(urdf)
                        for checker, binary in found.items():
                            compiled.urdfdom[key + checker] = check_urdf(binary, urdf)
                result.compiled.append(compiled)
        results.append(result)
    return results


def joints_read(folder: str) -> list[str]:
    """One line per movable joint and per link of every file, as the frontend reads it."""
    import math

    from robodesc.frontends.holo.lower import load_holo
    from robodesc.frontends.options import LoadOptions
    from robodesc.ir.diagnostics import Findings, RobodescError

    lines = []
    for path in robot_files(folder):
        rel = os.path.relpath(path, folder)
        try:
            robot = load_holo(path, LoadOptions(), Findings()).robot
        except RobodescError as exc:
            lines.append(f"{rel}: refused: {str(exc).splitlines()[0]}")
            continue
        for j in robot.joints:
            if j.type.value == "fixed":
                continue
            lim = j.limit
            lo, hi = (lim.lower, lim.upper) if lim is not None else (None, None)
            span = (
                f"[{lo:.6g}, {hi:.6g}] rad = [{math.degrees(lo):.4g}, {math.degrees(hi):.4g}] deg"
                if lo is not None and hi is not None and j.type.value == "revolute"
                else f"[{lo}, {hi}]"
            )
            damping = j.dynamics.damping if j.dynamics is not None else None
            lines.append(f"{rel}: joint {j.name} {j.type.value} {span} damping={damping}")
        for link in robot.links:
            inertial = link.inertial
            if inertial is None:
                lines.append(f"{rel}: link {link.name} no inertial")
                continue
            i = inertial.inertia
            diag = "none" if i is None else f"{i.ixx:.6g} {i.iyy:.6g} {i.izz:.6g}"
            lines.append(f"{rel}: link {link.name} mass={inertial.mass:g} inertia={diag}")
    return lines


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folder", help="a folder of HoloScript .holo robot files")
    parser.add_argument("--json", help="write the outcomes here")
    parser.add_argument("--label", default="", help="a label stored in the JSON (e.g. before, after)")
    parser.add_argument("--joints", action="store_true", help="print the joints and links read; no compile")
    args = parser.parse_args()
    if args.joints:
        print("\n".join(joints_read(args.folder)))
        return 0
    results = survey(args.folder)
    crashed = refused_by_urdfdom = 0
    for result in results:
        for c in result.compiled:
            bad = {k: v for k, v in c.urdfdom.items() if v != "ok"}
            crashed += c.outcome == "crashed"
            refused_by_urdfdom += bool(bad)
            verdict = "urdfdom ok" if c.urdfdom and not bad else ("urdfdom REFUSED " + str(bad) if bad else "")
            print(f"{c.outcome:8} {c.target:5} {result.path} {c.message} {verdict}".rstrip())
    print(f"{len(results)} files; {crashed} compiles crashed; {refused_by_urdfdom} ROS outputs refused by urdfdom")
    if args.json:
        with open(args.json, "w", encoding="utf-8") as handle:
            json.dump({"label": args.label, "files": [asdict(r) for r in results]}, handle, indent=1)
            handle.write("\n")
    return 1 if crashed or refused_by_urdfdom else 0


if __name__ == "__main__":
    sys.exit(main())
