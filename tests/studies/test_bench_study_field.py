"""The study-cost benchmark (studies/bench_study_field.py) runs in fast mode and counts the solver work of both
field models (no timing is asserted)."""
import pytest


@pytest.mark.slow           # 14 s on the shared 2-core machine, most of it compiling and planning in a fresh process
def test_both_fields_solve_the_same_points_and_the_layered_one_costs_more(fast_run, read_csv):
    rows = read_csv(fast_run("bench_study_field") / "bench_study_field.csv")
    pixel, layered = rows
    assert (pixel["field"], layered["field"]) == ("parallel_plate", "layered")
    assert pixel["solves"] == layered["solves"] == "8"                 # 2 realisations x 2 voltages x 2 loads
    # the layered field adds its CG passes to every evaluation at 150 V and a field solve per 0 V point:
    # measured 1.8x the per-pixel study's FFT pairs on these 32² patches
    ratio = float(layered["fft_pairs"]) / float(pixel["fft_pairs"])
    assert ratio == pytest.approx(float(layered["fft_pair_ratio"]), rel=1e-12) and 1.2 < ratio < 4.0
    assert float(pixel["fft_pairs"]) > 0 and float(layered["cpu_s"]) > 0
