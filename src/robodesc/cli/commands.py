"""The commands: each turns parsed flags into an API call and hands the result to ``render``."""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import sys
from typing import Any

import robodesc.cli.render as render
from robodesc import api
from robodesc.cli.flags import target_options
from robodesc.emit.common.staging import check_output
from robodesc.ir.diagnostics import ConfigError
from robodesc.options import CompileOptions, build_options, check_numbers
from robodesc.pipeline import CompileResult, ValidationFailedError
from robodesc.targets import target_spec


def _input_options(args: argparse.Namespace) -> dict[str, Any]:
    return {
        "package_paths": dict(args.package),
        "xacro_args": dict(args.arg),
        "missing_mesh": args.missing_mesh,
        "invalid_inertia": args.invalid_inertia,
        "strict": args.strict,
        "trust_xacro": args.trust_xacro,
        "allowed_env": tuple(args.env),
        "plugins": tuple(args.plugin),
        **({"model_path": tuple(args.model_path)} if getattr(args, "model_path", None) else {}),
    }


def _bare_world(args: argparse.Namespace) -> dict[str, Any]:
    """A bare ``--world``: SDF's empty world around the model (a target option of -t sdf)."""
    return {"world": True} if getattr(args, "world", None) is True else {}


def world_options(args: argparse.Namespace) -> dict[str, Any]:
    """``--world FILE``, ``--terrain`` and the rest, as the API's keyword options."""
    out: dict[str, Any] = {}
    world = getattr(args, "world", None)
    if isinstance(world, str):
        out["world"] = world
    if getattr(args, "terrain", None):
        out["terrain"] = args.terrain
    if getattr(args, "cords", None):
        out["cords"] = args.cords
    if getattr(args, "terrain_size", None):
        out["terrain_size"] = _numbers(args.terrain_size, "--terrain-size", (3,))
    if getattr(args, "terrain_resolution", None) is not None:
        out["terrain_resolution"] = args.terrain_resolution
    spawn = getattr(args, "spawn", None)
    if spawn:
        # --spawn may be given several times: a copy of the robot at each point.
        points = [_numbers(text, "--spawn", (2, 3)) for text in ([spawn] if isinstance(spawn, str) else spawn)]
        out["spawn"] = points[0] if len(points) == 1 else points
    if getattr(args, "contact_sensors", None) is not None:
        out["contact_sensors"] = args.contact_sensors
    return out


def _numbers(text: str, flag: str, sizes: tuple[int, ...]) -> tuple[float, ...]:
    import math

    try:
        values = tuple(float(p) for p in text.split(","))
    except ValueError:
        values = ()
    if len(values) not in sizes or not all(math.isfinite(v) for v in values):
        wanted = " or ".join(str(n) for n in sizes)
        raise ConfigError(f"{flag} {text!r}: expected {wanted} comma-separated finite numbers")
    return values


def _pass_options(args: argparse.Namespace) -> dict[str, Any]:
    given: dict[str, Any] = {
        "rename": args.rename or None,
        "armature": args.armature or None,
        "strip": args.strip,
        "repair_inertia": args.repair_inertia,
        "sanitize_names": args.sanitize_names,
        "unique_materials": args.unique_materials,
        "merge_fixed": args.merge_fixed,
        "default_armature": args.default_armature,
        "copy_meshes": args.copy_meshes,
    }
    return {k: v for k, v in given.items() if v is not None}


def _accepted(target: str) -> set[str]:
    cls = target_spec(target).options
    return {f.name for f in dataclasses.fields(cls)} if cls is not None else set()


def compile_options(args: argparse.Namespace) -> CompileOptions:
    """The compile flags as options (every target's: each target keeps its own). ``batch`` runs
    many targets from one command line, so it takes them all."""
    opts = build_options(
        {**_input_options(args), **world_options(args), "mesh_paths": args.mesh_paths, "preset": args.preset}
    )
    # Every robot of a batch in the same world (--world FILE ...); a bare --world is SDF's own.
    opts.target_options = {**target_options(args), **_bare_world(args)}
    opts.passes = _pass_options(args)
    opts.validate = args.validate
    return opts


def compile_target(args: argparse.Namespace) -> str:
    """The target a compile command line names: -t, or the --isaac-sim / --ros2 shortcuts."""
    return "isaac" if args.isaac_sim else "ros2" if args.ros2 else str(args.target)


