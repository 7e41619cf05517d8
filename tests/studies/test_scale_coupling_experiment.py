"""The scale-coupling experiment (studies/scale_coupling.py) runs in fast mode: one row per variant,
realisation and load with finite differences of d_eq, real contact and A_R within a loose bound, the
differences are those of the written values, and the summary names every variant."""
import numpy as np
import pytest

# The fast mode's 32² patches carry a few micro-contacts each and its law has 7 nodes (measured at 100 V:
# d_eq +24 % on average, 38 % at most; real contact and A_R within 29 % and 28 %); the 4-node thinned law is
# a poor table (d_eq up to +510 %) and is only checked for finiteness. Far beyond 50 % the coupling is broken.
BOUND = 0.5
COLUMNS = ("equivalent_gap_um", "contact_fraction", "ridge_area_fraction")


@pytest.fixture(scope="module")
def output(load_experiment, fast_run):
    return load_experiment("scale_coupling"), fast_run("scale_coupling")


def test_rows_and_differences(output, read_csv):
    module, path = output
    rows = read_csv(path / "scale_coupling.csv")
    variants = {(row["law"], row["law_nodes"], row["ridge_pixels"]) for row in rows}
    assert variants == {("own", "7", "16"), ("own", "7", "32"), ("own", "4", "16")}
    assert len(rows) == len(variants) * 2 * 2                    # two realisations, two loads, one voltage
    for row in rows:
        assert row["voltage_V"] == "100.0" and row["coupled_converged"] == "True"
        assert all(float(row[key]) > 0 for key in ("resolved_cpu_s", "law_cpu_s", "ridge_cpu_s"))
        for column in COLUMNS:
            full, coupled = float(row[f"full_{column}"]), float(row[f"coupled_{column}"])
            difference = float(row[f"{column}_difference"])
            assert np.isfinite(difference) and difference == pytest.approx(coupled / full - 1, rel=1e-12)
            if row["law_nodes"] == "7":
                assert abs(difference) < BOUND, (column, row)


def test_summary_names_every_variant(output, read_csv):
    module, path = output
    lines = module.summarise(read_csv(path / "scale_coupling.csv"))
    assert [line for line in lines if line.startswith("law ")] == [
        "law own, 7 nodes, ridges 16 px per period:", "law own, 7 nodes, ridges 32 px per period:",
        "law own, 4 nodes, ridges 16 px per period:"]
    assert sum("CPU: coupled" in line for line in lines) == 3
