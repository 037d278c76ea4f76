"""``robodesc batch``: its arguments (compile's own, copied from the compile parser, plus the
batch's) and the command. Imported by the CLI when it builds its parser: keep it light."""

from __future__ import annotations

import argparse
import json
import os
import sys
from typing import Any

from robodesc.options import CompileOptions

# compile's arguments that mean one robot: batch has its own inputs, output folder and summary.
_NOT_COPIED = {"input", "output", "json", "quiet", "report", "help"}

EPILOG = """\
examples:
  robodesc batch robots/ -t usd -o out/ --no-validate          # every robot under robots/, all cores
  robodesc batch jobs.yaml -o out/                              # a manifest (YAML or CSV), see docs/batch.md
  robodesc batch arm.urdf.xacro -o out/ --sweep link_length=0.3,0.4 --sweep mass=1..2 --samples 10 --seed 7
  robodesc batch robots/ -o out/ --executor ray --address auto  # on a running Ray cluster
exit codes: 0 every job ok, 1 a validation check failed, 2 a job failed or bad options, 130 interrupted
"""


def add_batch_parser(sub: Any, compile_parser: argparse.ArgumentParser) -> argparse.ArgumentParser:
    p: argparse.ArgumentParser = sub.add_parser(
        "batch",
        help="compile many robots: files, folders, manifests, xacro sweeps; parallel and resumable",
        description="Compile every robot in INPUTS (files, folders searched for URDF/xacro/.holo/YAML/Python "
        "compositions, YAML or CSV manifests) into one folder per job under -o, with a summary "
        "(summary.json, summary.md). Jobs whose inputs, options and robodesc are unchanged since their "
        "last successful run are skipped. Takes every option of `robodesc compile`.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=EPILOG,
    )
    p.add_argument(
        "inputs", nargs="+", metavar="INPUT", help="robot files, folders, or manifests (.csv, .yaml with jobs:)"
    )
    p.add_argument(
        "-o", "--output", required=True, metavar="DIR", help="output folder: one folder per job, and the summary"
    )
    run = p.add_argument_group("running")
    run.add_argument(
        "-j",
        "--jobs",
        type=int,
        metavar="N",
        help="parallel workers (default: the number of cores; Ray: the cluster's CPUs)",
    )
    run.add_argument(
        "--executor",
        choices=["local", "ray"],
        default="local",
        help="a local process pool (default) or Ray tasks (pip install robodesc[ray])",
    )
    run.add_argument(
        "--address",
        metavar="ADDR",
        help="Ray cluster to join (auto, HOST:6379, ray://HOST:10001); default: start Ray on this machine",
    )
    run.add_argument(
        "--timeout",
        type=float,
        default=600.0,
        metavar="S",
        help="seconds one job may take before it is stopped (default 600)",
    )
    run.add_argument("--force", action="store_true", help="redo every job, even those unchanged since their last run")
    run.add_argument(
        "--suffix",
        metavar=".EXT",
        help="output file suffix, for targets that write more than one kind (.usdc for binary USD); "
        "default: the target's first (robodesc compile --help lists them)",
    )
    run.add_argument(
        "--run-python",
        action="store_true",
        help="also compile the Python compositions found in folders; they are programs and run when read, "
        "so only for folders you trust (a Python file named on the command line or in a manifest always runs)",
    )
    run.add_argument(
        "--thumbnails",
        action="store_true",
        help="draw a thumbnail of every robot into summary.html (MuJoCo, headless; about 0.5 s per robot, "
        "so off by default: a batch stays as fast as its compiles)",
    )
    # Before --suffix: the same choice for USD only.
    run.add_argument("--usd-format", choices=["usda", "usdc"], help=argparse.SUPPRESS)
    sw = p.add_argument_group("variant sweeps (xacro arguments)")
    sw.add_argument(
        "--sweep",
        action="append",
        default=[],
        metavar="NAME=V1,V2|NAME=LOW..HIGH",
        help="grid over listed values, or uniform random between LOW and HIGH (repeatable)",
    )
    sw.add_argument("--samples", type=int, metavar="N", help="random variants per grid point (needed with LOW..HIGH)")
    sw.add_argument("--seed", type=int, default=0, help="seed of the random variants (default 0)")
    p.add_argument("--json", action="store_true", help="print the summary as JSON on standard output")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar or table")
    for group in compile_parser._action_groups:
        actions = [a for a in group._group_actions if a.dest not in _NOT_COPIED]
        if not actions:
            continue
        # The parser's own two groups (options, positionals) exist in p already.
        own = group in (compile_parser._optionals, compile_parser._positionals)
        into = p if own else p.add_argument_group(group.title, group.description)
        for action in actions:
            into._add_action(action)
    return p


def run_command(args: argparse.Namespace, options: CompileOptions, target: str) -> int:
    """Plan, run, report. ``options`` and ``target`` are the compile command's own translation of its
    flags (the batch takes every option of ``robodesc compile``)."""
    from rich.console import Console

    from robodesc.batch import sweep
    from robodesc.batch.plan import plan
    from robodesc.batch.runner import exit_code, run_batch
    from robodesc.batch.summary import print_table
    from robodesc.ir.diagnostics import ConfigError

    if args.jobs is not None and args.jobs < 1:
        raise ConfigError(f"--jobs {args.jobs}: expected at least 1")
    if args.address and args.executor != "ray":
        raise ConfigError("--address names a Ray cluster: add --executor ray")
    if args.executor == "ray":
        try:
            import ray  # noqa: F401
        except ImportError:
            raise ConfigError("--executor ray needs Ray: pip install 'robodesc[ray]'") from None
    if args.executor == "local":
        from robodesc._forkserver import start_worker_server

        start_worker_server()  # if the console script has not: its imports overlap the planning below
    spec = sweep.from_cli(args.sweep, args.samples, args.seed)
    skipped: list[tuple[str, str]] = []
    jobs = plan(
        args.inputs,
        target=target,
        options=options,
        root=args.output,
        sweep=spec,
        suffix=args.suffix or (f".{args.usd_format}" if args.usd_format else None),
        run_python=args.run_python,
        skipped=skipped,
    )
    console = Console(stderr=True)
    run = run_batch(
        jobs,
        args.output,
        executor=args.executor,
        workers=args.jobs,
        timeout=args.timeout,
        force=args.force,
        address=args.address,
        progress=not args.quiet and console.is_terminal,
        progress_lines=not args.quiet and not args.json,
        console=console,
        skipped=skipped,
    )
    from robodesc.view.thumbs import summary_rows, write_summary_html

    write_summary_html(
        os.path.join(args.output, "summary.html"),
        summary_rows(run.summary, {job.id: job.options for job in jobs}, draw=args.thumbnails),
    )
    if args.json:
        print(json.dumps(run.summary, indent=2))
    if not args.quiet:
        print_table(run.summary, console)
        print(f"robodesc batch: wrote {args.output}/summary.md, summary.html and summary.json", file=sys.stderr)
    if run.interrupted:
        print("error: interrupted; finished jobs are kept and will be skipped next time", file=sys.stderr)
    return exit_code(run)