def cmd_compile(args: argparse.Namespace) -> int:
    target = compile_target(args)
    args.json_target, args.json_output = target, args.output
    if args.report:
        check_output(args.report, folder=False, source=args.input, what="--report")
        if args.output and os.path.abspath(args.report) == os.path.abspath(args.output):
            raise ConfigError(f"--report {args.report}: is also the output (-o); give another file")
    # Each target takes only its own options.
    accepted = _accepted(target)
    options = {
        **_input_options(args),
        **_pass_options(args),
        **{k: v for k, v in {**target_options(args), **_bare_world(args)}.items() if k in accepted},
        **world_options(args),
        "mesh_paths": args.mesh_paths,
        "preset": args.preset,
        "validate": args.validate,
    }
    progress = render.Progress(not args.quiet and not args.json)
    try:
        result = api.compile_to(args.input, target, args.output, progress=progress, **options)
    except ValidationFailedError as failed:
        progress.stop()
        return _validation_failed(args, target, failed.result)
    finally:
        progress.stop()
    report = result.validation
    if args.report and report is not None:
        from robodesc._files import write_atomic

        write_atomic(args.report, report.to_markdown())
    if args.preview and args.output and target_spec(target).folder:
        # A folder is what a user opens first: its picture of the robot as compiled. Written once the
        # folder is in place; a machine without an offscreen GL backend gets none, and is told.
        from robodesc.view import write_preview_png

        preview = write_preview_png(result.robot, args.output)
        if preview is not None:
            result.files["preview"] = preview
        elif not args.quiet and not args.json:
            print("note: no preview.png (no offscreen OpenGL: EGL or OSMesa; docs/view.md)", file=sys.stderr)
    if args.json:
        print(json.dumps(render.json_doc("compile", 0, target=target, output=args.output, result=result), indent=2))
        return 0
    render.print_findings(result.findings, args.quiet, args.verbose)
    if args.output is None and result.text is not None:
        sys.stdout.write(result.text)
    if report is not None and args.verbose:
        print(report.to_text(), file=sys.stderr)
    if not args.quiet:
        print(render.summary_line(result, target, args.output), file=sys.stderr)
    return 0


def cmd_layer(args: argparse.Namespace) -> int:
    """The Isaac folder's physics layer for an existing import (``api.isaac_physics_layer``)."""
    if not args.output:
        raise ConfigError("robodesc layer writes one file: give it with -o physics.usda")
    if not os.path.isfile(args.onto):
        raise ConfigError(f"--onto {args.onto}: no such file")
    options = {
        **_input_options(args),
        **_pass_options(args),
        **target_options(args),
        "mesh_paths": args.mesh_paths,
        "preset": args.preset,
        "validate": args.validate,
    }
    result = api.isaac_physics_layer(args.input, args.onto, args.output, stage=args.stage, **options)
    render.print_findings(result.findings, args.quiet, args.verbose)
    if not args.quiet:
        print(f"robodesc: physics layer {args.output} over {args.onto}", file=sys.stderr)
        if args.stage:
            print(f"robodesc: stage {args.stage} (open this one)", file=sys.stderr)
    return 0


def _validation_failed(args: argparse.Namespace, target: str, result: CompileResult) -> int:
    """Exit 1: the output differs from the source because of robodesc. Nothing was written; the
    full table is printed (and written to --report)."""
    report = result.validation
    assert report is not None  # raised only when validation ran
    if args.report:
        from robodesc._files import write_atomic

        write_atomic(args.report, report.to_markdown())
    if args.json:
        errors: list[dict[str, object]] = [
            {"severity": "error", "code": f"validation:{c.name}", "message": c.message, "element": c.element}
            for c in report.failures
        ]
        doc = render.json_doc("compile", 1, target=target, output=args.output, result=result, errors=errors)
        doc["files"] = {}
        print(json.dumps(doc, indent=2))
        return 1
    render.print_findings(result.findings, args.quiet, args.verbose)
    print(report.to_text(), file=sys.stderr)
    print(
        f"error: the output failed validation ({len(report.failures)} check(s) above); nothing was written. "
        "This is robodesc's fault: please report it. --no-validate writes the output anyway",
        file=sys.stderr,
    )
    return 1


