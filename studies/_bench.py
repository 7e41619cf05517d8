"""The benchmark scripts' shared helpers: a ``--repeat`` argument, the best of repeated timings and costs summed
over realisations. Imported by the scripts beside it (``python studies/bench_x.py`` puts ``studies/`` first on
the path); not a study itself.
"""
from __future__ import annotations

import argparse
import time


def count_argument(text) -> int:
    """An ``argparse`` type: a whole number of at least 1 (a study's ``--repeat``)."""
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


def best_of(solve, repeat: int = 1, clock=time.perf_counter) -> tuple:
    """The result of ``solve()`` and its shortest time [s] by ``clock`` over ``repeat`` calls (for deterministic
    solves: the least-disturbed timing)."""
    best = float("inf")
    for _ in range(repeat):
        start = clock()
        result = solve()
        best = min(best, clock() - start)
    return result, best


def summed_ratios(rows, group: tuple, reference, columns=("fft_pairs", "time_s")) -> list:
    """Benchmark rows (dicts) summed over everything not in ``group`` (e.g. over patch realisations), one row per
    group with the count, the sums of ``columns`` and each sum's ratio to the sum of the group ``reference(key)``
    (``key`` the group's values): the cost of solves whose single runs scatter with their path."""
    sums = {}
    for row in rows:
        key = tuple(row[name] for name in group)
        total = sums.setdefault(key, dict.fromkeys(columns, 0.0) | {"count": 0})
        for name in columns:
            total[name] += row[name]
        total["count"] += 1
    return [dict(zip(group, key), count=total["count"],
                 **{name: total[name] for name in columns},
                 **{f"{name}_ratio": total[name] / sums[reference(key)][name] for name in columns})
            for key, total in sums.items()]
