"""The adhesive validation and cost experiments run in fast mode, and their numbers hold."""
import pytest


def test_maugis_dugdale_pull_off(fast_run, read_csv):
    rows = read_csv(fast_run("adhesive_sphere") / "adhesive_sphere.csv")
    coarse, fine, extrapolated = (float(row["relative_error"]) for row in rows)
    # λ = 0.3 (between DMT and JKR): the BEM pull-off converges to first order in the pixel from the tensile side
    # (measured +2.8 % at 64², +1.5 % at 128²); the Richardson extrapolation meets Maugis (1992) to 0.26 %
    assert 0 < fine < coarse < 0.04
    assert abs(extrapolated) < 0.01


def test_electrostatic_cost_table(fast_run, read_csv):
    rows = read_csv(fast_run("bench_interactions") / "bench_interactions.csv")
    solves = [row for row in rows if row["section"].startswith("electrostatic")]
    assert all(row["converged"] == "True" for row in solves)
    cold = [row for row in solves if row["section"] == "electrostatic_cold"]
    continued = [row for row in solves if row["section"] == "electrostatic_continuation"]
    # the continuation starts from the last voltage's gap, the cold solve from the hard wall: in a non-convex
    # problem they may end on neighbouring equilibria (measured at 64²: 0 and 6 pixels of 4096 apart)
    for a, b in zip(cold, continued):
        assert float(b["contact_fraction"]) == pytest.approx(float(a["contact_fraction"]), abs=0.005)
    assert float(cold[1]["contact_fraction"]) > float(cold[0]["contact_fraction"])
    # the sweep row: the continuation's FFT pairs and their share of the cold solves'
    (sweep,) = [row for row in rows if row["section"] == "sweep"]
    pairs = [sum(float(row["fft_pairs"]) for row in kind) for kind in (cold, continued)]
    assert float(sweep["fft_pairs"]) == pairs[1]
    assert float(sweep["fft_pair_ratio"]) == pytest.approx(pairs[1] / pairs[0], rel=1e-12)
