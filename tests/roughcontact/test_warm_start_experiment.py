"""The warm-start study (experiments/warm_start.py) runs in fast mode and its files are self-consistent."""
import pytest


@pytest.fixture(scope="module")
def output(fast_run):
    return fast_run("warm_start")


STARTS = ("cold", "nested", "previous", "secant")


def test_sweep_rows(output, read_csv):
    sweeps = read_csv(output / "warm_start_sweep.csv")
    assert [(float(r["tol"]), r["start"]) for r in sweeps] == [(tol, start) for tol in (1e-6, 1e-8) for start in STARTS]
    for cold, nested, *warm in zip(*(sweeps[k::4] for k in range(4))):
        assert float(cold["ratio"]) == float(cold["iteration_ratio"]) == 1.0
        # 64² does not halve down to 2 × 64 px: the nested start falls back to the PK start, the same iterates
        assert nested["iterations"] == cold["iterations"]
        for r in warm:
            # a warm start never costs iterations on this sweep; the ratios are what the file says they are
            assert int(r["iterations"]) < int(cold["iterations"])
            assert float(r["iteration_ratio"]) == pytest.approx(int(cold["iterations"]) / int(r["iterations"]))
            assert float(r["ratio"]) == pytest.approx(float(cold["time_s"]) / float(r["time_s"]))


def test_step_rows_and_figure(output, read_csv):
    steps = read_csv(output / "warm_start_steps.csv")
    assert [(int(r["step"]), r["start"]) for r in steps] == [(k, s) for k in (3, 10, 20) for s in STARTS]
    for cold, nested, *warm in zip(*(steps[k::4] for k in range(4))):
        assert float(cold["first_residual"]) == pytest.approx(1.0)   # the cold start's residual is the scale
        assert nested["first_residual"] == cold["first_residual"]    # the fallback to the PK start at 64²
        for r in warm:
            assert 0 < float(r["first_residual"]) < 1                   # a warm start begins closer
            assert 0 < float(r["decades"]) < float(cold["decades"])
    assert (output / "warm_start_residuals.png").stat().st_size > 1000
