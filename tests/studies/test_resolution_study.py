"""The resolution study (studies/resolution.py) in fast mode, and its Richardson step on sequences with a
known limit."""
import numpy as np
import pytest

from roughcontact.study.scene import load_scene


@pytest.fixture(scope="module")
def study(load_experiment, tmp_path_factory):
    """The module, the output directory of its fast run and that run's convergence table."""
    module, path = load_experiment("resolution"), tmp_path_factory.mktemp("resolution")
    _, convergence, _ = module.main(["--fast", "--output", str(path)])
    return module, path, convergence


@pytest.mark.parametrize("order", [1.0, 1.5, 2.0])
def test_richardson_recovers_the_limit_and_the_order(load_experiment, order):
    module = load_experiment("resolution")
    pixels = 8.0 / 2 ** np.arange(5)
    converged, observed, regular = module.richardson(3.0 - 0.4 * pixels ** order)
    assert regular and observed == pytest.approx(order, rel=1e-12)
    assert converged == pytest.approx(3.0, rel=1e-12)


def test_richardson_declines_an_irregular_sequence(load_experiment):
    module = load_experiment("resolution")
    converged, _, regular = module.richardson([1.0, 1.3, 1.1, 1.25, 1.2])     # oscillating: no order
    assert not regular and converged == 1.2                                    # the finest value stands
    converged, _, regular = module.richardson([1.0, 1.5, 1.75, 1.8, 1.81])     # orders 1, 2.3, 2.3: finest two agree
    assert regular


def test_fast_run_rows_and_their_consistency(study, read_csv):
    module, path, convergence = study
    rows = read_csv(path / "resolution_profiles.csv")
    assert len(rows) == 2 * len(module.FAST_PIXELS) * len(module.NORMAL_FORCES) * len(module.SOLVES)
    assert all(row["converged"] == "True" for row in rows)
    stack = load_scene().screen.stack()
    for row in rows:
        # Eq. 25 and the field-equivalent gap invert Eq. 21 at the mean attraction of their model
        per_pixel, layered = float(row["fel_per_pixel_Pa"]), float(row["fel_layered_Pa"])
        assert float(stack.attraction(float(row["deq_um"]) * 1e-6, 200.0)) == pytest.approx(per_pixel, rel=1e-9)
        assert float(stack.attraction(float(row["field_deq_um"]) * 1e-6, 200.0)) == pytest.approx(layered, rel=1e-9)
        # with air breakdown at its contact lines (the default) the layered field holds every contact at ε0 E_bd²/2,
        # Eq. 23 three times that: at 200 V it attracts less than the per-pixel law on every gap (measured 0.40-0.68)
        assert 0.3 * per_pixel < layered < 0.8 * per_pixel
    by_law = {(row["normal_force_N"], row["law"], row["pixels"]): row for row in rows}
    # the attraction closes the gap: at 200 V more contact and a smaller d_eq than the hard wall at 0 V
    for force in ("0.5", "2.0"):
        for law in ("layered", "parallel_plate"):
            assert float(by_law[force, law, "512"]["deq_um"]) < float(by_law[force, "hard_wall", "512"]["deq_um"])


def test_convergence_table_and_preset_errors(study, read_csv):
    module, path, convergence = study
    table = read_csv(path / "resolution_convergence.csv")
    assert len(table) == len(module.NORMAL_FORCES) * len(module.SOLVES) * len(module.QUANTITIES)
    rows = read_csv(path / "resolution_profiles.csv")
    for entry in table:
        mine = [float(row[entry["quantity"]]) for row in rows if row["normal_force_N"] == entry["normal_force_N"]
                and row["law"] == entry["law"] and row["pixels"] == "128"]
        assert float(entry["mean_128"]) == pytest.approx(np.mean(mine), rel=1e-12)
        assert float(entry["error_draft"]) == pytest.approx(float(entry["mean_128"]) / float(entry["converged_value"])
                                                            - 1, rel=1e-9, abs=1e-15)
    errors = module.preset_errors(convergence)
    assert sorted(errors) == [128, 256, 512]
    fel = [entry for entry in convergence if entry["quantity"] == "fel_layered_Pa" and entry["law"] == "layered"]
    assert errors[128][0] == max(abs(entry["error_draft"]) for entry in fel) > 0
    for entry in table:                     # paired 95 % half-width of two realisations: finite, 0 at the finest
        assert float(entry["ci_draft"]) >= 0 and float(entry["ci_reference"]) == 0.0


def test_tables_rebuilt_from_stored_rows_are_the_runs(study, tmp_path):
    module, path, convergence = study
    _, again, _ = module.main(["--fast", "--profiles", str(path / "resolution_profiles.csv"), "--output",
                               str(tmp_path)])
    assert [entry["converged_value"] for entry in again] == [entry["converged_value"] for entry in convergence]


def test_correction_is_measured_on_some_realisations_and_tested_on_others(study, read_csv):
    module, path, _ = study
    rows = read_csv(path / "resolution_profiles.csv")
    for entry in read_csv(path / "resolution_correction.csv"):
        def fel(realisation, pixels):
            return next(float(row["fel_layered_Pa"]) for row in rows if row["law"] == "layered"
                        and row["normal_force_N"] == entry["normal_force_N"] and row["realisation"] == realisation
                        and row["pixels"] == pixels)
        factor = fel("0", "512") / fel("0", entry["pixels"])          # even realisation: the measurement
        assert float(entry["factor"]) == pytest.approx(factor, rel=1e-12)
        ratio = fel("1", entry["pixels"]) / fel("1", "512")           # odd realisation: the test
        assert float(entry["error_corrected"]) == pytest.approx(factor * ratio - 1, rel=1e-9, abs=1e-15)


def test_errors_are_against_the_reference_pixel_and_finer_pixels_measure_the_edges(load_experiment):
    module = load_experiment("resolution")
    pixels = list(module.PIXELS_PER_PERIOD)
    assert pixels[module.reference_column(pixels)] == module.REFERENCE_PIXELS == 4096
    assert module.reference_column([128, 256, 512]) == 2                  # a shorter sequence: its finest
    sequence = [1.0, 1.3, 1.1, 1.25, 1.2, 1.22, 1.5, 1.6]                   # irregular: no Richardson
    rows = [{"realisation": realisation, "normal_force_N": force, "law": law, "pixels": n, "converged": True,
             **{quantity: value * (1 + 0.1 * realisation) for quantity in module.QUANTITIES}}
            for realisation in (0, 1) for force in module.NORMAL_FORCES for _, law in module.SOLVES
            for n, value in zip(pixels, sequence)]
    for entry in module.convergence_rows(rows, pixels):
        assert not entry["richardson"] and entry["converged_value"] == pytest.approx(1.22 * 1.05, rel=1e-12)
        assert entry["error_reference"] == pytest.approx(1.1 / 1.22 - 1, rel=1e-12)
        # paired over the realisations: their differences from their own 4096-pixel values, −0.12 and −0.132
        spread = np.std([-0.12, -0.132], ddof=1)
        assert entry["ci_reference"] == pytest.approx(1.96 * spread / np.sqrt(2) / (1.22 * 1.05), rel=1e-9)
        assert entry["beyond_reference"] == pytest.approx(1.6 / 1.22 - 1, rel=1e-12)
