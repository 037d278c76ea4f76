"""The per-job function: one compile, in-process, in whichever worker runs it (a process of the
local pool or a Ray task). Everything it returns is plain data, so both executors hand the driver
the same :class:`JobResult`.

Which files a job read (the input, every xacro include and YAML file, Python modules of a
composition, the meshes) is recorded while it runs through Python's audit hook on ``open``: the
frontends need no bookkeeping of their own, and a new kind of include is covered the day it is
added. The mesh paths of the IR are added too, since some targets name meshes without opening them.
"""

from __future__ import annotations

import os
import sys
import time
import traceback
from typing import Any

from robodesc.batch.jobs import CRASHED, ERROR, OK, VALIDATION_FAILED, Job, JobResult
from robodesc.ir.diagnostics import RobodescError, VerificationError

_recording: tuple[set[str], set[str]] | None = None  # (opened to read, opened to write)
_hooked = False


# Python's libraries (their code, metadata a lazy import reads) are not the robot's inputs; robodesc's
# own code is covered by the build fingerprint instead. Data installed beside them (share/...) is.
def _library_dirs() -> tuple[str, ...]:
    import site
    import sysconfig

    dirs = [sysconfig.get_path(name) for name in ("stdlib", "platstdlib", "purelib", "platlib")]
    dirs += [*site.getsitepackages(), site.getusersitepackages()]
    dirs.append(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # robodesc itself
    return tuple(sorted({os.path.join(os.path.realpath(d), "") for d in dirs if d}))


_LIBRARIES = _library_dirs()
_CODE_SUFFIXES = (".py", ".pyc", ".so", ".pyd", ".pth", ".pyi", ".txt", ".json", ".toml", ".cfg")


def _audit(event: str, args: tuple[Any, ...]) -> None:
    if event != "open" or _recording is None:
        return
    path, mode, flags = args[0], args[1], args[2]
    if isinstance(path, bytes):
        path = os.fsdecode(path)
    if not isinstance(path, str):
        return
    if isinstance(mode, str):
        writes = any(c in mode for c in "wax+")
    else:  # os.open: only flags
        writes = isinstance(flags, int) and bool(flags & (os.O_WRONLY | os.O_RDWR))
    _recording[1 if writes else 0].add(path)


def _install_hook() -> None:
    global _hooked
    if not _hooked:
        sys.addaudithook(_audit)
        _hooked = True


def file_hash(path: str) -> str:
    """The file's BLAKE3 content hash: a cryptographic hash, several times faster than SHA-256 on
    the meshes a batch rehashes (``blake3:`` names it in the records)."""
    import blake3

    digest = blake3.blake3()
    with open(path, "rb") as handle:
        while chunk := handle.read(1 << 20):
            digest.update(chunk)
    return "blake3:" + digest.hexdigest()


# A worker hashes a mesh many robots share once: keyed by the file's identity, size and time,
# which only ever saves recomputing the same content hash within this process.
_hash_memo: dict[tuple[str, int, int, int], str] = {}


def _memo_hash(path: str) -> str:
    info = os.stat(path)
    key = (path, info.st_ino, info.st_size, info.st_mtime_ns)
    if key not in _hash_memo:
        _hash_memo[key] = file_hash(path)
    return _hash_memo[key]


def output_stamp(path: str) -> str:
    """How an output is recognised as the one this job wrote: its size and modification time. An
    output is not an input, and hashing every written USD file would cost more than the check saves."""
    info = os.stat(path)
    return f"{info.st_size}:{info.st_mtime_ns}"


def _dependencies(opened: tuple[set[str], set[str]], job: Job, robot: Any) -> dict[str, str]:
    explicit = {os.path.abspath(job.path)}  # the input, the world's files and the IR's meshes always count
    world = job.options.world
    explicit.update(os.path.abspath(p) for p in (world.file, world.terrain, world.cords) if p is not None)
    if robot is not None:
        for link in robot.links:
            for item in (*link.visuals, *link.collisions):
                mesh_path = getattr(item.geometry, "path", None)
                if isinstance(mesh_path, str):
                    explicit.add(os.path.abspath(mesh_path))
    # What the job wrote itself (outputs, a consumer's scratch files) is not an input.
    written = {os.path.abspath(p) for p in opened[1]}
    output = os.path.abspath(job.output)
    # A robot installed inside a Python package (stretch_urdf) still has its own includes.
    package = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(job.path))), "")
    deps: dict[str, str] = {}
    for path in sorted({os.path.abspath(p) for p in opened[0]} - written | explicit):
        if path not in explicit:
            if path.startswith(("/proc/", "/sys/", "/dev/")) or path == output or path.startswith(output + os.sep):
                continue
            if os.path.realpath(path).startswith(_LIBRARIES) and (
                not path.startswith(package) or path.endswith(_CODE_SUFFIXES)
            ):
                continue  # a library's code or metadata, read by a lazy import
        if os.path.isfile(path):  # not a folder, nor a temporary file already gone
            deps[path] = _memo_hash(path)
    return deps


