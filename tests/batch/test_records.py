"""The batch records: one JSON line per finished job, appended; a line a kill cut short is ignored,
and each run starts from one line per job."""

from __future__ import annotations

import json
from pathlib import Path

from robodesc.batch.cache import FORMAT, RECORDS, Records
from robodesc.batch.jobs import OK, Job, JobResult
from robodesc.options import CompileOptions


def _job(job_id: str) -> Job:
    return Job(
        id=job_id, input=f"{job_id}.urdf", path=f"/r/{job_id}.urdf", target="urdf", output="", options=CompileOptions()
    )


def test_records_append_survive_a_cut_line_and_compact(tmp_path: Path) -> None:
    records = Records(str(tmp_path))
    records.open()
    records.add(_job("a"), "k1", JobResult("a", OK, seconds=1.0))
    records.add(_job("b"), "k2", JobResult("b", OK))
    records.add(_job("a"), "k3", JobResult("a", OK, seconds=2.0))  # a rerun: the last line counts
    records.close()
    path = tmp_path / RECORDS
    with open(path, "a", encoding="utf-8") as handle:
        handle.write(f'{{"format": {FORMAT}, "id": "c", "key"')  # a kill in the middle of a line
    again = Records(str(tmp_path))
    assert set(again.known) == {"a", "b"}
    assert again.get("a") is not None and again.get("a")["key"] == "k3"  # type: ignore[index]
    again.open()  # rewritten: one line per job, the cut one gone
    again.close()
    lines = [json.loads(line) for line in path.read_text().splitlines()]
    assert sorted(line["id"] for line in lines) == ["a", "b"]
