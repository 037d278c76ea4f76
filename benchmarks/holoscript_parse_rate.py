"""How much of HoloScript's own repository the ``.holo`` frontend reads.

    PYTHONPATH=src python benchmarks/holoscript_parse_rate.py /path/to/HoloScript [--commit SHA]
        [--write docs/compositions.md] [--compile]

For every ``*.holo`` file under the checkout (sorted paths) it runs robodesc's HoloScript parser
and then the lowering to the IR, and sorts the outcome into:

- ``robot``: a robot came out (links, joints);
- ``no-robot``: the file parses but describes no robot (a scene, a UI, a service ...);
- ``refused``: the parser or the lowering stopped with a message (grouped by the message's first
  words, so that one construct is one row);
- ``crash``: anything else (a robodesc bug).

For the files that declare joints (any joint spelling HoloScript uses, found by a regular expression
over the text, independently of robodesc's parser) it lists the movable joints that arrive. With
``--compile`` each of those is also compiled to URDF, SDF, USD and the Isaac Sim folder through the
public API. ``--write FILE`` replaces the block between ``<!-- holoscript-parse-rate -->`` markers.

HoloScript's files are not part of robodesc (and are not copied into it); the numbers are
reproducible from the checkout and the commit printed with them.
"""

from __future__ import annotations

import argparse
import collections
import datetime
import os
import re
import sys
import tempfile
from dataclasses import dataclass, field

from robodesc.ir.diagnostics import Findings, RobodescError
from robodesc.ir.model import JointType

JOINT_RE = re.compile(
    r"@joint\w*|behavior\s+[\"']\w*Joint[\"']|^\s*joints?\s+[\"'\w{]|\bjoint_(type|parent)\s*:",
    re.M,
)
MARK = "<!-- holoscript-parse-rate -->"


@dataclass
class Outcome:
    path: str
    status: str  # robot | no-robot | refused | crash
    reason: str = ""
    links: int = 0
    movable: list[str] = field(default_factory=list)
    declares_joints: bool = False
    compiled: dict[str, str] = field(default_factory=dict)


def reason_key(message: str) -> str:
    """The message without its location and quoted names: one row per construct."""
    text = re.sub(r"^\S+:\d+:\d+: ", "", message.splitlines()[0])
    text = re.sub(r"'[^']*'|\"[^\"]*\"", "…", text)
    text = re.sub(r"\d+(\.\d+)?", "N", text)
    return text[:90]


def measure(path: str, rel: str, compile_targets: bool) -> Outcome:
    from robodesc.frontends.holo.lower import load_holo
    from robodesc.frontends.options import LoadOptions, MissingMesh

    with open(path, encoding="utf-8", errors="replace") as handle:
        text = handle.read()
    out = Outcome(rel, "robot", declares_joints=bool(JOINT_RE.search(text)))
    options = LoadOptions(missing_mesh=MissingMesh.PRIMITIVE)
    try:
        result = load_holo(path, options, Findings())
    except RobodescError as exc:
        message = str(exc)
        out.status = "no-robot" if "no robot" in message or "has no objects" in message else "refused"
        out.reason = reason_key(message)
        return out
    except RecursionError:
        out.status, out.reason = "crash", "RecursionError"
        return out
    except Exception as exc:
        out.status, out.reason = "crash", f"{type(exc).__name__}: {exc}"[:90]
        return out
    robot = result.robot
    out.links = len(robot.links)
    out.movable = [j.name for j in robot.joints if j.type is not JointType.FIXED]
    if compile_targets and out.declares_joints:
        out.compiled = compile_all(path)
    return out


