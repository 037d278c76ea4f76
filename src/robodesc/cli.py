"""``robodesc`` on the command line: a thin layer over :mod:`robodesc.api`.

Bad input never shows a traceback: each problem is one line ``error: file:line: element: what``.
Exit codes (docs/diagnostics.md): 0 written (warnings, if any, are listed), 1 the output failed
validation because of robodesc (nothing written), 2 refused (bad input, options or output path;
nothing written), 3 a robodesc bug (one line; ``--debug`` shows the trace).
A successful compile prints its warnings grouped by kind, then one summary line; ``-v`` lists every
finding; ``--json`` prints one JSON document on every exit path.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import threading
from collections import defaultdict
from collections.abc import Sequence
from typing import Any, NoReturn

from robodesc._version import __version__
from robodesc.emit.common.paths import PathMode
from robodesc.frontends.options import MissingMesh
from robodesc.ir.diagnostics import ConfigError, Finding, RobodescError, Severity, SourceLoc, VerificationError
from robodesc.options import CompileOptions, InvalidInertia, build_options
from robodesc.pipeline import TARGETS, compile_robot, target_options_class

EPILOG = """\
examples:
  robodesc compile robot.urdf.xacro -t urdf -o out/robot.urdf --package my_pkg=src/my_pkg
  robodesc compile go2.urdf.xacro -t urdf -o go2.urdf --missing-mesh warn --invalid-inertia repair
  robodesc inspect robot.urdf
exit codes: 0 written (warnings listed), 1 validation failed because of robodesc (nothing written),
            2 refused: bad input, options or output path (nothing written), 3 a robodesc bug
