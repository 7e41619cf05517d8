"""The spectrum study (experiments/preconditioner_spectrum.py) runs in fast mode, and its numbers obey the theory
they are meant to show."""
import numpy as np
import pytest


@pytest.fixture(scope="module")
def study(load_experiment, fast_run, read_csv):
    path = fast_run("preconditioner_spectrum")
    return load_experiment("preconditioner_spectrum"), path, read_csv(path / "spectrum.csv")


def test_spectrum_files(study):
    _, path, rows = study
    assert [int(row["n"]) for row in rows] == [32, 64, 128] and (path / "spectrum.png").stat().st_size > 0
    assert rows[-1]["kappa"] == "" and all(row["kappa"] for row in rows[:2])     # 128²: measured rate only


def test_spectrum_obeys_the_theory(study):
    module, _, rows = study
    dense = rows[:2]
    for row in dense:
        # S_cc ≥ (K_cc)⁻¹ (Schur complement of K⁻¹), so the spectrum starts at 1; round-off of the dense
        # eigensolver is ~1e-13 here
        assert float(row["lambda_min"]) >= 1 - 1e-9
        # keeping the Schur term on a wider band of non-contact pixels can only lower κ
        assert float(row["kappa"]) > float(row["kappa_band_1px"]) > float(row["kappa_band_2px"]) > 1
        # the solver's linear phase runs at CG's rate for this κ: measured 0.99 (32²) and 0.90 (64²) of the
        # bound; 15 % allows for contact-set changes still inside the last 10 steps
        assert float(row["measured_decades_per_step"]) == pytest.approx(
            float(row["cg_bound_decades_per_step"]), rel=0.15)
    # finer grids (more roughness scales) condition worse: κ rises, and with it the steps
    implied = [float(row["implied_kappa"]) for row in rows]
    assert implied == sorted(implied) and float(dense[1]["kappa"]) > float(dense[0]["kappa"])


def test_spectrum_helpers_against_known_cases(study):
    module = study[0]
    rng = np.random.default_rng(0)
    basis = rng.standard_normal((6, 6))
    matrix = basis @ basis.T + 6 * np.eye(6)
    # Vᵀ M V: same spectrum as the compression by an explicit orthonormal zero-mean basis (QR of I − 11ᵀ/m)
    explicit = np.linalg.qr(np.eye(6) - 1 / 6)[0][:, :5]
    np.testing.assert_allclose(np.linalg.eigvalsh(module.zero_mean_compression(matrix)),
                               np.linalg.eigvalsh(explicit.T @ matrix @ explicit), rtol=1e-12)
    # preconditioning by the exact inverse of the compressed operator, V (Vᵀ M V)⁻¹ Vᵀ, leaves only 1s
    exact = explicit @ np.linalg.inv(explicit.T @ matrix @ explicit) @ explicit.T
    np.testing.assert_allclose(module.preconditioned_spectrum(matrix, exact), 1.0, rtol=1e-12)
    for kappa in (1.5, 4.0, 20.0):
        assert module.implied_kappa(module.cg_rate(kappa)) == pytest.approx(kappa, rel=1e-12)
