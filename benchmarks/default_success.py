"""Default-flag success rate of ``robodesc compile`` on collections of real robot files.

    python benchmarks/default_success.py --corpus                      # the 100-robot test corpus
    python benchmarks/default_success.py DIR [DIR ...]                 # every *.urdf / *.urdf.xacro below DIR
    python benchmarks/default_success.py --corpus DIR --json out.json  # also keep every row

Each robot file is compiled the way a new user would: ``robodesc compile FILE -t urdf|sdf|usd -o
OUT`` and ``--isaac-sim -o OUT_DIR``, no flags beyond the package map a corpus entry declares. The
script prints, per target, how many robots exited 0, and the failures grouped by the first error
line with names and numbers blanked out (the failure's class). Each robot runs in its own process
(``--python`` picks the interpreter, so the same script measures two checkouts), two at a time.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import glob
import io
import json
import os
import re
import subprocess
import sys
import tempfile
from collections import Counter, defaultdict
from contextlib import redirect_stderr, redirect_stdout
from typing import Any

TARGETS = {
    "urdf": ["-t", "urdf", "-o", "{out}/robot.urdf"],
    "sdf": ["-t", "sdf", "-o", "{out}/robot.sdf"],
    "usd": ["-t", "usd", "-o", "{out}/robot.usda"],
    # --no-preview: the folder's picture is not part of the conversion this measures (docs/view.md).
    "isaac": ["--isaac-sim", "-o", "{out}/isaac", "--no-preview"],
    "mjcf": ["-t", "mjcf", "-o", "{out}/robot.xml"],
}
# Procedurally generated objects (1000 random meshes in pybullet_data): not robots anyone wrote.
SKIP_DIRS = ("random_urdfs",)


def find_files(root: str) -> list[str]:
    out = []
    for pattern in ("*.urdf", "*.URDF", "*.urdf.xacro"):
        out += glob.glob(os.path.join(root, "**", pattern), recursive=True)
    return sorted(p for p in set(out) if not any(f"{os.sep}{d}{os.sep}" in p for d in SKIP_DIRS))


def count_links(path: str) -> int | None:
    """Links in a plain URDF by a forgiving read (None for xacro, which needs expanding)."""
    if path.endswith(".xacro"):
        return None
    try:
        from lxml import etree

        parser = etree.XMLParser(recover=True, resolve_entities=False, no_network=True, huge_tree=False)
        with open(path, "rb") as handle:
            data = handle.read().replace(b"\0", b"")
        root = etree.fromstring(data, parser)
        if root is None:
            return 0
        return len(root.findall(".//link"))
    except Exception:
        return 0


_BLANKS = [
    (re.compile(r"'[^']*'"), "'…'"),
    (re.compile(r'"[^"]*"'), '"…"'),
    (re.compile(r"\S+\.(urdf|xacro|sdf|usda|usd|stl|STL|obj|dae|DAE)\S*"), "FILE"),
    (re.compile(r"-?\d+(\.\d+)?(e[-+]?\d+)?"), "N"),
]


def failure_class(exit_code: int, stderr: str) -> str:
    errors = [ln for ln in stderr.splitlines() if ln.startswith("error:")]
    if "Traceback" in stderr:
        last = [ln for ln in stderr.splitlines() if ln.strip()][-1]
        return f"crash: {last.split(':')[0]}"
    if exit_code == 1:
        fails = [ln.strip() for ln in stderr.splitlines() if "FAIL" in ln]
        first = fails[0] if fails else (errors[0] if errors else "exit 1")
        text = first
    else:
        text = errors[0] if errors else (stderr.strip().splitlines() or ["(no message)"])[-1]
    text = text.removeprefix("error: ")
    # drop the "file:line: element" prefix: the class is what went wrong
    parts = text.split(": ")
    if len(parts) > 2 and (".urdf" in parts[0] or ".xacro" in parts[0] or "<string>" in parts[0]):
        text = ": ".join(parts[1:])
    for pattern, repl in _BLANKS:
        text = pattern.sub(repl, text)
    return f"exit {exit_code}: {text[:150]}"


def worker(path: str, packages: list[str], targets: list[str]) -> dict[str, Any]:
    """Run in a child process: every target through ``robodesc.cli.main``, as the console script would."""
    os.environ.setdefault("PXR_WORK_THREAD_LIMIT", "1")
    from robodesc.cli import main

    rows = {}
    for target in targets:
        with tempfile.TemporaryDirectory(prefix="robodesc-default-") as tmp:
            argv = ["compile", path, *[a.format(out=tmp) for a in TARGETS[target]]]
            for pkg in packages:
                argv += ["--package", pkg]
            err, out = io.StringIO(), io.StringIO()
            try:
                with redirect_stderr(err), redirect_stdout(out):
                    code = main(argv)
            except SystemExit as exc:
                code = int(exc.code or 0)
            except BaseException as exc:
                import traceback

                err.write("Traceback\n" + "".join(traceback.format_exception(exc)))
                code = 3
            text = err.getvalue()
            rows[target] = {
                "exit": code,
                "class": "ok" if code == 0 else failure_class(code, text),
                "stderr": text[-3000:],
            }
    return rows


def run_one(python: str, item: dict[str, Any], targets: list[str], timeout: float) -> dict[str, Any]:
    cmd = [python, os.path.abspath(__file__), "--worker", item["path"], "--targets", ",".join(targets)]
    for pkg in item.get("packages", []):
        cmd += ["--package", pkg]
    env = dict(os.environ, PXR_WORK_THREAD_LIMIT="1")
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
        rows = json.loads(proc.stdout.strip().splitlines()[-1])
    except subprocess.TimeoutExpired:
        rows = {t: {"exit": -1, "class": f"timeout after {timeout:.0f} s", "stderr": ""} for t in targets}
    except (json.JSONDecodeError, IndexError):
        rows = {t: {"exit": -2, "class": "worker died", "stderr": proc.stderr[-2000:]} for t in targets}
    return {**item, "targets": rows}


def corpus_items() -> list[dict[str, Any]]:
    from robodesc.validation.corpora import all_robots

    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    shared = os.environ.get("ROBODESC_SHARED_CORPUS", os.path.join(os.path.dirname(here), "shared", "corpus"))
    out = []
    for r in all_robots(shared):
        out.append(
            {
                "collection": "corpus/" + r.corpus,
                "path": r.path,
                "name": r.name,
                "packages": [f"{k}={v}" for k, v in r.packages.items()],
            }
        )
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("roots", nargs="*", help="folders to search for *.urdf and *.urdf.xacro")
    ap.add_argument("--corpus", action="store_true", help="the 100-robot corpus of robodesc.validation.corpora")
    ap.add_argument("--python", default=sys.executable, help="interpreter whose robodesc is measured")
    ap.add_argument("--targets", default=",".join(TARGETS))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=600)
    ap.add_argument("--json", help="write every row here")
    ap.add_argument(
        "--compare",
        nargs=2,
        metavar=("BEFORE.json", "AFTER.json"),
        help="print a before/after table from two --json files (AFTER may be several files joined by commas)",
    )
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    ap.add_argument("--package", action="append", default=[], help=argparse.SUPPRESS)
    args = ap.parse_args()
    targets = args.targets.split(",")
    if args.compare:
        before = _read(args.compare[0])
        after = [row for name in args.compare[1].split(",") for row in _read(name)]
        print_compare(before, after, targets)
        return 0
    if args.worker:
        print(json.dumps(worker(args.worker, args.package, targets)))
        return 0

    items = corpus_items() if args.corpus else []
    for root in args.roots:
        root = os.path.abspath(root)
        for path in find_files(root):
            items.append(
                {"collection": os.path.basename(root.rstrip(os.sep)), "path": path, "name": os.path.relpath(path, root)}
            )
    for item in items:
        item["links"] = count_links(item["path"])
    results = []
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        futures = [pool.submit(run_one, args.python, it, targets, args.timeout) for it in items]
        for n, fut in enumerate(concurrent.futures.as_completed(futures), 1):
            res = fut.result()
            results.append(res)
            marks = " ".join(f"{t}:{res['targets'][t]['exit']}" for t in targets)
            print(f"[{n}/{len(items)}] {res['collection']} {res['name']}: {marks}", file=sys.stderr, flush=True)
    results.sort(key=lambda r: (r["collection"], r["name"]))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as handle:
            json.dump(results, handle, indent=1)
    print_summary(results, targets)
    return 0


def _read(path: str) -> list[dict[str, Any]]:
    with open(path, encoding="utf-8") as handle:
        rows: list[dict[str, Any]] = json.load(handle)
    return rows


def print_compare(before: list[dict[str, Any]], after: list[dict[str, Any]], targets: list[str]) -> None:
    """Robots with at least one link, per collection: exit-0 counts before -> after, per target.
    Only robots present in both runs are counted."""
    key = {(r["collection"], r["name"]): r for r in after}
    by_coll: dict[str, list[tuple[dict[str, Any], dict[str, Any]]]] = defaultdict(list)
    for r in before:
        if (r["collection"], r["name"]) in key and (r["links"] is None or r["links"] > 0):
            by_coll[r["collection"]].append((r, key[(r["collection"], r["name"])]))
    print("| collection | robots | " + " | ".join(f"{t} before → after" for t in targets) + " |")
    print("|---|---:|" + "---:|" * len(targets))
    totals: Counter[str] = Counter()
    n_all = 0
    for coll, pairs in sorted(by_coll.items()):
        n_all += len(pairs)
        cells = []
        for t in targets:
            b = sum(1 for x, _ in pairs if x["targets"][t]["exit"] == 0)
            a = sum(1 for _, y in pairs if y["targets"][t]["exit"] == 0)
            totals[t + "b"] += b
            totals[t + "a"] += a
            cells.append(f"{b} → {a}")
        print(f"| {coll} | {len(pairs)} | " + " | ".join(cells) + " |")
    print(f"| **all** | {n_all} | " + " | ".join(f"{totals[t + 'b']} → {totals[t + 'a']}" for t in targets) + " |")


def print_summary(results: list[dict[str, Any]], targets: list[str]) -> None:
    by_coll: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for r in results:
        by_coll[r["collection"]].append(r)
    print("| collection | robots | " + " | ".join(targets) + " |")
    print("|---|---|" + "---|" * len(targets))
    total: Counter[str] = Counter()
    denom = 0
    for coll, rows in sorted(by_coll.items()):
        eligible = [r for r in rows if r["links"] is None or r["links"] > 0]
        denom += len(eligible)
        cells = []
        for t in targets:
            ok = sum(1 for r in eligible if r["targets"][t]["exit"] == 0)
            total[t] += ok
            cells.append(f"{ok}/{len(eligible)}")
        print(f"| {coll} | {len(eligible)} | " + " | ".join(cells) + " |")
    print(f"| **all** | {denom} | " + " | ".join(f"{total[t]}/{denom}" for t in targets) + " |")
    print()
    classes: dict[str, Counter[str]] = defaultdict(Counter)
    example: dict[str, str] = {}
    for r in results:
        if r["links"] == 0:
            continue
        for t in targets:
            c = r["targets"][t]["class"]
            if c != "ok":
                classes[c][t] += 1
                example.setdefault(c, f"{r['collection']}/{r['name']}")
    print("failure classes (robot-target count; first example):")
    for c, cnt in sorted(classes.items(), key=lambda kv: -sum(kv[1].values())):
        print(
            f"  {sum(cnt.values()):4d}  {c}  [{', '.join(f'{t}={n}' for t, n in sorted(cnt.items()))}]  e.g. {example[c]}"
        )


if __name__ == "__main__":
    sys.exit(main())