"""


def _key_value(text: str) -> tuple[str, str]:
    name, sep, value = text.partition("=")
    name = name.removesuffix(":")  # ROS style NAME:=VALUE
    if not sep or not name:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    return name, value


def _add_package_and_arg(g: argparse._ActionsContainer) -> None:
    g.add_argument(
        "--package",
        metavar="NAME=DIR",
        action="append",
        type=_key_value,
        default=[],
        help="where ROS package NAME lives, for package:// URIs and $(find NAME) (repeatable). "
        "Without it robodesc looks above the input for package.xml, beside that package, "
        "then in ROS_PACKAGE_PATH and AMENT_PREFIX_PATH.",
    )
    g.add_argument(
        "--arg", metavar="NAME=VALUE", action="append", type=_key_value, default=[], help="xacro argument (repeatable)"
    )
    g.add_argument(
        "--env",
        metavar="NAME",
        action="append",
        default=[],
        help="let xacro's $(env NAME) / $(optenv NAME) read this environment variable (repeatable); "
        "no other variable is read",
    )
    g.add_argument(
        "--trust-xacro",
        action="store_true",
        help="expand xacro with upstream's Python evaluation: expressions may run code, read any file "
        "and the whole environment. Only for files you trust (docs/security.md)",
    )


def _add_input_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("input")
    _add_package_and_arg(g)
    g.add_argument(
        "--missing-mesh",
        choices=[m.value for m in MissingMesh],
        default="warn",
        help="a mesh file that does not exist: keep the reference with a warning (warn, default; USD leaves "
        "the shape out), fail (error), substitute a box of its scale (primitive) or drop that visual/collision (drop)",
    )
    g.add_argument(
        "--invalid-inertia",
        choices=[m.value for m in InvalidInertia],
        default="warn",
        help="physically invalid mass or inertia in the source (mass <= 0, a tensor that is not positive "
        "definite or breaks the triangle inequality): pass through with a warning (warn, default), fail "
        "(error), or repair from geometry and report each repair (repair)",
    )
    g.add_argument(
        "--strict",
        action="store_true",
        help="every warning is an error: refuse (exit 2, nothing written) when the source has any defect, "
        "unknown elements included (for CI pipelines)",
    )


class _UsageError(Exception):
    """argparse found a bad command line (exit 2): raised instead of exiting so --json can report it."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        raise _UsageError(f"{self.prog}: {message}")


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="robodesc",
        description="Compile robot descriptions: URDF/xacro and compositions to URDF, SDF and Isaac-ready USD.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--version", action="version", version=f"robodesc {__version__}")
    parser.add_argument("--debug", action="store_true", help="show the traceback of an internal error")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")

    comp = sub.add_parser(
        "compile",
        help="compile a robot description to a target",
        description="Compile INPUT (URDF, .xacro) to a target format, running the verifier and the passes you select.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=EPILOG,
    )
    comp.add_argument("input", help="URDF, .xacro, composition (.yaml, .holo) file")
    comp.add_argument(
        "-t",
        "--target",
        choices=sorted(TARGETS),
        default="urdf",
        help="output format (default: urdf; isaac and ros2 write folders, as --isaac-sim and --ros2 do)",
    )
    comp.add_argument(
        "-o",
        "--output",
        help="output file, or folder for --ros2/--isaac-sim (default: standard output for text targets)",
    )
    comp.add_argument(
        "--isaac-sim",
        action="store_true",
        help="write everything Isaac Sim / Isaac Lab need to the folder -o: USD asset, Isaac-flavoured URDF, "
        "importer_settings.json, an Isaac Lab ArticulationCfg module, the validation report (runs --preset isaac_sim)",
    )
    comp.add_argument(
        "--ros2",
        action="store_true",
        help="write a ROS 2 / Gazebo Harmonic folder to -o: URDF with <ros2_control> (gz_ros2_control), "
        "controllers.yaml, a launch file, a ros_gz_bridge YAML for every sensor topic and a world",
    )
    _add_input_options(comp)
    out = comp.add_argument_group("output")
    out.add_argument(
        "--mesh-paths",
        choices=[m.value for m in PathMode],
        default="relative",
        help="how mesh paths are written: relative to the output file (default, portable), absolute, "
        "package:// where the input used a package, or keep exactly as written",
    )
    ps = comp.add_argument_group("passes (see docs/passes.md)")
    ps.add_argument(
        "--preset",
        choices=["isaac_sim", "ros2", "gazebo", "mujoco", "quad_sdk"],
        help="a named set of passes for a target or a workflow",
    )
    ps.add_argument(
        "--rename",
        action="append",
        default=[],
        metavar="SPEC",
        help="rename joints: OLD=NEW, re:PATTERN=REPLACEMENT; prefix link: to rename links (repeatable, first match wins)",
    )
    ps.add_argument(
        "--armature",
        action="append",
        default=[],
        metavar="REGEX=VALUE",
        help="reflected rotor inertia (kg·m²) for joints matching REGEX, or REGEX=J_ROTOR*N^2 (repeatable, first match wins)",
    )
    ps.add_argument(
        "--strip",
        metavar="KINDS",
        help="remove gazebo,transmission,ros2_control,dont_collapse,contact,surface (comma list, or all)",
    )
    ps.add_argument(
        "--repair-inertia",
        choices=["geometry", "quad_sdk", "off"],
        help="repair missing/invalid inertials: from geometry, or by Quad-SDK's constants",
    )
    ps.add_argument(
        "--sanitize-names",
        action="store_true",
        default=None,
        help="make every name a valid USD/Isaac identifier (originals kept as displayName)",
    )
    ps.add_argument(
        "--unique-materials",
        action="store_true",
        default=None,
        help="one uniquely named material per distinct colour/texture",
    )
    ps.add_argument(
        "--merge-fixed",
        action="store_true",
        default=None,
        help="lump fixed-joint children into their parents (kept as fixed frames; dont_collapse respected)",
    )
    ps.add_argument(
        "--copy-meshes", action="store_true", default=None, help="copy meshes into a meshes/ folder next to the output"
    )
    sdf = comp.add_argument_group("SDF (-t sdf)")
    sdf.add_argument(
        "--sdf-version",
        choices=["1.7", "1.9", "1.10", "1.11"],
        help="SDF version (default 1.10; 1.11 keeps mimic joints; 1.9 for older libsdformat)",
    )
    sdf.add_argument(
        "--world", action="store_true", help="wrap the model in a world with ground plane, physics and light"
    )
    sdf.add_argument(
        "--gazebo-classic",
        action="store_true",
        help="Gazebo Classic plugins (libgazebo_ros_*) instead of Harmonic's gz-sim systems",
    )
    sim = comp.add_argument_group("simulation (SDF, USD, Isaac)")
    sim.add_argument(
        "--fix-base",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="weld the root link to the world, or float it with --no-fix-base (defaults: SDF floats, "
        "USD/Isaac fix, as their importers do; a composition's own choice wins)",
    )
    isaac = comp.add_argument_group("USD and Isaac Sim (-t usd, --isaac-sim; see docs/isaac.md)")
    isaac.add_argument("--drive-type", choices=["force", "acceleration"], help="joint drive type (default force)")
    isaac.add_argument(
        "--target-type",
        choices=["none", "position", "velocity"],
        help="drive target (default position; none = passive joints, gains 0)",
    )
    isaac.add_argument(
        "--stiffness",
        action="append",
        metavar="VALUE|REGEX=VALUE",
        help="drive stiffness in SI (N·m/rad, N/m), one number or rules (repeatable, first match wins); written per degree in USD",
    )
    isaac.add_argument(
        "--damping",
        action="append",
        metavar="VALUE|REGEX=VALUE",
        help="drive damping in SI (N·m·s/rad, N·s/m), like --stiffness",
    )
    isaac.add_argument(
        "--collision-approximation",
        choices=["convexHull", "convexDecomposition", "boundingCube", "boundingSphere", "none"],
        help="how mesh colliders are approximated (default convexHull)",
    )
    isaac.add_argument(
        "--self-collision", action="store_true", default=None, help="collide the robot's links with each other"
    )
    isaac.add_argument(
        "--solver-position-iterations", type=int, metavar="N", help="PhysX articulation position iterations"
    )
    isaac.add_argument(
        "--solver-velocity-iterations", type=int, metavar="N", help="PhysX articulation velocity iterations"
    )
    isaac.add_argument(
        "--contact-offset",
        type=float,
        metavar="M",
        help="PhysX contact offset on every collider (default PhysX's ~2 cm)",
    )
    isaac.add_argument("--rest-offset", type=float, metavar="M", help="PhysX rest offset on every collider")
    isaac.add_argument(
        "--merge-fixed-joints",
        action="store_true",
        default=None,
        help="importer setting: merge fixed joints on URDF import (dont_collapse keeps marked bodies)",
    )
    isaac.add_argument(
        "--layered",
        action="store_true",
        default=None,
        help="USD as an interface layer + payload (like NVIDIA's converter) instead of one file",
    )
    isaac.add_argument(
        "--physics-scene",
        action="store_true",
        default=None,
        help="add a /PhysicsScene beside the robot (outside the default prim)",
    )
    isaac.add_argument("--init-pos", metavar="X,Y,Z", help="Isaac Lab spawn position of the base (m)")
    isaac.add_argument(
        "--init-joint-pos",
        action="append",
        metavar="REGEX=VALUE",
        help="Isaac Lab initial joint positions (rad; repeatable, first match wins)",
    )
    isaac.add_argument(
        "--isaac-lab-version",
        choices=["3", "2"],
        help="Isaac Lab the generated module targets (default 3: quaternions x,y,z,w and joint_*_limit; "
        "2: w,x,y,z and *_limit_sim)",
    )
    ros2 = comp.add_argument_group("ROS 2 (--ros2)")
    ros2.add_argument(
        "--command-interface",
        choices=["position", "velocity", "effort"],
        help="what the controllers command (default position)",
    )
    ros2.add_argument(
        "--controller",
        choices=["joint_trajectory", "forward_command"],
        help="the command controller (default joint_trajectory)",
    )
    val = comp.add_argument_group("validation")
    val.add_argument(
        "--validate",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="load the output in an independent consumer (MuJoCo for URDF, Drake for SDF, usd-core's UsdPhysics parser for USD, plus mujoco-usd when "
        "installed) and compare masses, inertias, joints, limits and forward kinematics with the IR (default: on)",
    )
    val.add_argument("--report", metavar="FILE.md", help="also write the validation report as Markdown")
    comp.add_argument(
        "--json", action="store_true", help="print a JSON summary (findings, files, validation) on standard output"
    )
    comp.add_argument("-q", "--quiet", action="store_true", help="print errors only")
    comp.add_argument(
        "-v", "--verbose", action="store_true", help="list every finding (informational ones too), not one per kind"
    )

    from robodesc.batch.command import add_batch_parser

    add_batch_parser(sub, comp)  # takes compile's own options

    insp = sub.add_parser(
        "inspect",
        help="show a robot's tree, DOF, mass and findings",
        description="Load INPUT and describe it: kinematic tree, degrees of freedom, total mass and every finding.",
    )
    insp.add_argument("input")
    _add_input_options(insp)
    insp.add_argument("--json", action="store_true", help="machine-readable output")

    valp = sub.add_parser(
        "validate",
        help="compile a robot in memory and check the result in an independent consumer",
        description="Load INPUT (URDF, .xacro, .yaml, .holo), emit the target in memory, load it in MuJoCo "
        "(URDF), Drake (SDF) or mujoco-usd (USD), and compare masses, COMs, inertias, joint types, axes, "
        "limits and forward kinematics at random configurations with the IR; then step a short simulation "
        "under gravity. Exit 1 when a check fails.",
    )
    valp.add_argument("input")
    valp.add_argument("-t", "--target", choices=sorted(TARGETS), default="urdf")
    _add_input_options(valp)
    valp.add_argument("--report", metavar="FILE.md", help="write the report as Markdown")
    valp.add_argument("--json", action="store_true", help="print the report as JSON")

    exp = sub.add_parser(
        "expand",
        help="print the URDF a .xacro expands to",
        description="Expand a .xacro file and print the URDF; line numbers in robodesc's messages about xacro input refer to this text.",
    )
    exp.add_argument("input")
    _add_package_and_arg(exp)
    _add_view_parsers(sub)  # robodesc view / render / inspect --html (the block after COMMANDS)
    for sp in (comp, insp, valp, exp):
        sp.add_argument(
            "--debug", action="store_true", default=argparse.SUPPRESS, help="show the traceback of an internal error"
        )
    return parser


