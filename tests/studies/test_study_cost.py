"""The study-cost calibration (studies/study_cost.py) runs in fast mode: one row per voltage, its FFT pairs
counted per solve, the cost of a solve in Green-operator applications against the model of
roughcontact.study.cost, the peak memory in patch arrays (no timing is asserted beyond positivity)."""
import pytest


def test_the_fast_calibration_rows(fast_run, read_csv):
    rows = read_csv(fast_run("study_cost") / "study_cost.csv")
    assert [(row["n"], row["voltage_V"]) for row in rows] == [("32", "0.0"), ("32", "100.0")]
    for row in rows:
        pairs, largest = float(row["pairs_mean"]), float(row["pairs_max"])
        assert 0 < pairs <= largest and float(row["pair_seconds"]) > 0
        assert float(row["ratio"]) == pytest.approx(float(row["applications"]) / pairs, rel=1e-12)
        assert float(row["model_applications"]) > 0 and 5 < float(row["peak_patch_arrays"]) < 200
    # the attraction costs more pairs and more memory than the hard wall
    assert float(rows[1]["pairs_mean"]) > float(rows[0]["pairs_mean"])
    assert float(rows[1]["peak_patch_arrays"]) > float(rows[0]["peak_patch_arrays"])
