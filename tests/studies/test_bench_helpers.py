"""The benchmark scripts' helpers (studies/_bench.py): costs summed over realisations, the --repeat type."""
import argparse

import pytest


def test_summed_ratios_sums_over_the_rest_and_divides_by_the_reference_group(load_experiment):
    summed_ratios = load_experiment("_bench").summed_ratios
    rows = [dict(case="a", law=law, seed=seed, fft_pairs=pairs, time_s=seconds)
            for law, seed, pairs, seconds in (("plate", 0, 10.0, 1.0), ("plate", 1, 30.0, 3.0),
                                               ("layered", 0, 50.0, 2.0), ("layered", 1, 70.0, 10.0))]
    totals = {row["law"]: row for row in summed_ratios(rows, ("case", "law"), lambda key: (key[0], "plate"))}
    assert totals["layered"]["count"] == 2 and totals["layered"]["fft_pairs"] == 120.0
    # the ratio of the sums (120/40 = 3, 12/4 = 3), not the mean of the per-seed ratios (5 and 2.33)
    assert totals["layered"]["fft_pairs_ratio"] == 3.0 and totals["layered"]["time_s_ratio"] == 3.0
    assert totals["plate"]["fft_pairs_ratio"] == 1.0


def test_repeat_is_a_whole_number_of_at_least_one(load_experiment):
    count_argument = load_experiment("_bench").count_argument
    assert count_argument("3") == 3
    with pytest.raises(argparse.ArgumentTypeError, match="at least 1, got 0"):
        count_argument("0")