def _common_options(args: argparse.Namespace) -> dict[str, Any]:
    return {
        "package_paths": dict(args.package),
        "xacro_args": dict(args.arg),
        "missing_mesh": args.missing_mesh,
        "invalid_inertia": args.invalid_inertia,
        "strict": args.strict,
        "trust_xacro": args.trust_xacro,
        "allowed_env": tuple(args.env),
    }


# ---- printing --------------------------------------------------------------------------------
def _path(path: str | None) -> str:
    """A path as the user should read it: relative to the working directory when that is shorter."""
    if not path:
        return path or ""
    suffix = ""
    if path.endswith(" (expanded)"):
        path, suffix = path.removesuffix(" (expanded)"), " (expanded)"
    if os.path.isabs(path):
        rel = os.path.relpath(path)
        if len(rel) < len(path):
            path = rel
    return path + suffix


def _render(f: Finding, severity: Severity | None = None) -> str:
    loc = f.loc
    if loc is not None and loc.file:
        loc = SourceLoc(_path(loc.file), loc.line, loc.column)
    where = f"{loc}: " if loc is not None else ""
    what = f"{f.element}: " if f.element else ""
    return f"{(severity or f.severity).value}: {where}{what}{f.message}"


def _finding_dict(f: Finding) -> dict[str, object]:
    from robodesc.advice import advice_for

    out = f.as_dict()
    if out.get("file"):
        out["file"] = _path(str(out["file"]))
    advice = advice_for(f.code)
    if advice is not None and f.severity is not Severity.INFO:
        out["consumers"] = advice.consumers
        out["repair"] = advice.repair
    return out


