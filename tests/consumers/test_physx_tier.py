"""The consumer tier's PhysX columns: how a compile's PhysX rows become the tier's verdicts
(run_tier.physx_verdict) and the corpus report's cell (corpus_report.physx_cell). No engine runs."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from types import ModuleType
from typing import Any

from tests.conftest import ROOT


def _module(name: str, path: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, ROOT / path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


run_tier = _module("run_tier", "tests/consumers/run_tier.py")
corpus_report = _module("corpus_report", "benchmarks/corpus_report.py")


def _compile(checks: list[dict[str, Any]], rc: int = 0) -> subprocess.CompletedProcess[str]:
    rows = [{"element": "", "message": "", **c} for c in checks]
    return subprocess.CompletedProcess([], rc, json.dumps({"validation": {"checks": rows}}), "")


def test_equal_masses_and_drives() -> None:
    got = run_tier.physx_verdict(
        _compile(
            [
                {"name": "physx-load", "status": "pass"},
                {"name": "physx-mass", "status": "pass"},
                {"name": "physx-drive", "status": "pass"},
                {"name": "mass", "status": "pass"},
            ]
        )
    )
    assert got == {"": "pass", "_loads": True, "_masses": "equal", "_drives": "equal"}


def test_a_known_mismatch_passes_the_compile_but_is_a_difference() -> None:
    got = run_tier.physx_verdict(
        _compile(
            [
                {"name": "physx-load", "status": "pass"},
                {
                    "name": "physx-massless",
                    "status": "warn",
                    "element": "link 'base'",
                    "message": "PhysX gives this link 29.4 kg [known mismatch until h-masses lands; issue #38]",
                },
                {
                    "name": "physx-inertia",
                    "status": "warn",
                    "element": "link 'text_left'",
                    "message": "x [a defect of the source, carried through unchanged]",
                },
                {"name": "physx-max-force", "status": "fail", "element": "joint 'elbow'"},
            ],
            rc=1,
        )
    )
    assert got[""] == "fail: physx-max-force joint 'elbow'"
    assert got["_masses"] == "differ: 1 (physx-massless): physx-massless link 'base'"
    assert got["_drives"] == "differ: 1 (physx-max-force): physx-max-force joint 'elbow'"


def test_no_interpreter_and_no_conversion() -> None:
    skipped = run_tier.physx_verdict(_compile([{"name": "physx", "status": "skip"}]))
    assert skipped == {"": "skip: no PhysX interpreter"}
    broken = run_tier.physx_verdict(subprocess.CompletedProcess([], 2, "not json", "error: the file is gone"))
    assert broken == {"": "not converted: error: the file is gone"}


def test_corpus_report_cell_shows_the_split() -> None:
    verdicts = {"physx": "pass", "physx_masses": "differ: 3 (physx-massless)", "physx_drives": "equal"}
    assert corpus_report.physx_cell(verdicts, "physx") == "pass; masses differ: 3 (physx-massless); drives equal"
    assert corpus_report.physx_cell({}, "physx_isaac") == "–"
