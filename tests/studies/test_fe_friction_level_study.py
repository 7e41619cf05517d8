"""studies/fe_friction_level.py on the packaged FE table: the like-for-like comparison is at equal F_T/F_N, the
FE at μ0 at 0 V, and its columns are what they say (numpy only)."""
import numpy as np
import pytest

from roughcontact.fe.feed import FEAreaReduction


@pytest.fixture(scope="module")
def script(load_experiment):
    return load_experiment("fe_friction_level")


@pytest.fixture(scope="module")
def rows(script):
    return script.level_rows(FEAreaReduction.from_summary())


def test_zero_volts_compares_the_fe_at_mu0(rows):
    for row in rows:
        if row["voltage_V"] == 0.0:
            assert row["friction_F_T_over_F_N"] == 0.26                # the seed's law at 0 V: μ0 exactly
        else:
            assert row["friction_F_T_over_F_N"] > 0.26
        # the two mappings of one FE length ratio: 1 − r² = (1 − r)(1 + r)
        r = 1 - row["fe_reduction_linear"]
        assert row["fe_reduction_isotropic"] == pytest.approx(1 - r ** 2, rel=1e-12)
        assert 0 < row["fe_reduction_linear"] < row["fe_reduction_isotropic"] < 1


def test_the_fe_reduction_grows_with_load_and_friction(rows):
    at = {(row["normal_force_N"], row["voltage_V"]): row for row in rows}
    for voltage in (0.0, 100.0):
        values = [at[(f, voltage)]["fe_reduction_linear"] for f in (0.5, 1.0, 1.5, 2.0)]
        assert np.all(np.diff(values) > 0)
    assert all(at[(f, 100.0)]["fe_reduction_linear"] > at[(f, 0.0)]["fe_reduction_linear"] for f in (1.0, 2.0))


def test_measured_values_and_exponents(script, rows):
    measured = [row for row in rows if np.isfinite(row["sirin_2019b_reduction"])]
    assert len(measured) == 4
    exponents = {(row["voltage_V"], row["column"]): row for row in script.exponent_rows(rows)}
    assert exponents[(0.0, "sirin_2019b_reduction")]["ratio_per_doubling"] == pytest.approx(15 / 8)
    for row in exponents.values():
        assert row["exponent"] == pytest.approx(np.log2(row["ratio_per_doubling"]), rel=1e-12)