def _print_findings(findings: Sequence[Finding], quiet: bool, verbose: bool = False) -> None:
    """Warnings grouped by kind: a count, one example, what consumers do and what repairs it.
    ``verbose`` lists every finding, informational ones too; ``quiet`` prints none."""
    if quiet:
        return
    if verbose:
        for f in findings:
            print(_render(f), file=sys.stderr)
        return
    from robodesc.advice import advice_for

    groups: dict[str, list[Finding]] = defaultdict(list)
    for f in findings:
        if f.severity is Severity.WARNING:
            groups[f.code].append(f)
    for code, items in groups.items():
        more = f" (and {len(items) - 1} more {code}; -v lists them)" if len(items) > 1 else ""
        print(_render(items[0]) + more, file=sys.stderr)
        advice = advice_for(code)
        if advice is not None:
            repair = f" Repair: {advice.repair}." if advice.repair else ""
            print(f"  -> {advice.consumers}.{repair}", file=sys.stderr)


def _report_error(err: RobodescError) -> int:
    if isinstance(err, VerificationError):
        for f in err.findings:
            print(_render(f, Severity.ERROR), file=sys.stderr)
        codes = {f.code for f in err.findings}
        if codes & {"bad-mass", "bad-inertia"}:
            print(
                "hint: --invalid-inertia repair fixes these from geometry; --invalid-inertia warn passes them through",
                file=sys.stderr,
            )
        if err.__class__.__name__ == "StrictError":
            print("hint: --strict turned these warnings into errors; without it the output is written", file=sys.stderr)
    else:
        loc = err.loc
        if loc is not None and loc.file:
            loc = SourceLoc(_path(loc.file), loc.line, loc.column)
        where = f"{loc}: " if loc is not None else ""
        what = f"{err.element}: " if err.element else ""
        print(f"error: {where}{what}{err.message}", file=sys.stderr)
    return err.exit_code


def _error_dicts(err: BaseException) -> list[dict[str, object]]:
    if isinstance(err, VerificationError):
        return [{**_finding_dict(f), "severity": "error"} for f in err.findings]
    if isinstance(err, RobodescError):
        loc = err.loc
        return [
            {
                "severity": "error",
                "code": type(err).__name__,
                "message": err.message,
                "element": err.element,
                "file": _path(loc.file) if loc and loc.file else None,
                "line": loc.line if loc else None,
                "column": loc.column if loc else None,
            }
        ]
    return [{"severity": "error", "code": type(err).__name__, "message": str(err)}]


def _summary_line(result: Any, target: str, out: str | None) -> str:
    robot = result.robot
    where = _path(out) if out else "standard output"
    mass = robot.total_mass()
    head = (
        f"robodesc: {target} {where}: {len(robot.links)} links, {len(robot.joints)} joints, "
        f"{robot.dof} DOF, {mass:.4g} kg"
    )
    return f"{head}; {_verdict(result)}"


# The numbers validation compares with the source, and their units (simulation metrics such as
# penetration are not errors against the source and are left to the full table).
_COMPARED = {
    "fk_position": " m",
    "fk_rotation": " rad",
    "com": " m",
    "mass": " (relative)",
    "inertia": " (relative)",
    "axis": "",
    "limit": "",
}


