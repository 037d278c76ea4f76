"""``robodesc`` on the command line: a thin layer over :mod:`robodesc.api`.

Bad input never shows a traceback: each problem is one line ``error: file:line: element: what``,
and the exit code is 2 (1 when a validation check fails).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Sequence
from typing import Any, NoReturn

from robodesc._version import __version__
from robodesc.emit.common.paths import PathMode
from robodesc.frontends.options import MissingMesh
from robodesc.ir.diagnostics import ConfigError, Finding, RobodescError, Severity, VerificationError
from robodesc.options import InvalidInertia, build_options
from robodesc.pipeline import TARGETS, compile_robot, target_options_class

EPILOG = """\
examples:
  robodesc compile robot.urdf.xacro -t urdf -o out/robot.urdf --package my_pkg=src/my_pkg
  robodesc compile go2.urdf.xacro -t urdf -o go2.urdf --missing-mesh warn --invalid-inertia repair
  robodesc inspect robot.urdf
exit codes: 0 ok, 1 validation failed, 2 bad input or options
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


def _add_input_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("input")
    _add_package_and_arg(g)
    g.add_argument(
        "--missing-mesh",
        choices=[m.value for m in MissingMesh],
        default="error",
        help="a mesh file that does not exist: fail (error, default), keep the reference (warn), "
        "substitute a box of its scale (primitive) or drop that visual/collision (drop)",
    )
    g.add_argument(
        "--invalid-inertia",
        choices=[m.value for m in InvalidInertia],
        default="error",
        help="physically invalid mass or inertia in the source (mass <= 0, a tensor that is not positive "
        "definite or breaks the triangle inequality): fail (error, default), pass through (warn), or "
        "repair from geometry and report each repair (repair)",
    )
    g.add_argument("--strict", action="store_true", help="unknown elements are errors instead of being kept verbatim")


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="robodesc",
        description="Compile robot descriptions: URDF/xacro and compositions to URDF, SDF and Isaac-ready USD.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--version", action="version", version=f"robodesc {__version__}")
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
    return parser


def _common_options(args: argparse.Namespace) -> dict[str, Any]:
    return {
        "package_paths": dict(args.package),
        "xacro_args": dict(args.arg),
        "missing_mesh": args.missing_mesh,
        "invalid_inertia": args.invalid_inertia,
        "strict": args.strict,
    }


def _print_findings(findings: Sequence[Finding], quiet: bool) -> None:
    for f in findings:
        if quiet and f.severity is not Severity.ERROR:
            continue
        print(f.render(), file=sys.stderr)


def _report_error(err: RobodescError) -> int:
    if isinstance(err, VerificationError):
        for line in err.render_all():
            print(f"error: {line}", file=sys.stderr)
        codes = {f.code for f in err.findings}
        if codes & {"bad-mass", "bad-inertia"}:
            print(
                "hint: --invalid-inertia repair fixes these from geometry; --invalid-inertia warn passes them through",
                file=sys.stderr,
            )
    else:
        print(f"error: {err.render()}", file=sys.stderr)
    return err.exit_code


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


def _cmd_compile(args: argparse.Namespace) -> int:
    opts = build_options({**_common_options(args), "mesh_paths": args.mesh_paths, "preset": args.preset})
    opts.target_options = _target_options(args)
    opts.passes = _pass_options(args)
    target = "isaac" if args.isaac_sim else "ros2" if args.ros2 else args.target
    # Each target takes only its own options.
    opts.target_options = {k: v for k, v in opts.target_options.items() if k in _accepted(target)}

    def progress(step: str) -> None:
        if not args.quiet and not args.json:
            print(f"robodesc: {step}", file=sys.stderr)

    opts.validate = args.validate
    result = compile_robot(args.input, target, args.output, opts, progress)
    report = result.validation
    if args.report and report is not None:
        from robodesc.emit.common.files import write_atomic

        write_atomic(args.report, report.to_markdown())
    if args.json:
        summary: dict[str, Any] = {
            "target": result.target,
            "files": result.files,
            "findings": [f.as_dict() for f in result.findings],
            "validation": json.loads(report.to_json()) if report is not None else None,
        }
        print(json.dumps(summary, indent=2))
    else:
        _print_findings(result.findings, args.quiet)
        if args.output is None and result.text is not None:
            sys.stdout.write(result.text)
        elif not args.quiet:
            for role, path in result.files.items():
                print(f"robodesc: wrote {role}: {path}", file=sys.stderr)
        if report is not None and (not args.quiet or not report.ok):
            print(report.to_text(), file=sys.stderr)
    if report is not None and not report.ok:
        print("error: the output failed validation (see the report above); --no-validate skips it", file=sys.stderr)
        return 1
    return 0


def _cmd_validate(args: argparse.Namespace) -> int:
    import tempfile

    lower = args.input.lower()
    if lower.endswith((".sdf", ".usd", ".usda", ".usdc")):
        kind = "sdf" if lower.endswith(".sdf") else "usd"
        print(
            f"error: {args.input}: robodesc validates an output against the robot it was compiled from; "
            f"run: robodesc validate SOURCE -t {kind}",
            file=sys.stderr,
        )
        return 2
    opts = build_options(_common_options(args))
    with tempfile.TemporaryDirectory(prefix="robodesc-validate-") as tmp:
        out = f"{tmp}/robot.{'usda' if args.target == 'usd' else args.target}"
        result = compile_robot(args.input, args.target, out, opts)
        report = result.validation
        if report is None:
            print("error: nothing to validate", file=sys.stderr)
            return 2
        if args.report:
            from robodesc.emit.common.files import write_atomic

            write_atomic(args.report, report.to_markdown())
        if args.json:
            print(report.to_json())
        else:
            _print_findings(result.findings, quiet=True)
            print(report.to_text())
    return 0 if report.ok else 1


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
    text = expand_xacro(args.input, dict(args.arg), resolver, findings)
    _print_findings(list(findings), False)
    sys.stdout.write(text + "\n")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 2
    try:
        if args.command == "compile":
            return _cmd_compile(args)
        if args.command == "expand":
            return _cmd_expand(args)
        if args.command == "validate":
            return _cmd_validate(args)
        return _cmd_inspect(args)
    except RobodescError as err:
        return _report_error(err)
    except KeyboardInterrupt:
        print("error: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the reader (| head) went away: not an error of ours
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


def run() -> NoReturn:
    """The ``robodesc`` console script: :func:`main`, then exit without the interpreter's teardown.

    Every output is written and closed (atomically) before ``main`` returns, so tearing down the
    loaded modules (numpy, lxml, usd-core when validating) would only cost 20-40 ms of each run."""
    code = main()
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except BrokenPipeError:
        pass
    os._exit(code)


if __name__ == "__main__":
    run()
