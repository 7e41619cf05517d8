"""The field evaluation's pass benchmark runs in fast mode and prints each pass against the FFT pair (no timing
is asserted beyond the rows' own consistency)."""


def test_every_pass_is_timed_against_the_elastic_fft_pair(fast_run, read_csv):
    rows = read_csv(fast_run("bench_field_passes") / "bench_field_passes.csv")
    assert [row["pass"] for row in rows] == ["elastic FFT pair", "field FFT pair (M D)", "start pass",
                                             "CG pass, pointwise", "output pass"]
    pair = float(rows[0]["ms"])
    assert float(rows[0]["fft_pairs"]) == 1.0
    for row in rows:
        assert float(row["ms"]) > 0
        assert float(row["fft_pairs"]) == float(row["ms"]) / pair
