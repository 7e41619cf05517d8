"""Why every good start still leaves the fine solve ~25 steps: the spectrum of the preconditioned operator (a script;
docs/solver.md, "Why the linear phase sets the step count").

    python experiments/preconditioner_spectrum.py            # dense spectra 32² … 128², rates to 1024², ≈ 1 min
    python experiments/preconditioner_spectrum.py --fast     # ≤ 128², seconds (the CI smoke run)

Once the contact set I_c holds, the solver runs conjugate gradients on the compliance restricted to I_c,
A = K_cc, on the zero-mean subspace (load control), preconditioned with the restricted inverse kernel
S_cc = (K⁻¹)_cc. Their product has eigenvalues in [1, λ_max]: the identity A⁻¹ = S_cc − S_cn S_nn⁻¹ S_nc
(Schur complement of the inverse; n = outside I_c) gives S_cc ≥ A⁻¹. CG then gains at least
−log10((√κ − 1)/(√κ + 1)) decades per step, κ = λ_max/λ_min, whatever the start. On the benchmark surface of
``experiments/bench_contact.py`` at p̄ = 0.01 E* this writes to ``--output``:

* ``spectrum.csv``: for each grid, the contact-set size, and either the dense spectrum's λ_min, λ_max, κ, the
  share of eigenvalues above 2 and the CG bound [decades/step] (``--dense`` sizes), or only the κ implied by
  the measured rate; the measured linear-phase rate of the solver (the last ``RATE_STEPS`` steps at tol
  1e-10); and, on the dense grids, κ with the Schur term kept exactly on the band of non-contact pixels
  within ``--band`` pixels of I_c (how local the missing term is);
* ``spectrum.png``: the sorted eigenvalues of each dense grid.
"""
from __future__ import annotations

import argparse
import math
import os
import sys
from pathlib import Path

import numpy as np
import scipy.linalg
import scipy.ndimage

sys.path.insert(0, str(Path(__file__).resolve().parent))    # the benchmark's surface and the output writers, shared
from _output import save_semilogy, write_csv  # noqa: E402
from bench_contact import E_STAR, PRESSURE, rough_surface  # noqa: E402

from roughcontact import ElasticHalfSpace, solve_contact  # noqa: E402

RATE_STEPS = 10          # the measured rate: mean decades per step over the solve's last RATE_STEPS steps
TOL = 1e-10              # tight, so that the linear phase (contact set fixed) dominates the history


def kernel_images(half: ElasticHalfSpace):
    """The compliance K and the stiffness S = K⁻¹ of a unit pressure / displacement at pixel (0, 0): the
    operators' matrix entries, K_ij = k[x_i − x_j, y_i − y_j] on the periodic grid."""
    unit = np.zeros(half.grid.shape)
    unit[0, 0] = 1.0
    stiffness = np.empty_like(unit)
    half.stiffness_into(unit.copy(), stiffness)
    return half.displacement(unit), stiffness


def block(image, rows, columns, shape):
    """Dense matrix image[x_r − x_c, y_r − y_c] (periodic) between the flat pixel indices ``rows``, ``columns``."""
    (row_x, row_y), (column_x, column_y) = np.unravel_index(rows, shape), np.unravel_index(columns, shape)
    return image[(row_x[:, None] - column_x) % shape[0], (row_y[:, None] - column_y) % shape[1]]


def zero_mean_compression(matrix):
    """Vᵀ M V with V an orthonormal basis of the zero-mean vectors: the Householder reflection H that maps
    the unit constant vector to −e₁ has V as its last m − 1 columns, so Vᵀ M V = (H M H)[1:, 1:]."""
    m = matrix.shape[0]
    v = np.full(m, 1 / math.sqrt(m))
    v[0] += 1.0
    beta = 2 / (v @ v)
    p = beta * (matrix @ v)
    w = p - (beta / 2 * (v @ p)) * v
    return (matrix - np.outer(v, w) - np.outer(w, v))[1:, 1:]


def preconditioned_spectrum(compliance, preconditioner):
    """Eigenvalues of M A on the zero-mean subspace (ascending), from the symmetric Lᵀ A L with M = L Lᵀ."""
    lower = scipy.linalg.cholesky(zero_mean_compression(preconditioner), lower=True)
    return scipy.linalg.eigvalsh(lower.T @ zero_mean_compression(compliance) @ lower)


def cg_rate(kappa):
    """CG's guaranteed decades per step at condition number κ: −log10((√κ − 1)/(√κ + 1))."""
    root = math.sqrt(kappa)
    return -math.log10((root - 1) / (root + 1)) if kappa > 1 else math.inf