def _failure_findings(err: RobodescError) -> list[dict[str, Any]]:
    if isinstance(err, VerificationError) and err.findings:
        return [f.as_dict() for f in err.findings]
    loc = err.loc
    code = "".join("-" + c.lower() if c.isupper() else c for c in type(err).__name__).lstrip("-")
    return [
        {
            "severity": "error",
            "code": code.removesuffix("-error") or "error",
            "message": err.message,
            "element": err.element,
            "file": loc.file if loc else None,
            "line": loc.line if loc else None,
            "column": loc.column if loc else None,
            "stage": "",
        }
    ]


# compile_robot's progress messages -> the stage names a failed job reports.
_STAGES = {
    "loading": "load",
    "verifying": "verify",
    "running": "passes",
    "copying": "copy-meshes",
    "writing": "emit",
    "validating": "validate",
}


def run_job(job: Job) -> JobResult:
    """Compile one job with the same pipeline call as ``robodesc compile``; never raises for a job's
    own failure (it is the job's result)."""
    global _recording
    from robodesc.pipeline import compile_robot

    _install_hook()
    started = time.perf_counter()
    result = JobResult(job.id, OK)
    robot = None
    opened: tuple[set[str], set[str]] = (set(), set())
    _recording = opened
    try:
        result.stage = "load"

        def progress(step: str) -> None:
            result.stage = _STAGES.get(step.split(" ", 1)[0].rstrip(":"), result.stage)

        compiled = compile_robot(job.path, job.target, job.output, job.options, progress)
        robot = compiled.robot
        result.findings = [f.as_dict() for f in compiled.findings]
        result.files = dict(compiled.files)
        result.robot = {"name": robot.name, "links": len(robot.links), "joints": len(robot.joints)}
        report = compiled.validation
        if report is not None:
            import json

            result.validation = json.loads(report.to_json())
            if not report.ok:
                result.status = VALIDATION_FAILED
    except RobodescError as err:
        result.status = ERROR
        result.error = err.render()
        result.findings = _failure_findings(err)
    except KeyboardInterrupt:
        # Workers ignore SIGINT (init_worker): Ctrl-C reaches the driver alone. One raised here came
        # from the job's own code (a Python composition), and ends that job, not the batch.
        result.status = ERROR
        result.error = f"{job.path}: the job's own code raised KeyboardInterrupt"
    except Exception as err:  # a bug in robodesc or a consumer: this job's result, not the batch's end
        result.status = CRASHED
        result.error = f"{type(err).__name__}: {err}"
        result.detail = traceback.format_exc()
    finally:
        _recording = None
    if result.status == OK:
        result.stage = ""
    result.seconds = time.perf_counter() - started
    if result.status in (OK, VALIDATION_FAILED):
        result.deps = _dependencies(opened, job, robot)
        result.outputs = {path: output_stamp(path) for path in sorted(result.files.values()) if os.path.isfile(path)}
    return result


# Meshes a worker keeps between its jobs: a family of robots, or a sweep's variants, share them.
MESH_BUDGET = 256 * 1024 * 1024


def prepare_worker() -> None:
    """What every worker (a local pool's process, a Ray worker) sets up once: one USD work thread
    per worker, the pipeline imported, meshes kept across jobs."""
    os.environ.setdefault("PXR_WORK_THREAD_LIMIT", "1")
    import robodesc.pipeline  # noqa: F401
    from robodesc.meshes.data import keep_across_runs, keeping

    if not keeping():
        keep_across_runs(MESH_BUDGET)


def init_worker() -> None:
    """Start of a local worker process: Ctrl-C goes to the driver alone, which stops the pool; the
    pipeline is imported here once, not once per job."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    prepare_worker()
