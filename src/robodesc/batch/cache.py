"""Which jobs can be skipped: content hashes, never file times.

A job is skipped when its last run wrote its outputs and nothing it depends on changed since:

- the static key: the job's input path, target, output, options, the ROS package search path and
  the robodesc build (its version and a hash of its own code, so that a development install that
  changes without a version bump does not reuse stale outputs);
- the content hash of every file the job read last time (the input, every file it included, the
  meshes): a file that would be newly included can only come from a changed file already listed;
- every output it wrote, by size and modification time (an output deleted or edited by hand is
  rewritten; outputs are not inputs, so a stamp is enough and costs no hashing).

Records live in ``ROOT/.robodesc-batch/records.jsonl``, one JSON line per job, appended (and
flushed) as each job ends, so a batch killed at any point keeps every finished job; a line a kill
cut short is ignored. Each run starts by rewriting the file with the last record of every job.
"""

from __future__ import annotations

import hashlib
import json
import os
from typing import Any

from robodesc.batch.jobs import WROTE_OUTPUTS, Job, JobResult
from robodesc.batch.worker import file_hash, output_stamp

RECORDS = os.path.join(".robodesc-batch", "records.jsonl")
FORMAT = 3  # 2: file hashes are BLAKE3; 3: one file of JSON lines


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


class Records:
    """Every job's last record; :meth:`add` appends one as a job ends."""

    def __init__(self, root: str) -> None:
        self.path = os.path.join(root, RECORDS)
        self.known: dict[str, dict[str, Any]] = {}
        self._handle: Any = None
        try:
            with open(self.path, encoding="utf-8") as handle:
                for line in handle:
                    try:
                        data = json.loads(line)
                    except ValueError:  # a line a kill cut short
                        continue
                    if isinstance(data, dict) and data.get("format") == FORMAT and isinstance(data.get("id"), str):
                        self.known[data["id"]] = data
        except (OSError, UnicodeDecodeError):
            pass

    def get(self, job_id: str) -> dict[str, Any] | None:
        return self.known.get(job_id)

    def open(self) -> None:
        """Rewrite the file with one line per job (dropping older lines and a cut one), then append."""
        from robodesc._files import write_atomic

        write_atomic(self.path, "".join(json.dumps(r, sort_keys=True) + "\n" for r in self.known.values()))
        self._handle = open(self.path, "a", encoding="utf-8")  # noqa: SIM115 (closed by close())

    def add(self, job: Job, key: str, result: JobResult) -> None:
        data = {"format": FORMAT, "id": job.id, "key": key, "result": result.as_dict()}
        self.known[job.id] = data
        if self._handle is not None:
            # One line, flushed at once: json's C encoder (an indent would take the pure-Python one).
            self._handle.write(json.dumps(data, sort_keys=True) + "\n")
            self._handle.flush()

    def close(self) -> None:
        if self._handle is not None:
            self._handle.close()
            self._handle = None


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


def fresh_result(records: Records, job: Job, key: str, hashes: Hashes) -> JobResult | None:
    """The recorded result when the job may be skipped, else ``None``."""
    record = records.get(job.id)
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