def _verdict(result: Any) -> str:
    report = result.validation
    if report is None:
        return "not validated (--no-validate)"
    consumer = getattr(report, "consumer", "")
    unloaded = next((c for c in report.checks if c.message.startswith("not loaded: ")), None)
    if unloaded is not None:  # the consumer cannot take this model at all (MuJoCo's depth limit)
        return f"not validated by {consumer}: {unloaded.message.removeprefix('not loaded: ').split(';')[0]}"
    largest = sorted(((v, k) for k, v in report.max_errors.items() if v is not None and k in _COMPARED), reverse=True)[
        :2
    ]
    errors = ", ".join(f"{k} {v:.2g}{_COMPARED[k]}" for v, k in largest)
    state = "passed" if report.ok else "FAILED"
    extra = []
    if result.source_failures:
        extra.append(f"{len(result.source_failures)} source defect(s) the consumer refused, listed as warnings")
    if errors:
        extra.append(f"largest errors: {errors}")
    return f"validation by {consumer} {state}" + (f" ({'; '.join(extra)})" if extra else "")


class _Progress:
    """A spinner on standard error for steps that take more than about two seconds (a large xacro,
    many meshes, validation); nothing at all when standard error is not a terminal."""

    DELAY = 2.0

    def __init__(self, enabled: bool) -> None:
        self.console: Any = None
        if enabled:
            from rich.console import Console

            console = Console(stderr=True)
            if console.is_terminal:
                self.console = console
        self.step = ""
        self.status: Any = None
        self.timer: threading.Timer | None = None
        self.lock = threading.Lock()

    def __call__(self, step: str) -> None:
        if self.console is None:
            return
        with self.lock:
            self.step = step
            if self.status is not None:
                self.status.update(f"robodesc: {step}")
            elif self.timer is None:
                self.timer = threading.Timer(self.DELAY, self._show)
                self.timer.daemon = True
                self.timer.start()

    def _show(self) -> None:
        with self.lock:
            if self.console is None or self.timer is None:
                return
            self.status = self.console.status(f"robodesc: {self.step}")
            self.status.start()

    def stop(self) -> None:
        with self.lock:
            if self.timer is not None:
                self.timer.cancel()
                self.timer = None
            if self.status is not None:
                self.status.stop()
                self.status = None


def _gains(values: list[str] | None, flag: str) -> float | dict[str, float] | None:
    """``--stiffness 100`` or ``--stiffness 'knee.*=50' --stiffness '.*=20'``."""
    if not values:
        return None
    if len(values) == 1 and "=" not in values[0]:
        return _number(values[0], flag)
    table: dict[str, float] = {}
    for item in values:
        pattern, sep, value = item.rpartition("=")
        if not sep or not pattern:
            raise ConfigError(f"{flag} {item!r}: expected a number or REGEX=VALUE")
        table[pattern] = _number(value, flag)
    return table