def cmd_validate(args: argparse.Namespace) -> int:
    _refuse_output_as_input(args.input)
    if args.report:
        check_output(args.report, folder=False, source=args.input, what="--report")
    args.json_target = args.target
    dynamics, options = _dynamics_options(args), _input_options(args)
    # The world goes in the compile, and with it into what every engine runs (docs/worlds.md).
    options.update(
        {**{k: v for k, v in _bare_world(args).items() if k in _accepted(args.target)}, **world_options(args)}
    )
    if isinstance(dynamics, dict):
        _place_gains(args, dynamics, options)
    elif args.stiffness or args.damping:
        raise ConfigError("--stiffness and --damping set the gains --dynamics simulates: add --dynamics")
    clip_format = _video_setup(args, dynamics)
    result = api.check(args.input, args.target, dynamics=dynamics, **options)
    report = result.validation
    if report is None:
        raise ConfigError(f"target {args.target!r} has nothing to validate")
    code = 0 if report.ok and (result.dynamics is None or result.dynamics.ok) else 1
    clips = _write_clips(args, result.dynamics, clip_format)
    if args.report:
        from robodesc._files import write_atomic

        write_atomic(args.report, report.to_markdown())
    if args.json:
        doc = render.json_doc("validate", code, target=args.target, result=result)
        doc["files"] = {}
        doc["dynamics"] = result.dynamics.as_dict() if result.dynamics is not None else None
        if args.video:
            doc["videos"] = [render.clip_dict(c) for c in clips]
        print(json.dumps(doc, indent=2))
    else:
        render.print_findings(result.findings, quiet=False)
        print(report.to_text())
        if result.dynamics is not None:
            print(result.dynamics.to_text())
        if args.video:
            render.print_clips(clips, args.video, simulated=result.dynamics is not None)
    return code


def _video_setup(args: argparse.Namespace, dynamics: dict[str, Any] | bool) -> str | None:
    """``--video DIR``: refused before any work when it cannot be written (exit 2); the runners then
    record the poses the clips draw. A progress line per engine on a terminal. The clips' format."""
    if isinstance(dynamics, dict) and sys.stderr.isatty() and not args.json:
        dynamics["progress"] = _progress
    if not args.video:
        if args.video_format:
            raise ConfigError("--video-format sets the format of --video's clips: add --video DIR")
        return None
    if not isinstance(dynamics, dict):
        raise ConfigError("--video DIR draws the runs of --dynamics: add --dynamics")
    from robodesc.view.render import prefer_backend
    from robodesc.view.video import check_video_folder, choose_format

    check_video_folder(args.video, args.input)
    chosen = choose_format(args.video_format)
    dynamics["record"] = True
    prefer_backend()  # before the engines import MuJoCo: the clips then draw in this process
    return chosen


def _write_clips(args: argparse.Namespace, report: Any, clip_format: str | None) -> list[Any]:
    if clip_format is None or report is None:
        return []
    from robodesc.view.video import write_dynamics_clips

    progress = _progress if sys.stderr.isatty() and not args.json else None
    return write_dynamics_clips(report, args.video, fmt=clip_format, progress=progress)


def _progress(line: str) -> None:
    print(f"robodesc: {line} ...", file=sys.stderr, flush=True)


def _dynamics_options(args: argparse.Namespace) -> dict[str, Any] | bool:
    """False without --dynamics; else the DynamicsOptions fields the flags set."""
    if not getattr(args, "dynamics", False):
        return False
    pose: dict[str, float] = {}
    for rule in args.pose:
        pattern, sep, value = rule.rpartition("=")
        try:
            pose[pattern] = float(value)
        except ValueError:
            raise ConfigError(f"--pose {rule!r}: expected REGEX=VALUE with a number") from None
        if not sep:
            raise ConfigError(f"--pose {rule!r}: expected REGEX=VALUE")
    check_numbers(pose, "pose")
    return {"engines": args.engines, **({"pose": pose} if pose else {})}


def _place_gains(args: argparse.Namespace, dynamics: dict[str, Any], options: dict[str, Any]) -> None:
    """``--stiffness``/``--damping`` of ``validate --dynamics``: compile options when the checked
    target writes drives (the file then carries them, as the engine reading it simulates it), else
    the simulated gains only."""
    from robodesc.cli.flags import gain_rules

    spec = target_spec(args.target)
    declared = {f.name for f in dataclasses.fields(spec.options)} if spec.options else set()
    for name in ("stiffness", "damping"):
        values = getattr(args, name, None) or []
        if values:
            (options if name in declared else dynamics)[name] = gain_rules(values, f"--{name}")


