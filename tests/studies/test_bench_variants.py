"""The parameter-study benchmark (studies/bench_variants.py) runs in fast mode: the study of 2 inputs at two
levels costs at most 2k + 1 single studies, here less, since one variant is the baseline (no timing is
asserted)."""


def test_a_one_at_a_time_study_costs_less_than_its_single_studies(fast_run, read_csv):
    study, singles = read_csv(fast_run("bench_variants") / "bench_variants.csv")
    assert (study["run"], singles["run"]) == ("parameter study", "single studies")
    assert study["variants"] == singles["variants"] == "5"
    # 1 realisation x 2 voltages per study, 2 loads per task: 5 single studies are 10 tasks and 20 solves; the
    # variant with the layer's baseline modulus shares the baseline's 2 tasks, so the study solves 8 tasks
    assert (singles["tasks"], singles["solves"], singles["budget_solves"]) == ("10", "20", "20")
    assert (study["tasks"], study["solves"]) == ("8", "16")
    assert float(study["cpu_s"]) > 0 and float(singles["cpu_s"]) > 0
