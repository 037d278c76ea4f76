"""The seeded mutation fuzzer (tests/fuzz/fuzzer.py) in the suite.

CI runs ``ROBODESC_FUZZ_CASES`` cases (default 300, about a minute on two cores); the test tier
``tests/fuzz/run.sh`` runs 2,000 of the same sequence, each chunk in a child process so that a
signal or a hang in native code is counted too. The long mode in process is the same test with more
cases, e.g. ``ROBODESC_FUZZ_CASES=5000 python -m pytest tests/fuzz -k fuzz``
(or ``python tests/fuzz/fuzzer.py 5000``). ``ROBODESC_FUZZ_SEED`` picks another sequence; a failing
case is reproduced by its number and seed, and its folder is kept (the failure message names it).
"""

from __future__ import annotations

import os

import pytest

from tests.fuzz.fuzzer import Outcome, run_case, summary

CASES = int(os.environ.get("ROBODESC_FUZZ_CASES", "300"))
SEED = int(os.environ.get("ROBODESC_FUZZ_SEED", "17"))


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory: pytest.TempPathFactory) -> list[Outcome]:
    root = tmp_path_factory.mktemp("fuzz")
    return [run_case(i, SEED, root) for i in range(CASES)]


def test_fuzz_no_crash_hang_or_bad_output(outcomes: list[Outcome]) -> None:
    bad = [o for o in outcomes if o.status in ("crash", "hang", "bad-output")]
    assert not bad, summary(bad)


def test_fuzz_no_blame_for_a_source_defect(outcomes: list[Outcome]) -> None:
    # Exit 1 says "robodesc's fault"; on a mutated source that is a false blame (or a real bug).
    blamed = [o for o in outcomes if o.status == "blame"]
    assert not blamed, summary(blamed)


def test_fuzz_batches_run_no_python_and_write_only_inside_their_output(outcomes: list[Outcome]) -> None:
    # escaped: a batch, or a compile through a meshes link out of its output folder; stray-file: a
    # file left in the working folder; abs-path: a view page naming this machine's paths.
    bad = [o for o in outcomes if o.status in ("ran-python", "escaped", "stray-file", "abs-path")]
    assert not bad, summary(bad)


def test_fuzz_failed_runs_leave_earlier_output(outcomes: list[Outcome]) -> None:
    # Outputs are staged, validated there and moved only on success (docs/diagnostics.md).
    partial = [o for o in outcomes if o.status == "partial-output"]
    assert not partial, summary(partial)


def test_fuzz_reaches_every_target_and_seed(outcomes: list[Outcome]) -> None:
    plain = {"urdf", "sdf", "usda", "usdc", "isaac", "mjcf", "ros2"}
    commands = {"view", "render", "dynamics"}
    # The clips (dynamics-video, render-video) are one case in ten of their commands: 300 cases
    # may hold none of one kind.
    reached = {o.target for o in outcomes} - {"dynamics-video", "render-video"}
    assert reached == plain | {f"batch-{t}" for t in plain} | commands
    assert len({o.seed_file for o in outcomes}) == 4
    assert any(o.status == "ok" for o in outcomes) and any(o.status == "refused" for o in outcomes)
