"""The command line's grammar: every command, its flags and their help.

A target's options come from its options dataclass (``robodesc.emit.common.flags``): adding an
option to a target is adding a field there, and the flag appears here by itself."""

from __future__ import annotations

import argparse
from typing import Any, NoReturn

from robodesc._version import __version__
from robodesc.cli.flags import add_target_flags, target_lines
from robodesc.emit.common.paths import PathMode
from robodesc.frontends.load import describe_inputs
from robodesc.frontends.options import MissingMesh
from robodesc.options import InvalidInertia
from robodesc.passes.presets import PRESETS
from robodesc.targets import DEFAULT_TARGET, TARGETS

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


def add_package_and_arg(g: argparse._ActionsContainer) -> None:
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


def add_input_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("input")
    g.add_argument(
        "--model-path",
        action="append",
        default=[],
        metavar="DIR",
        help="a folder searched for model:// URIs of an SDF model's includes and meshes and of a world "
        "(repeatable; before GZ_SIM_RESOURCE_PATH and GAZEBO_MODEL_PATH)",
    )
    g.add_argument(
        "--plugin",
        metavar="MODULE",
        action="append",
        default=[],
        help="load a Python module that adds a target (exports TARGET) or an input format (exports FRONTEND); "
        "it is code and runs (repeatable; docs/architecture.md)",
    )
    add_package_and_arg(g)
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


