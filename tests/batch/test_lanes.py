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
