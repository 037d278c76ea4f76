"""Which job a local worker runs next: neighbours in the job list go to the same worker.

Jobs next to each other in a plan usually share meshes: one description package's robots, a
folder of variants, a sweep of one input. A worker keeps the meshes it has read
(:func:`robodesc.meshes.data.keep_across_runs`), so handing it its neighbours' jobs saves reading
them again; handing out jobs in list order to whichever worker is free would make every worker
read every family's meshes (a third more mesh reading on the 100-robot corpus with two workers).

So each worker starts on its own contiguous share of the list and works through it in order. A
worker whose share is done takes the back half of the largest share left (work stealing), so the
workers still finish together. The order only decides where a job runs, never what it writes.
"""

from __future__ import annotations


class Lanes:
    """``count`` workers' shares of ``total`` jobs, as ``[next, end)`` ranges of job indexes."""

    def __init__(self, total: int, count: int) -> None:
        count = max(1, min(count, total))
        bounds = [total * lane // count for lane in range(count + 1)]
        self.ranges = [[bounds[lane], bounds[lane + 1]] for lane in range(count)]

    def take(self, lane: int, ahead: bool = False) -> int | None:
        """The index of the next job for ``lane``, or None when no job is left for anyone.

        ``ahead``: a job to queue behind the one the worker is running. Only from its own share,
        and never the share's last job, which stays free for a worker that runs dry to take
        rather than wait behind another worker's queue at the end of the batch."""
        share = self.ranges[lane]
        if ahead:
            if share[1] - share[0] < 2:
                return None
        elif share[0] == share[1]:
            victim = max(self.ranges, key=lambda r: r[1] - r[0])
            left = victim[1] - victim[0]
            if left == 0:
                return None
            # The back half (the whole of a last job): the victim keeps the jobs next to its current one.
            middle = victim[1] - (left + 1) // 2
            share[0], share[1] = middle, victim[1]
            victim[1] = middle
        index = share[0]
        share[0] += 1
        return index
