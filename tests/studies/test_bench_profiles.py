"""The profile preconditioning benchmark runs in fast mode and its rows are self-consistent (no timing is asserted)."""


def test_both_settings_solve_every_profile(fast_run, read_csv, load_experiment):
    load_experiment("field_check")          # the script takes its profiles from studies/field_check.py
    rows = read_csv(fast_run("bench_profiles") / "bench_profiles.csv")
    assert {row["preconditioned"] for row in rows} == {"True", "False"}
    for row in rows:
        # 2 profiles x 2 loads; each step costs at least one FFT pair, the K⁻¹ steps one more
        assert int(row["solves"]) == 4 and float(row["fft_pairs"]) >= int(row["steps"]) > 0
    preconditioned = next(row for row in rows if row["preconditioned"] == "True")
    assert float(preconditioned["fft_pairs"]) >= 2 * int(preconditioned["steps"]) - 4
