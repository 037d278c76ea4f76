"""The local pool's order: each worker works through its own contiguous share of the jobs, and one
that runs out takes the back half of the largest share left."""

from __future__ import annotations

import random

import pytest

from robodesc.batch.lanes import Lanes


@pytest.mark.parametrize("total, workers", [(0, 2), (1, 4), (2, 2), (7, 3), (100, 2), (100, 8), (5, 1)])
def test_every_job_is_handed_out_once(total: int, workers: int) -> None:
    lanes = Lanes(total, workers)
    rng = random.Random(total * 31 + workers)
    seen: list[int] = []
    active = list(range(len(lanes.ranges)))
    while active:
        lane = rng.choice(active)  # workers finish in any order
        index = lanes.take(lane)
        if index is None:
            active.remove(lane)
        else:
            seen.append(index)
    assert sorted(seen) == list(range(total))


def test_shares_are_contiguous_and_a_free_worker_steals_the_back_half() -> None:
    lanes = Lanes(10, 2)
    assert lanes.ranges == [[0, 5], [5, 10]]
    assert [lanes.take(0) for _ in range(5)] == [0, 1, 2, 3, 4]
    assert lanes.take(1) == 5  # worker 1 is still on its first job when worker 0 runs dry
    assert lanes.take(0) == 8  # worker 1 had 6..9 left: worker 0 takes 8 and 9
    assert lanes.take(1) == 6 and lanes.take(1) == 7
    assert lanes.take(0) == 9
    assert lanes.take(1) is None and lanes.take(0) is None


def test_more_workers_than_jobs() -> None:
    lanes = Lanes(2, 8)
    assert len(lanes.ranges) == 2


def test_a_queued_job_never_takes_a_share_s_last_job_or_steals() -> None:
    lanes = Lanes(6, 2)  # [0, 3) and [3, 6)
    assert lanes.take(0) == 0 and lanes.take(0, ahead=True) == 1
    assert lanes.take(0, ahead=True) is None  # 2 is the share's last: left for whoever is idle
    assert lanes.take(1) == 3 and lanes.take(1, ahead=True) == 4
    assert lanes.take(1, ahead=True) is None
    assert lanes.take(1) == 5
    assert lanes.take(1) == 2  # worker 1, idle, takes the job worker 0 did not queue
    assert lanes.take(0, ahead=True) is None and lanes.take(0) is None


@pytest.mark.parametrize(
    "argv, starts",
    [
        (["batch", "robots/", "-o", "out"], True),
        (["batch", "robots/", "-o", "out", "--executor", "local"], True),
        (["batch", "robots/", "-o", "out", "--executor", "ray"], False),
        (["batch", "robots/", "--executor=ray"], False),
        (["batch", "--help"], False),
        (["compile", "robot.urdf", "-o", "r.usda"], False),
        ([], False),
    ],
)
def test_the_console_script_starts_the_fork_server_for_local_batches_only(argv: list[str], starts: bool) -> None:
    from robodesc._console import _runs_local_workers

    assert _runs_local_workers(argv) is starts