def _number(text: str, flag: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise ConfigError(f"{flag} {text!r}: expected a number") from None


def _target_options(args: argparse.Namespace) -> dict[str, Any]:
    """Only the flags the user set, so every option class keeps its own defaults."""
    init_pos = None
    if args.init_pos:
        parts = args.init_pos.split(",")
        if len(parts) != 3:
            raise ConfigError(f"--init-pos {args.init_pos!r}: expected X,Y,Z")
        init_pos = tuple(_number(p, "--init-pos") for p in parts)
    joint_pos = _gains(args.init_joint_pos, "--init-joint-pos")
    given = {
        "drive_type": args.drive_type,
        "target_type": args.target_type,
        "stiffness": _gains(args.stiffness, "--stiffness"),
        "damping": _gains(args.damping, "--damping"),
        "collision_approximation": args.collision_approximation,
        "self_collision": args.self_collision,
        "solver_position_iterations": args.solver_position_iterations,
        "solver_velocity_iterations": args.solver_velocity_iterations,
        "contact_offset": args.contact_offset,
        "rest_offset": args.rest_offset,
        "merge_fixed_joints": args.merge_fixed_joints,
        "layered": args.layered,
        "physics_scene": args.physics_scene,
        "init_pos": init_pos,
        "init_joint_pos": {".*": joint_pos} if isinstance(joint_pos, float) else joint_pos,
        "isaac_lab_version": args.isaac_lab_version,
        "version": args.sdf_version,
        "world": args.world or None,
        "flavour": "classic" if args.gazebo_classic else None,
        "fix_base": args.fix_base,
        "command_interface": args.command_interface,
        "controller": args.controller,
    }
    return {k: v for k, v in given.items() if v is not None}


def _pass_options(args: argparse.Namespace) -> dict[str, Any]:
    given: dict[str, Any] = {
        "rename": args.rename or None,
        "armature": args.armature or None,
        "strip": args.strip,
        "repair_inertia": args.repair_inertia,
        "sanitize_names": args.sanitize_names,
        "unique_materials": args.unique_materials,
        "merge_fixed": args.merge_fixed,
        "copy_meshes": args.copy_meshes,
    }
    return {k: v for k, v in given.items() if v is not None}


def _accepted(target: str) -> set[str]:
    import dataclasses

    cls = target_options_class(target)
    return {f.name for f in dataclasses.fields(cls)} if cls is not None else set()


def _json_doc(
    command: str,
    exit_code: int,
    *,
    target: str | None = None,
    output: str | None = None,
    result: Any = None,
    errors: list[dict[str, object]] | None = None,
    report: Any = None,
) -> dict[str, Any]:
    """The one JSON document every exit path prints with --json."""
    doc: dict[str, Any] = {
        "command": command,
        "ok": exit_code == 0,
        "exit_code": exit_code,
        "target": target,
        "output": _path(output) if output else None,
        "files": {},
        "summary": None,
        "findings": [],
        "errors": errors or [],
        "validation": None,
    }
    if result is not None:
        robot = result.robot
        doc["files"] = {role: _path(p) for role, p in result.files.items()}
        doc["summary"] = {
            "robot": robot.name,
            "links": len(robot.links),
            "joints": len(robot.joints),
            "dof": robot.dof,
            "mass": robot.total_mass(),
            "validation": _verdict(result),
        }
        doc["findings"] = [_finding_dict(f) for f in result.findings]
        report = report if report is not None else result.validation
    if report is not None:
        doc["validation"] = json.loads(report.to_json())
    return doc


def _compile_options(args: argparse.Namespace) -> CompileOptions:
    """The compile flags as options (every target's: each target keeps its own)."""
    opts = build_options({**_common_options(args), "mesh_paths": args.mesh_paths, "preset": args.preset})
    opts.target_options = _target_options(args)
    opts.passes = _pass_options(args)
    opts.validate = args.validate
    return opts


def _cmd_compile(args: argparse.Namespace) -> int:
    from robodesc.pipeline import ValidationFailedError, check_output

    opts = _compile_options(args)
    target = "isaac" if args.isaac_sim else "ros2" if args.ros2 else args.target
    # Each target takes only its own options.
    opts.target_options = {k: v for k, v in opts.target_options.items() if k in _accepted(target)}
    args.json_target, args.json_output = target, args.output
    if args.report:
        check_output(args.report, folder=False, source=args.input, what="--report")
        if args.output and os.path.abspath(args.report) == os.path.abspath(args.output):
            raise ConfigError(f"--report {args.report}: is also the output (-o); give another file")
    opts.validate = args.validate
    progress = _Progress(not args.quiet and not args.json)
    try:
        result = compile_robot(args.input, target, args.output, opts, progress)
    except ValidationFailedError as failed:
        progress.stop()
        return _validation_failed(args, target, failed.result)
    finally:
        progress.stop()
    report = result.validation
    if args.report and report is not None:
        from robodesc.emit.common.files import write_atomic

        write_atomic(args.report, report.to_markdown())
    if args.json:
        print(json.dumps(_json_doc("compile", 0, target=target, output=args.output, result=result), indent=2))
        return 0
    _print_findings(result.findings, args.quiet, args.verbose)
    if args.output is None and result.text is not None:
        sys.stdout.write(result.text)
    if report is not None and args.verbose:
        print(report.to_text(), file=sys.stderr)
    if not args.quiet:
        print(_summary_line(result, target, args.output), file=sys.stderr)
    return 0


def _validation_failed(args: argparse.Namespace, target: str, result: Any) -> int:
    """Exit 1: the output differs from the source because of robodesc. Nothing was written; the
    full table is printed (and written to --report)."""
    report = result.validation
    if args.report:
        from robodesc.emit.common.files import write_atomic

        write_atomic(args.report, report.to_markdown())
    if args.json:
        errors = [
            {"severity": "error", "code": f"validation:{c.name}", "message": c.message, "element": c.element}
            for c in report.failures
        ]
        doc = _json_doc("compile", 1, target=target, output=args.output, result=result, errors=errors)
        doc["files"] = {}
        print(json.dumps(doc, indent=2))
        return 1
    _print_findings(result.findings, args.quiet, args.verbose)
    print(report.to_text(), file=sys.stderr)
    print(
        f"error: the output failed validation ({len(report.failures)} check(s) above); nothing was written. "
        "This is robodesc's fault: please report it. --no-validate writes the output anyway",
        file=sys.stderr,
    )
    return 1


def _cmd_validate(args: argparse.Namespace) -> int:
    import tempfile

    from robodesc.pipeline import ValidationFailedError

    lower = args.input.lower()
    if lower.endswith((".sdf", ".usd", ".usda", ".usdc")):
        kind = "sdf" if lower.endswith(".sdf") else "usd"
        raise ConfigError(
            f"{args.input}: robodesc validates an output against the robot it was compiled from; "
            f"run: robodesc validate SOURCE -t {kind}"
        )
    if args.report:
        from robodesc.pipeline import check_output

        check_output(args.report, folder=False, source=args.input, what="--report")
    opts = build_options(_common_options(args))
    args.json_target = args.target
    with tempfile.TemporaryDirectory(prefix="robodesc-validate-") as tmp:
        spec_folder = args.target in ("isaac", "ros2")
        out = f"{tmp}/robot" + ("" if spec_folder else f".{'usda' if args.target == 'usd' else args.target}")
        code = 0
        try:
            result = compile_robot(args.input, args.target, out, opts)
        except ValidationFailedError as failed:
            result, code = failed.result, 1
        report = result.validation
        if report is None:
            raise ConfigError(f"target {args.target!r} has nothing to validate")
        if args.report:
            from robodesc.emit.common.files import write_atomic

            write_atomic(args.report, report.to_markdown())
        if args.json:
            doc = _json_doc("validate", code, target=args.target, result=result)
            doc["files"] = {}
            print(json.dumps(doc, indent=2))
        else:
            _print_findings(result.findings, quiet=False)
            print(report.to_text())
    return code


def _cmd_inspect(args: argparse.Namespace) -> int:
    from robodesc.inspect_robot import describe

    opts = build_options(_common_options(args))
    report = describe(args.input, opts)
    if args.json:
        print(json.dumps(report.as_dict(), indent=2))
    else:
        sys.stdout.write(report.render())
    return 0 if report.ok else 2


def _cmd_expand(args: argparse.Namespace) -> int:
    from robodesc.frontends.packages import PackageResolver
    from robodesc.frontends.xacro_expand import expand_xacro
    from robodesc.ir.diagnostics import Findings

    findings = Findings()
    resolver = PackageResolver(explicit=dict(args.package), input_file=args.input)
    text = expand_xacro(
        args.input, dict(args.arg), resolver, findings, trust=args.trust_xacro, allowed_env=tuple(args.env)
    )
    for f in findings:
        print(_render(f), file=sys.stderr)
    sys.stdout.write(text + "\n")
    return 0


def _cmd_batch(args: argparse.Namespace) -> int:
    from robodesc.batch.command import run_command

    return run_command(args, _compile_options)


COMMANDS = {
    "compile": _cmd_compile,
    "batch": _cmd_batch,
    "expand": _cmd_expand,
    "validate": _cmd_validate,
    "inspect": _cmd_inspect,
}


# ---- view and render (robodesc.view): one block, ported as is ---------------------------------
def _add_view_parsers(sub: Any) -> None:
    from robodesc.view.views import VIEWS  # numpy-free: building the parser must not import numpy

    for name, what in (("view", "an HTML viewer page"), ("render", "a PNG picture")):
        p = sub.add_parser(
            name,
            help=f"{what} of a robot" + (" (self-contained, offline)" if name == "view" else " (MuJoCo, headless)"),
            description=(
                "Write one self-contained HTML file that shows INPUT in the browser, offline: the robot at its "
                "home pose, the kinematic tree, a slider per joint, colliders, frames, axes, centres of mass, "
                "inertia boxes, robodesc's findings linked to their links and, with --target, what the passes "
                "repaired (before and after). docs/view.md"
                if name == "view"
                else "Render INPUT to a PNG with MuJoCo's offscreen renderer (EGL or OSMesa: no display or GPU "
                "needed), the camera framing the robot. docs/view.md"
            ),
        )
        p.add_argument("input")
        p.add_argument("-o", "--output", required=True, metavar="FILE.html" if name == "view" else "FILE.png")
        p.add_argument(
            "-t",
            "--target",
            choices=sorted(TARGETS),
            help="show the robot as compiled for this target, after its passes (with their repairs)",
        )
        p.add_argument("--preset", help="the passes' preset (with --target), as for compile")
        if name == "render":
            p.add_argument("--view", choices=list(VIEWS), default="iso", help="camera direction (default iso)")
            p.add_argument("--size", default="800x600", metavar="WxH", help="image size in pixels (default 800x600)")
            p.add_argument("--grid", action="store_true", help="front, side, top and iso in a 2x2 grid")
            p.add_argument("--collision", action="store_true", help="draw the colliders only")
        _add_input_options(p)
        p.add_argument(
            "--debug", action="store_true", default=argparse.SUPPRESS, help="show the traceback of an internal error"
        )
    sub.choices["inspect"].add_argument(
        "--html", metavar="FILE.html", help="also write the viewer page (robodesc view) to FILE.html"
    )


def _view_options(args: argparse.Namespace) -> CompileOptions:
    return build_options({**_common_options(args), "preset": getattr(args, "preset", None)})


def _cmd_view(args: argparse.Namespace) -> int:
    from robodesc.view import write_view_html

    page = write_view_html(args.input, args.output, options=_view_options(args), target=args.target)
    print(
        f"robodesc: {_path(page.path)}: {page.links} links, {page.meshes} meshes, {page.findings} findings, "
        f"{page.repairs} repairs; {page.bytes / 1e6:.1f} MB in {page.seconds:.2f} s",
        file=sys.stderr,
    )
    return 0


def _cmd_render(args: argparse.Namespace) -> int:
    from robodesc.view.render import parse_size, render_png

    done = render_png(
        args.input,
        args.output,
        view=args.view,
        size=parse_size(args.size),
        grid_views=args.grid,
        collision=args.collision,
        options=_view_options(args),
        target=args.target,
    )
    for why in done.skipped:
        print(f"warning: not drawn: {why}", file=sys.stderr)
    print(
        f"robodesc: {_path(done.path)}: {done.width}x{done.height} ({done.backend}) in {done.seconds:.2f} s",
        file=sys.stderr,
    )
    return 0


def _cmd_inspect_or_view(args: argparse.Namespace) -> int:
    code = _cmd_inspect(args)
    if getattr(args, "html", None):
        from robodesc.view import write_view_html

        write_view_html(args.input, args.html, options=build_options(_common_options(args)))
    return code


COMMANDS.update(view=_cmd_view, render=_cmd_render, inspect=_cmd_inspect_or_view)
# ---- end of view and render ---------------------------------------------------------------------


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    # usd-core prints a banner when PXR_WORK_THREAD_LIMIT is set; this turns such alerts off.
    os.environ.setdefault("TF_ENV_SETTING_ALERTS_ENABLED", "0")
    want_json = "--json" in argv
    debug = "--debug" in argv
    command = next((a for a in argv if a in COMMANDS), "")
    parser = _parser()
    try:
        args = parser.parse_args(argv)
    except _UsageError as exc:
        if want_json:
            doc = _json_doc(command, 2, errors=[{"severity": "error", "code": "usage", "message": str(exc)}])
            print(json.dumps(doc, indent=2))
        else:
            print(
                f"error: {exc} (robodesc {command or ''} --help lists the options)".replace("  ", " "), file=sys.stderr
            )
        return 2
    if args.command is None:
        parser.print_help()
        return 2
    want_json = bool(getattr(args, "json", False))

    def fail(code: int, errors: list[dict[str, object]]) -> int:
        if want_json:
            doc = _json_doc(
                args.command,
                code,
                target=getattr(args, "json_target", None),
                output=getattr(args, "json_output", None),
                errors=errors,
            )
            print(json.dumps(doc, indent=2))
        return code

    try:
        return COMMANDS[args.command](args)
    except RobodescError as err:
        code = err.exit_code if want_json else _report_error(err)
        return fail(code, _error_dicts(err))
    except KeyboardInterrupt:
        print("error: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the reader (| head) went away: not an error of ours
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except OSError as exc:
        # The environment: a full disk, a permission changed mid-run, a vanished folder.
        where = f"{_path(exc.filename)}: " if getattr(exc, "filename", None) else ""
        message = f"{where}{exc.strerror or exc}"
        if not want_json:
            print(f"error: {message}", file=sys.stderr)
        return fail(2, [{"severity": "error", "code": "environment", "message": message}])
    except (RecursionError, MemoryError) as exc:
        what = "too deeply nested" if isinstance(exc, RecursionError) else "too large for the memory available"
        message = f"{_path(getattr(args, 'input', ''))}: the input is {what}"
        if not want_json:
            print(f"error: {message}", file=sys.stderr)
        return fail(2, [{"severity": "error", "code": type(exc).__name__, "message": message}])
    except Exception as exc:  # the last line of defence: one line, exit 3
        message = f"{type(exc).__name__}: {exc}".strip()
        if not want_json:
            print(
                f"robodesc bug: {message.splitlines()[0][:300]} -- this is an internal error, not a problem "
                "with your input; please report it (--debug shows the traceback)",
                file=sys.stderr,
            )
        if debug:
            import traceback

            traceback.print_exc()
        return fail(3, [{"severity": "error", "code": "internal", "message": message}])


def tune_gc() -> None:
    """Make the cyclic garbage collector run less often, for a process that compiles and exits.

    A compile allocates millions of small objects (the IR, lxml proxies, findings) and frees few
    cycles, so the default threshold of 700 allocations has the collector walk the growing heap
    again and again: about a sixth of a 20,000-link chain's time. Objects alive after the imports
    are moved out of its sight (``gc.freeze``). Only the console script calls it: a long-lived
    process that imports robodesc keeps its own collector settings."""
    import gc

    gc.freeze()
    gc.set_threshold(100_000, 50, 100)


def run() -> NoReturn:
    """The ``robodesc`` console script: :func:`main`, then exit without the interpreter's teardown.

    Every output is written and closed (atomically) before ``main`` returns, so tearing down the
    loaded modules (numpy, lxml, usd-core when validating) would only cost 20-40 ms of each run."""
    tune_gc()
    code = main()
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except BrokenPipeError:
        pass
    os._exit(code)


if __name__ == "__main__":
    run()