def implied_kappa(rate):
    """The κ whose CG bound is ``rate`` decades per step (the inverse of :func:`cg_rate`)."""
    factor = 10.0 ** -rate
    return ((1 + factor) / (1 - factor)) ** 2


def measured_rate(result) -> float:
    """Mean decades per step of the relative rms gap error over the solve's last ``RATE_STEPS`` steps."""
    residuals = result.residuals[-RATE_STEPS - 1:]
    return math.log10(residuals[0] / residuals[-1]) / (residuals.size - 1)


def band_kappa(mask, compliance, stiffness_image, contact, width):
    """κ of the preconditioner S_cc − S_cb S_bb⁻¹ S_bc: the Schur term kept exactly on the band b of non-contact
    pixels within ``width`` pixels (8-connected) of the contact set."""
    window = tuple(slice(n, 2 * n) for n in mask.shape)     # the middle tile of a 3 × 3 tiling: periodic dilation
    near = scipy.ndimage.binary_dilation(np.tile(mask, (3, 3)), np.ones((3, 3), bool), iterations=width)[window]
    band = np.flatnonzero(near & ~mask)
    coupling = block(stiffness_image, band, contact, mask.shape)
    schur = coupling.T @ scipy.linalg.solve(block(stiffness_image, band, band, mask.shape), coupling, assume_a="pos")
    eigenvalues = preconditioned_spectrum(compliance, block(stiffness_image, contact, contact, mask.shape) - schur)
    return eigenvalues[-1] / eigenvalues[0]


def grid_row(n, dense, bands):
    """The row of grid n², and its eigenvalues (None unless ``dense``)."""
    surface = rough_surface(n)
    half = ElasticHalfSpace(surface.grid, E_star=E_STAR)
    result = solve_contact(surface, half, mean_pressure=PRESSURE, tol=TOL)
    contact = np.flatnonzero(result.contact.ravel())
    rate = measured_rate(result)
    row = {"n": n, "contact_points": contact.size, "contact_fraction": result.contact_fraction,
           "measured_decades_per_step": rate, "implied_kappa": implied_kappa(rate), "iterations": result.iterations}
    if not dense:
        return row, None
    compliance_image, stiffness_image = kernel_images(half)
    compliance = block(compliance_image, contact, contact, half.grid.shape)
    eigenvalues = preconditioned_spectrum(compliance, block(stiffness_image, contact, contact, half.grid.shape))
    kappa = eigenvalues[-1] / eigenvalues[0]
    row.update(lambda_min=eigenvalues[0], lambda_max=eigenvalues[-1], kappa=kappa,
               share_above_2=float(np.mean(eigenvalues > 2)), cg_bound_decades_per_step=cg_rate(kappa))
    for width in bands:
        row[f"kappa_band_{width}px"] = band_kappa(result.contact, compliance, stiffness_image, contact, width)
    return row, eigenvalues


def plot_spectra(path, spectra):
    save_semilogy(path, {f"{n}²": (np.linspace(0, 1, values.size), values) for n, values in spectra.items()},
                  xlabel="eigenvalue rank / count", ylabel="eigenvalue of S_cc K_cc",
                  title="preconditioned contact-set operator")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--dense", type=int, nargs="+", default=[32, 64, 128],
                        help="grids whose spectrum is computed densely (O(m³), m contact points)")
    parser.add_argument("--rates", type=int, nargs="*", default=[256, 512, 1024],
                        help="larger grids: measured rate and implied κ only")
    parser.add_argument("--band", type=int, nargs="*", default=[1, 2, 4], help="Schur band widths [pixels]")
    parser.add_argument("--output", default="out/preconditioner_spectrum", help="output directory")
    parser.add_argument("--fast", action="store_true", help="32² and 64² dense, 128² rate only: a smoke run")
    args = parser.parse_args(argv)
    if args.fast:
        args.dense, args.rates, args.band = [32, 64], [128], [1, 2]
    os.makedirs(args.output, exist_ok=True)
    rows, spectra = [], {}
    for n, dense in [(n, True) for n in args.dense] + [(n, False) for n in args.rates]:
        row, eigenvalues = grid_row(n, dense, args.band)
        rows.append(row)
        if eigenvalues is not None:
            spectra[n] = eigenvalues
    columns = list(dict.fromkeys(key for row in rows for key in row))     # the dense grids' columns too
    write_csv(Path(args.output) / "spectrum.csv", rows, columns=columns, echo=True)
    plot_spectra(Path(args.output) / "spectrum.png", spectra)


if __name__ == "__main__":
    main()
