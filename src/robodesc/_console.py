"""The ``robodesc`` console script: one light step before :func:`robodesc.cli.run`.

``robodesc batch`` forks its workers from a fork server that imports robodesc once. Started here,
before the CLI (and the pipeline behind it) is imported, the server's imports overlap the
command's own start instead of delaying the first job (about 0.1 s of a batch of 100 robots that
takes under 3 s). Nothing else happens here: every other command goes straight to the CLI.
"""

from __future__ import annotations

import sys
from typing import NoReturn

from robodesc._forkserver import start_worker_server


def _runs_local_workers(args: list[str]) -> bool:
    if args[:1] != ["batch"] or "-h" in args or "--help" in args:
        return False
    for i, arg in enumerate(args):
        if arg == "--executor=ray" or (arg == "--executor" and args[i + 1 : i + 2] == ["ray"]):
            return False
    return True


def run() -> NoReturn:
    if _runs_local_workers(sys.argv[1:]):
        start_worker_server()
    from robodesc.cli import run as cli_run

    cli_run()