class UsageError(Exception):
    """argparse found a bad command line (exit 2): raised instead of exiting so --json can report it."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{self.prog}: {message}")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="robodesc",
        description=f"Compile robot descriptions ({describe_inputs()}) to {', '.join(TARGETS)}.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--version", action="version", version=f"robodesc {__version__}")
    parser.add_argument("--debug", action="store_true", help="show the traceback of an internal error")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    compile_parser = _compile_parser(sub)

    from robodesc.batch.command import add_batch_parser

    add_batch_parser(sub, compile_parser)  # takes compile's own options
    commands = [
        compile_parser,
        _layer_parser(sub),
        _inspect_parser(sub),
        _validate_parser(sub),
        _expand_parser(sub),
        *_view_parsers(sub),
    ]
    for sp in commands:
        sp.add_argument(
            "--debug", action="store_true", default=argparse.SUPPRESS, help="show the traceback of an internal error"
        )
    return parser


def _layer_parser(sub: Any) -> argparse.ArgumentParser:
    """``robodesc layer ROBOT --onto IMPORTED.usd -o physics.usda``: compile's flags (the Isaac
    ones matter), the imported USD, and the layer file."""
    lay = _compile_parser(
        sub,
        "layer",
        "write robodesc's physics as a USD layer over a robot Isaac Sim 6's importer already imported",
        "Compile INPUT as --isaac-sim does and write only its physics layer, addressed to the prims of "
        "--onto (the USD Isaac Sim 6's URDF importer wrote from that robot's URDF; docs/isaac.md). Prims the "
        "layer cannot find are named in a warning.",
    )
    lay.add_argument("--onto", required=True, metavar="IMPORTED.usd", help="the USD the importer wrote")
    lay.add_argument(
        "--stage",
        metavar="STAGE.usda",
        help="also write the stage to open: the layer sublayered over --onto, the importer's physx variant selected",
    )
    return lay


def _compile_parser(
    sub: Any,
    name: str = "compile",
    summary: str = "compile a robot description to a target",
    text: str = "",
) -> argparse.ArgumentParser:
    comp: argparse.ArgumentParser = sub.add_parser(
        name,
        help=summary,
        description=text
        or f"Compile INPUT ({describe_inputs()}) to a target format, running the verifier and the passes you select.\n\ntargets:\n{target_lines()}",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=EPILOG,
    )
    comp.add_argument("input", help=f"the robot: {describe_inputs()}")
    comp.add_argument(
        "-t",
        "--target",
        choices=list(TARGETS),
        default=DEFAULT_TARGET,
        help=f"output format (default: {DEFAULT_TARGET}; the list above says what each writes)",
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
    add_input_options(comp)
    out = comp.add_argument_group("output")
    out.add_argument(
        "--mesh-paths",
        choices=[m.value for m in PathMode],
        default="relative",
        help="how mesh paths are written: relative to the output file (default, portable), absolute, "
        "package:// where the input used a package, or keep exactly as written",
    )
    _add_pass_flags(comp)
    add_target_flags(comp)
    add_world_options(comp)
    val = comp.add_argument_group("validation")
    val.add_argument(
        "--validate",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="load the output in an independent consumer (each target names its own in the list above) and "
        "compare masses, inertias, joints, limits and forward kinematics with the IR (default: on)",
    )
    val.add_argument("--report", metavar="FILE.md", help="also write the validation report as Markdown")
    out.add_argument(
        "--preview",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="folder targets (--isaac-sim, --ros2): also write preview.png, a picture of the robot as compiled "
        "(default: on; about 1 s)",
    )
    comp.add_argument(
        "--json", action="store_true", help="print a JSON summary (findings, files, validation) on standard output"
    )
    comp.add_argument("-q", "--quiet", action="store_true", help="print errors only")
    comp.add_argument(
        "-v", "--verbose", action="store_true", help="list every finding (informational ones too), not one per kind"
    )

    return comp


def add_world_options(p: argparse.ArgumentParser, picture: bool = False) -> None:
    """The world around the robot (docs/worlds.md): read once, written by every target that can.
    ``picture``: the options ``view`` and ``render`` draw (the ground and where the robot stands)."""
    g = p.add_argument_group("world (docs/worlds.md)" + (": the robot drawn standing on its ground" if picture else ""))
    g.add_argument(
        "--world",
        nargs="?",
        const=True,
        metavar="FILE",
        help="put the robot in an SDF world (.world, .sdf): its terrain, static models and physics "
        "(-t mjcf, usd, sdf, --isaac-sim). Bare, with -t sdf: wrap the model in an empty world with a ground "
        "plane, physics and light. A world file as the INPUT instead compiles the world alone",
    )
    g.add_argument(
        "--terrain",
        metavar="FILE",
        help="put the robot on a bare terrain: a mesh (STL, PLY, OBJ, DAE) or a grey PNG height image "
        "(with --terrain-size)",
    )
    g.add_argument(
        "--terrain-size", metavar="X,Y,Z", help="a height image's extent in x and y and the height of white (m)"
    )
    g.add_argument(
        "--terrain-resolution",
        type=float,
        metavar="M",
        help="heightfield cell for targets that need one (MJCF), in metres (default 0.02)",
    )
    g.add_argument(
        "--spawn",
        metavar="X,Y[,Z]",
        action="append",
        help="where the robot stands in the world (default: the world's include of it, else the origin); "
        "without Z its height comes from the ground under its feet. Given several times: a copy of the robot "
        "at each point (MJCF, USD, SDF), each on the ground under its own feet",
    )
    if picture:
        return
    g.add_argument(
        "--cords",
        metavar="FILE.yaml",
        help="fields of compliant cords (vines) in the world: chains of capsules on spherical joints hanging "
        "from anchors (docs/worlds.md, 'Cords'); with no --world, on a plane",
    )
    g.add_argument(
        "--contact-sensors",
        nargs="?",
        const="",
        metavar="REGEX",
        help="a contact sensor on each foot robodesc finds, or on each link REGEX matches: MJCF touch, USD "
        "PhysxContactReportAPI, SDF contact sensor, Isaac Lab ContactSensorCfg",
    )


def _add_pass_flags(comp: argparse.ArgumentParser) -> None:
    ps = comp.add_argument_group("passes (see docs/passes.md)")
    ps.add_argument(
        "--preset",
        choices=list(PRESETS),
        help="a named set of passes for a target, or a workflow on top of the target's own (gazebo_parity: behave as in Gazebo; docs/contact.md)",
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
        "--default-armature",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="estimate armature from each revolute joint's effort limit where the source gives none "
        "(default: on for -t mjcf and the Isaac folder, off elsewhere; docs/passes.md)",
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
        action=argparse.BooleanOptionalAction,
        default=None,
        help="lump fixed-joint children into their parents (kept as fixed frames: sites in MJCF; dont_collapse "
        "respected). Default: on for -t mjcf, off elsewhere; --no-merge-fixed keeps them as bodies",
    )
    ps.add_argument(
        "--copy-meshes",
        action="store_true",
        default=None,
        help="copy the meshes and textures the output refers to into meshes/ next to it (-t usd: textures only, "
        "mesh geometry is embedded; -t mjcf: its folder holds its meshes without the flag)",
    )


def _inspect_parser(sub: Any) -> argparse.ArgumentParser:
    insp: argparse.ArgumentParser = sub.add_parser(
        "inspect",
        help="show a robot's tree, DOF, mass and findings",
        description="Load INPUT and describe it: kinematic tree, degrees of freedom, total mass and every finding.",
    )
    insp.add_argument("input")
    add_input_options(insp)
    insp.add_argument("--json", action="store_true", help="machine-readable output")
    insp.add_argument("-q", "--quiet", action="store_true", help="print errors only")
    insp.add_argument(
        "-v", "--verbose", action="store_true", help="list every finding (informational ones too), not one per kind"
    )

    return insp


def _validate_parser(sub: Any) -> argparse.ArgumentParser:
    valp: argparse.ArgumentParser = sub.add_parser(
        "validate",
        help="compile a robot in memory and check the result in an independent consumer",
        description=f"Load INPUT ({describe_inputs()}), compile it to the target in a temporary folder, load "
        "the output in the target's independent consumer, and compare masses, COMs, inertias, joint types, "
        "axes, limits and forward kinematics at random configurations with the IR; then step a short "
        "simulation under gravity. Exit 1 when a check fails.",
    )
    valp.add_argument("input")
    valp.add_argument(
        "-t",
        "--target",
        choices=list(TARGETS),
        default=DEFAULT_TARGET,
        help=f"the target to check (default {DEFAULT_TARGET})",
    )
    add_input_options(valp)
    add_world_options(valp)
    valp.add_argument("--report", metavar="FILE.md", help="write the report as Markdown")
    valp.add_argument("--json", action="store_true", help="print the report as JSON")
    dyn = valp.add_argument_group("dynamics (docs/dynamics.md)")
    dyn.add_argument(
        "--dynamics",
        action="store_true",
        help="also simulate on CPU: drives hold the home pose under gravity (fixed base), the floating robot "
        "dropped onto a plane, a block with the robot's friction on tilted planes; per engine, against the "
        "other engines and against the source where an engine reads it. Exit 1 when an output behaves unlike "
        "its source",
    )
    dyn.add_argument(
        "--engines",
        metavar="LIST",
        type=lambda text: tuple(e.strip() for e in text.split(",") if e.strip()),
        default=(),
        help="comma-separated engines for --dynamics: mujoco, drake, newton, physx (default: mujoco, drake and the "
        "engines that read the target: newton and physx for usd, physx for the Isaac folder; newton costs seconds "
        "to import and runs only when named or for its target)",
    )
    for name, unit in (("stiffness", "N·m/rad, N/m"), ("damping", "N·m·s/rad, N·s/m")):
        dyn.add_argument(
            f"--{name}",
            metavar="[REGEX=]VALUE",
            action="append",
            default=[],
            help=f"drive {name} for --dynamics in SI ({unit}): your controller's gains, one number or rules "
            "(repeatable, first match wins). The checked file is compiled with them when its target takes them; "
            "default: the target's own, else derived (docs/dynamics.md)",
        )
    dyn.add_argument(
        "--pose",
        metavar="REGEX=VALUE",
        action="append",
        default=[],
        help="home pose for --dynamics (rad or m, first match wins; repeatable); default 0 clamped into the limits",
    )
    dyn.add_argument(
        "--video",
        metavar="DIR",
        help="with --dynamics: write a clip per scenario the robot moves in (hold-fixed, drop) to "
        "DIR/<robot>_<scenario>.mp4, one panel per engine side by side, drawn by MuJoCo's offscreen renderer "
        "from the poses each engine reported, at half speed. MP4 needs imageio-ffmpeg (pip install "
        "'robodesc[video]'); without it a GIF is written. Files already in DIR are replaced one by one, "
        "never written through",
    )
    dyn.add_argument(
        "--video-format",
        choices=("mp4", "gif"),
        help="the clips' format for --video (default: mp4 when imageio-ffmpeg is installed, else gif)",
    )

    return valp


def _expand_parser(sub: Any) -> argparse.ArgumentParser:
    exp: argparse.ArgumentParser = sub.add_parser(
        "expand",
        help="print the URDF a .xacro expands to",
        description="Expand a .xacro file and print the URDF; line numbers in robodesc's messages about xacro input refer to this text.",
    )
    exp.add_argument("input")
    add_package_and_arg(exp)
    return exp


def _view_parsers(sub: Any) -> list[argparse.ArgumentParser]:
    """``view`` (an HTML page) and ``render`` (a PNG): robodesc.view, docs/view.md."""
    from robodesc.view.views import VIEWS  # numpy-free: building the parser must not import numpy

    made = []
    for name, what in (("view", "an HTML viewer page"), ("render", "a PNG picture")):
        p: argparse.ArgumentParser = sub.add_parser(
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
        p.add_argument("input", help=f"the robot: {describe_inputs()}")
        p.add_argument("-o", "--output", required=name == "view", metavar="FILE.html" if name == "view" else "FILE.png")
        p.add_argument(
            "-t",
            "--target",
            choices=list(TARGETS),
            help="show the robot as compiled for this target, after its passes (with their repairs)",
        )
        p.add_argument("--preset", choices=list(PRESETS), help="the passes' preset (with --target), as for compile")
        if name == "render":
            p.add_argument("--view", choices=list(VIEWS), default="iso", help="camera direction (default iso)")
            p.add_argument("--size", metavar="WxH", help="image size in pixels (default 800x600; 640x480 for --video)")
            p.add_argument("--grid", action="store_true", help="front, side, top and iso in a 2x2 grid")
            p.add_argument("--collision", action="store_true", help="draw the colliders only")
            p.add_argument(
                "--video",
                metavar="FILE.mp4",
                help="also (or instead of -o) write a clip: every driven joint swept from its home position to its "
                "lower limit, to its upper limit and back, in 4 s at 25 fps, the root still; .mp4 (needs "
                "imageio-ffmpeg: pip install 'robodesc[video]') or .gif. --size sets its frame size (default "
                "640x480, rounded down to multiples of 16)",
            )
        add_input_options(p)
        add_world_options(p, picture=True)
        made.append(p)
    sub.choices["inspect"].add_argument(
        "--html", metavar="FILE.html", help="also write the viewer page (robodesc view) to FILE.html"
    )
    return made
