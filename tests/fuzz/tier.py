"""The fuzz test tier: many cases of tests/fuzz/fuzzer.py, each one unable to take the run down.

``python -m tests.fuzz.tier 2000`` (what ``tests/fuzz/run.sh`` runs) hands the cases to a child
process that runs them in process, as the suite does, and reports each case's start and outcome in a
progress file. The driver watches it: a child that dies by a signal (a segfault in native code) is
a ``crash`` of the case it was running, a case that gives no answer within the time bound plus a
grace (a hang inside native code, where ``SIGALRM`` cannot reach Python) is a ``hang``; either way
the child is replaced and the run goes on at the next case. The child is also replaced every
``CHUNK`` cases, so that one case's leftovers cannot change the next few hundred.

Prints a line per failing case as it comes, then the counts: crashes, hangs, false blames (exit 1
"robodesc's fault" on a mutated source), ok, refused, and any other failure class; exits 1 when
any case failed. ``--json FILE`` keeps every outcome.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

from tests.fuzz.fuzzer import TIME_LIMIT, Outcome, run_case

CHUNK = 200
GRACE = 60  # seconds beyond the per-case bound before the driver stops a child
REPO = Path(__file__).resolve().parents[2]


def _child(first: int, last: int, seed: int, root: Path, time_limit: int, progress: Path) -> None:
    with progress.open("a", encoding="utf-8") as log:
        for i in range(first, last):
            log.write(json.dumps({"start": i}) + "\n")
            log.flush()
            outcome = run_case(i, seed, root, time_limit)
            log.write(json.dumps({"done": dataclasses.asdict(outcome)}) + "\n")
            log.flush()


def _spawn(first: int, last: int, seed: int, root: Path, time_limit: int, progress: Path) -> subprocess.Popen[bytes]:
    argv = [sys.executable, "-m", "tests.fuzz.tier", "--child", str(first), str(last), str(seed), str(root)]
    argv += ["--time-limit", str(time_limit), "--progress", str(progress)]
    return subprocess.Popen(
        argv,
        cwd=REPO,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,  # its batch workers go with it when it is stopped
    )


def _stop(child: subprocess.Popen[bytes]) -> None:
    with contextlib.suppress(ProcessLookupError):
        os.killpg(child.pid, signal.SIGKILL)
    child.wait()


def _signal_text(code: int) -> str:
    if code < 0:
        try:
            return f"killed by {signal.Signals(-code).name}"
        except ValueError:
            pass
    return f"the child exited with code {code}"


def drive(cases: int, seed: int, root: Path, time_limit: int, echo: bool = True) -> list[Outcome]:
    outcomes: dict[int, Outcome] = {}
    next_case = 0
    n_child = 0
    while next_case < cases:
        last = min(cases, next_case + CHUNK)
        progress = root / f"progress-{n_child}.jsonl"
        n_child += 1
        child = _spawn(next_case, last, seed, root, time_limit, progress)
        started: tuple[int, float] | None = None
        offset = 0
        while True:
            code = child.poll()
            if progress.exists():
                with progress.open(encoding="utf-8") as f:
                    f.seek(offset)
                    for line in f:
                        if not line.endswith("\n"):
                            break
                        offset += len(line.encode("utf-8"))
                        event = json.loads(line)
                        if "start" in event:
                            started = (event["start"], time.monotonic())
                        else:
                            o = Outcome(**event["done"])
                            outcomes[o.case] = o
                            next_case = o.case + 1
                            started = None
                            if echo and o.failed:
                                print(_line(o), flush=True)
            if code is not None:
                if started is not None:  # the case it was running took it down
                    i = started[0]
                    outcomes[i] = Outcome(i, "?", "?", [], "crash", code, _signal_text(code), str(root / f"case{i}"))
                    next_case = i + 1
                    if echo:
                        print(_line(outcomes[i]), flush=True)
                elif code != 0 and next_case < last:
                    raise SystemExit(f"the fuzz child failed before case {next_case}: {_signal_text(code)}")
                break
            if started is not None and time.monotonic() - started[1] > time_limit + GRACE:
                _stop(child)
                i = started[0]
                detail = f"no answer within {time_limit + GRACE} s (native code: SIGALRM did not reach it)"
                outcomes[i] = Outcome(i, "?", "?", [], "hang", None, detail, str(root / f"case{i}"))
                next_case = i + 1
                if echo:
                    print(_line(outcomes[i]), flush=True)
                break
            time.sleep(0.2)
        if echo:
            print(f"... {next_case} of {cases} cases", flush=True)
    return [outcomes[i] for i in sorted(outcomes)]


def _line(o: Outcome) -> str:
    last = o.detail.strip().splitlines()[-1] if o.detail.strip() else ""
    return f"  case {o.case} [{o.seed_file} -> {o.target}, {'+'.join(o.mutations)}] {o.status}: {last[:300]} ({o.case_dir})"


HEADLINE = (("crash", "crashes"), ("hang", "hangs"), ("blame", "false blames"), ("ok", "ok"), ("refused", "refused"))


def counts(outcomes: list[Outcome]) -> dict[str, int]:
    by = Counter(o.status for o in outcomes)
    named = {label: by.pop(status, 0) for status, label in HEADLINE}
    return {**named, **dict(sorted(by.items()))}


def by_target(outcomes: list[Outcome]) -> dict[str, dict[str, int]]:
    """Counts per class, per target or command."""
    table: dict[str, Counter[str]] = {}
    for o in outcomes:
        table.setdefault(o.target, Counter())[o.status] += 1
    return {t: dict(sorted(c.items())) for t, c in sorted(table.items())}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("cases", type=int, nargs="?", default=2000)
    p.add_argument("--seed", type=int, default=17)
    p.add_argument("--dir", type=Path, help="where the cases are written (failing ones are kept)")
    p.add_argument("--time-limit", type=int, default=TIME_LIMIT, help="seconds per case")
    p.add_argument("--json", type=Path, help="write every outcome and the counts here")
    p.add_argument("--child", nargs=4, metavar=("FIRST", "LAST", "SEED", "DIR"), help=argparse.SUPPRESS)
    p.add_argument("--progress", type=Path, help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.child:
        first, last, seed, root = args.child
        _child(int(first), int(last), int(seed), Path(root), args.time_limit, args.progress)
        return 0
    root = args.dir or Path(tempfile.mkdtemp(prefix="robodesc-fuzz-tier-"))
    root.mkdir(parents=True, exist_ok=True)
    began = time.monotonic()
    outcomes = drive(args.cases, args.seed, root, args.time_limit)
    seconds = time.monotonic() - began
    tally = counts(outcomes)
    print(
        f"{len(outcomes)} cases (seed {args.seed}) in {seconds:.0f} s: "
        + ", ".join(f"{n} {k}" for k, n in tally.items())
    )
    print(f"by target: {dict(sorted(Counter(o.target for o in outcomes).items()))}")
    by_class = by_target(outcomes)
    for target, row in by_class.items():
        print(f"  {target:<12} " + ", ".join(f"{n} {status}" for status, n in row.items()))
    if args.json:
        args.json.write_text(
            json.dumps(
                {
                    "seed": args.seed,
                    "cases": args.cases,
                    "seconds": round(seconds, 1),
                    "counts": tally,
                    "by_target": by_target(outcomes),
                    "outcomes": [dataclasses.asdict(o) for o in outcomes],
                },
                indent=1,
            )
        )
    return 1 if any(o.failed for o in outcomes) else 0


if __name__ == "__main__":
    sys.exit(main())
