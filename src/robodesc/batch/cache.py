"""Which jobs can be skipped: content hashes, never file times.

A job is skipped when its last run wrote its outputs and nothing it depends on changed since:

- the static key: the job's input path, target, output, options, the ROS package search path and
  the robodesc build (its version and a hash of its own code, so that a development install that
  changes without a version bump does not reuse stale outputs);
- the content hash of every file the job read last time (the input, every file it included, the
  meshes): a file that would be newly included can only come from a changed file already listed;
- every output it wrote, by size and modification time (an output deleted or edited by hand is
  rewritten; outputs are not inputs, so a stamp is enough and costs no hashing).

Records live in ``ROOT/.robodesc-batch/jobs/``, one JSON file per job, written as each job ends,
so a batch killed at any point keeps every finished job.
"""

from __future__ import annotations

import hashlib
import json
import os
from typing import Any

from robodesc.batch.jobs import WROTE_OUTPUTS, Job, JobResult
from robodesc.batch.worker import file_hash, output_stamp

RECORDS = os.path.join(".robodesc-batch", "jobs")
FORMAT = 2  # 2: file hashes are BLAKE3


def build_fingerprint() -> str:
    """robodesc's version and a hash of its installed code (Python sources and C extensions)."""
    from robodesc._version import __version__

    package = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # robodesc/
    digest = hashlib.sha256(__version__.encode())
    for folder, dirs, names in sorted(os.walk(package)):
        dirs.sort()
        dirs[:] = [d for d in dirs if d != "__pycache__"]
        for name in sorted(names):
            if name.endswith((".py", ".so", ".pyd")):
                path = os.path.join(folder, name)
                digest.update(os.path.relpath(path, package).encode() + b"\0" + file_hash(path).encode())
    return f"{__version__}+{digest.hexdigest()[:16]}"


def job_key(job: Job, fingerprint: str) -> str:
    data = {
        "format": FORMAT,
        "robodesc": fingerprint,
        "input": os.path.abspath(job.path),
        "target": job.target,
        "output": job.output,
        "options": job.options_dict(),
        "env": {name: os.environ.get(name, "") for name in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")},
    }
    return hashlib.sha256(json.dumps(data, sort_keys=True, default=str).encode()).hexdigest()


def record_path(root: str, job_id: str) -> str:
    name = hashlib.sha256(job_id.encode()).hexdigest()[:24] + ".json"
    return os.path.join(root, RECORDS, name)


def write_record(root: str, job: Job, key: str, result: JobResult) -> None:
    from robodesc.emit.common.files import write_atomic

    data = {"format": FORMAT, "id": job.id, "key": key, "result": result.as_dict()}
    write_atomic(record_path(root, job.id), json.dumps(data, indent=1, sort_keys=True))


def read_record(root: str, job_id: str) -> dict[str, Any] | None:
    try:
        with open(record_path(root, job_id), encoding="utf-8") as handle:
            data = json.load(handle)
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) and data.get("format") == FORMAT and data.get("id") == job_id else None


class Hashes:
    """File hashes, each computed once per batch (robots share meshes)."""

    def __init__(self) -> None:
        self._known: dict[str, str | None] = {}

    def get(self, path: str) -> str | None:
        if path not in self._known:
            try:
                self._known[path] = file_hash(path)
            except OSError:
                self._known[path] = None
        return self._known[path]


def fresh_result(root: str, job: Job, key: str, hashes: Hashes) -> JobResult | None:
    """The recorded result when the job may be skipped, else ``None``."""
    record = read_record(root, job.id)
    if record is None or record.get("key") != key:
        return None
    result = JobResult.from_dict(record.get("result") or {})
    if result.status not in WROTE_OUTPUTS or not result.deps:
        return None
    if any(hashes.get(path) != digest for path, digest in result.deps.items()):
        return None
    try:
        if any(output_stamp(path) != stamp for path, stamp in result.outputs.items()):
            return None
    except OSError:
        return None  # an output is gone
    if any(not os.path.exists(path) for path in result.files.values()):
        return None
    result.cached = True
    return result
