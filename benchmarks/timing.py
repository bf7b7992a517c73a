"""Warm wall times: the median of repeated runs within a time budget."""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable


def warm_timing(measure: Callable[[], float], first: float, repeats: int,
                budget: float) -> tuple[float, int]:
    """Median wall time of ``repeats`` warm runs, ``first`` being one of them; fewer runs when a
    run takes longer than ``budget / repeats`` (at least the first). Returns (median, count)."""
    samples = [first]
    count = max(1, min(repeats, int(budget // max(first, 1e-9))))
    while len(samples) < count:
        samples.append(measure())
    return statistics.median(samples), len(samples)


def median_time(call: Callable[[], object], repeats: int, budget: float) -> tuple[float, int]:
    """:func:`warm_timing` of ``call``, its first run included."""
    start = time.perf_counter()
    call()
    first = time.perf_counter() - start

    def again():
        begin = time.perf_counter()
        call()
        return time.perf_counter() - begin

    return warm_timing(again, first, repeats, budget)
