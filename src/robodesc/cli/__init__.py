"""``robodesc`` on the command line: a thin layer over :mod:`robodesc.api`.

``parser`` holds the grammar (target flags come from the targets' options dataclasses), ``commands``
turns flags into API calls, ``render`` prints what comes back.

Bad input never shows a traceback: each problem is one line ``error: file:line: element: what``.
Exit codes (docs/diagnostics.md): 0 written (warnings, if any, are listed), 1 the output failed
validation because of robodesc (nothing written), 2 refused (bad input, options or output path;
nothing written), 3 a robodesc bug (one line; ``--debug`` shows the trace).
A successful compile prints its warnings grouped by kind, then one summary line; ``-v`` lists every
finding; ``--json`` prints one JSON document on every exit path.
"""

from __future__ import annotations

import itertools
import json
import os
import sys
from collections.abc import Sequence
from typing import NoReturn

import robodesc.cli.render as render
from robodesc.cli.commands import COMMANDS
from robodesc.cli.parser import UsageError, build_parser
from robodesc.ir.diagnostics import RobodescError
from robodesc.plugins import load_plugins


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


def _named_plugins(argv: list[str]) -> list[str]:
    named = [v for a, v in itertools.pairwise(argv) if a == "--plugin"]
    return named + [a.removeprefix("--plugin=") for a in argv if a.startswith("--plugin=")]


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    # usd-core prints a banner when PXR_WORK_THREAD_LIMIT is set; this turns such alerts off.
    os.environ.setdefault("TF_ENV_SETTING_ALERTS_ENABLED", "0")
    want_json = "--json" in argv
    debug = "--debug" in argv
    command = next((a for a in argv if a in COMMANDS), "")
    try:  # before the parser is built: a plugin's target is a -t choice, its options are flags
        load_plugins(_named_plugins(argv))
    except RobodescError as err:
        return render.report_error(err)
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except UsageError as exc:
        if want_json:
            doc = render.json_doc(command, 2, errors=[{"severity": "error", "code": "usage", "message": str(exc)}])
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
            doc = render.json_doc(
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
        code = err.exit_code if want_json else render.report_error(err)
        return fail(code, render.error_dicts(err))
    except KeyboardInterrupt:
        print("error: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the reader (| head) went away: not an error of ours
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except OSError as exc:
        # The environment: a full disk, a permission changed mid-run, a vanished folder.
        where = f"{render.display_path(exc.filename)}: " if getattr(exc, "filename", None) else ""
        message = f"{where}{exc.strerror or exc}"
        if not want_json:
            print(f"error: {message}", file=sys.stderr)
        return fail(2, [{"severity": "error", "code": "environment", "message": message}])
    except (RecursionError, MemoryError) as exc:
        what = "too deeply nested" if isinstance(exc, RecursionError) else "too large for the memory available"
        message = f"{render.display_path(getattr(args, 'input', ''))}: the input is {what}"
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
