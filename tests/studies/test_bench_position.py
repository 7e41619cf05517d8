"""The displacement-control benchmark runs in fast mode: both controls reach the same flat position, every solve
and sweep converges."""


def test_both_controls_reach_the_same_equilibrium(fast_run, read_csv):
    rows = read_csv(fast_run("bench_position") / "bench_position.csv")
    points = [row for row in rows if row["section"] == "point"]
    sweeps = [row for row in rows if row["section"] == "sweep"]
    assert len(points) == 6 and len(sweeps) == 6
    assert all(row["converged"] == "True" for row in rows)
    for position, load in zip(points[::2], points[1::2]):
        assert (position["control"], load["control"]) == ("penetration", "mean_pressure")
        assert position["contact_fraction"] == load["contact_fraction"]
        # the solves' tolerance is 1e-8 of the rms height
        assert abs(float(load["flat_position_difference_rms"])) <= 1e-8
    for row in sweeps:
        assert float(row["flat_position_difference_rms"]) <= 1e-8