def _refuse_output_as_input(path: str) -> None:
    """``validate robot.usda``: what robodesc wrote, not what it reads. Say how to check it."""
    from robodesc.frontends.load import frontend_for
    from robodesc.ir.diagnostics import ParseError
    from robodesc.targets import TARGETS

    if not os.path.isfile(path):
        return
    try:
        frontend_for(path)
    except ParseError:
        for name in TARGETS:
            if path.lower().endswith(target_spec(name).suffixes or ("\0",)):
                raise ConfigError(
                    f"{path}: robodesc validates an output against the robot it was compiled from; "
                    f"run: robodesc validate SOURCE -t {name}"
                ) from None


def cmd_inspect(args: argparse.Namespace) -> int:
    report = api.inspect(args.input, **_input_options(args))
    if args.strict:
        from robodesc.pipeline import refuse_warnings

        refuse_warnings(report.findings, [])
    if args.html:
        from robodesc.view import write_view_html

        write_view_html(args.input, args.html, options=build_options(_input_options(args)))
    if args.json:
        doc = report.as_dict()
        doc["findings"] = [render.finding_dict(f) for f in report.findings]
        print(json.dumps(doc, indent=2))
        return 0
    # As compile prints them: grouped by kind on standard error; the description on standard output.
    render.print_findings(report.findings, args.quiet, args.verbose)
    if not args.quiet:
        sys.stdout.write(report.render())
    return 0


def _view_options(args: argparse.Namespace) -> CompileOptions:
    # The world the picture shows the robot in (--world, --terrain, --spawn ...).
    return build_options({**_input_options(args), **world_options(args), "preset": getattr(args, "preset", None)})


def cmd_view(args: argparse.Namespace) -> int:
    from robodesc.view import write_view_html

    page = write_view_html(args.input, args.output, options=_view_options(args), target=args.target)
    print(
        f"robodesc: {render.display_path(page.path)}: {page.links} links, {page.meshes} meshes, "
        f"{page.findings} findings, {page.repairs} repairs; {page.bytes / 1e6:.1f} MB in {page.seconds:.2f} s",
        file=sys.stderr,
    )
    return 0


def cmd_render(args: argparse.Namespace) -> int:
    from robodesc.view.render import parse_size, render_png

    if not args.output and not args.video:
        raise ConfigError("render: give -o FILE.png, --video FILE.mp4, or both")
    if args.video:
        from robodesc.view.video import check_video_file

        check_video_file(args.video, args.input)  # before the picture: a bad path costs nothing
    if args.output:
        done = render_png(
            args.input,
            args.output,
            view=args.view,
            size=parse_size(args.size or "800x600"),
            grid_views=args.grid,
            collision=args.collision,
            options=_view_options(args),
            target=args.target,
        )
        for why in done.skipped:
            print(f"warning: not drawn: {why}", file=sys.stderr)
        print(
            f"robodesc: {render.display_path(done.path)}: {done.width}x{done.height} ({done.backend}) in {done.seconds:.2f} s",
            file=sys.stderr,
        )
    if args.video:
        from robodesc.view.video import render_video

        clip = render_video(
            args.input,
            args.video,
            size=parse_size(args.size or "640x480"),
            collision=args.collision,
            options=_view_options(args),
            target=args.target,
        )
        render.print_clips([clip])
    return 0


def cmd_expand(args: argparse.Namespace) -> int:
    from robodesc.frontends.packages import PackageResolver
    from robodesc.frontends.xacro_expand import expand_xacro
    from robodesc.ir.diagnostics import Findings

    findings = Findings()
    resolver = PackageResolver(explicit=dict(args.package), input_file=args.input)
    text = expand_xacro(
        args.input, dict(args.arg), resolver, findings, trust=args.trust_xacro, allowed_env=tuple(args.env)
    )
    for f in findings:
        print(render.render_finding(f), file=sys.stderr)
    sys.stdout.write(text + "\n")
    return 0


def cmd_batch(args: argparse.Namespace) -> int:
    from robodesc.batch.command import run_command

    return run_command(args, compile_options(args), compile_target(args))


COMMANDS = {
    "layer": cmd_layer,
    "compile": cmd_compile,
    "batch": cmd_batch,
    "expand": cmd_expand,
    "validate": cmd_validate,
    "inspect": cmd_inspect,
    "view": cmd_view,
    "render": cmd_render,
}