def compile_all(path: str) -> dict[str, str]:
    """Compile through the CLI, as a user would (validation on): ``ok`` is exit code 0."""
    import contextlib
    import io

    from robodesc.cli import main as cli_main

    results: dict[str, str] = {}
    with tempfile.TemporaryDirectory() as tmp:
        outputs = {"urdf": "r.urdf", "sdf": "r.sdf", "usd": "r.usda", "isaac": "isaac"}
        for target, out in outputs.items():
            args = ["compile", path, "-o", os.path.join(tmp, out), "--missing-mesh", "primitive", "-q"]
            args += ["--isaac-sim"] if target == "isaac" else ["-t", target]
            err = io.StringIO()
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                try:
                    code = cli_main(args)
                except SystemExit as exc:  # argparse
                    code = int(exc.code or 0)
            last = [line for line in err.getvalue().splitlines() if line.strip()]
            results[target] = "ok" if code == 0 else f"exit {code}: {(last[-1] if last else '')[:80]}"
    return results


def run(root: str, compile_targets: bool) -> list[Outcome]:
    files: list[str] = []
    for base, dirs, names in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in (".git", "node_modules"))
        files.extend(os.path.join(base, n) for n in names if n.endswith(".holo"))
    files = sorted(f for f in files if os.path.isfile(f))
    sys.setrecursionlimit(10_000)
    return [measure(f, os.path.relpath(f, root), compile_targets) for f in files]


def report(outcomes: list[Outcome], commit: str, date: str) -> str:
    n = len(outcomes)
    status = collections.Counter(o.status for o in outcomes)
    parsed = n - status["refused"] - status["crash"]
    lines = [
        MARK,
        f"Measured {date} on HoloScript commit `{commit}` with `benchmarks/holoscript_parse_rate.py`:",
        "",
        "| outcome | files |",
        "|---|---|",
        f"| `.holo` files | {n} |",
        f"| read (robot or no robot) | {parsed} ({100.0 * parsed / max(n, 1):.1f} %) |",
        f"| — a robot | {status['robot']} |",
        f"| — no robot in it | {status['no-robot']} |",
        f"| refused with a message | {status['refused']} |",
        f"| crash (robodesc bug) | {status['crash']} |",
        "",
    ]
    reasons = collections.Counter(o.reason for o in outcomes if o.status in ("refused", "crash"))
    if reasons:
        lines += ["| refused because | files |", "|---|---|"]
        lines += [f"| {r.replace('|', '/')} | {c} |" for r, c in reasons.most_common()]
        lines.append("")
    jointed = [o for o in outcomes if o.declares_joints]
    lines += [
        f"Files that declare joints ({len(jointed)}): movable joints that arrive"
        + (", and compile results" if any(o.compiled for o in jointed) else ""),
        "",
        "| file | outcome | links | movable joints | URDF | SDF | USD | Isaac |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for o in jointed:
        comp = [o.compiled.get(t, "—") for t in ("urdf", "sdf", "usd", "isaac")]
        what = o.status if o.status == "robot" else f"{o.status}: {o.reason}"
        lines.append(
            f"| {o.path} | {what.replace('|', '/')} | {o.links} | {len(o.movable)} | "
            + " | ".join(c.replace("|", "/") for c in comp)
            + " |"
        )
    lines += ["", MARK]
    return "\n".join(lines)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("root", help="a HoloScript checkout")
    ap.add_argument("--commit", default="unknown", help="the checkout's commit, printed with the numbers")
    ap.add_argument("--date", default=datetime.date.today().isoformat())
    ap.add_argument("--compile", action="store_true", help="compile the files that declare joints")
    ap.add_argument("--write", help="markdown file whose marked block is replaced")
    ap.add_argument("--verbose", action="store_true", help="one line per file")
    args = ap.parse_args()
    outcomes = run(args.root, args.compile)
    if args.verbose:
        for o in outcomes:
            print(f"{o.status:9} {o.path} {o.reason} {len(o.movable) if o.status == 'robot' else ''}")
    text = report(outcomes, args.commit, args.date)
    print(text)
    if args.write:
        with open(args.write, encoding="utf-8") as handle:
            doc = handle.read()
        if doc.count(MARK) == 2:
            head, _, rest = doc.partition(MARK)
            _, _, tail = rest.partition(MARK)
            doc = head + text + tail
        else:
            doc = doc.rstrip("\n") + "\n\n" + text + "\n"
        with open(args.write, "w", encoding="utf-8") as handle:
            handle.write(doc)
    return 0


if __name__ == "__main__":
    sys.exit(main())
