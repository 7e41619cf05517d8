"""The benchmark problem of the solver studies in ``studies/`` (docs/dev/benchmarks.md), and a contact-set count.

The benchmark surface is a seeded self-affine patch on a periodic 1 mm × 1 mm window whose short-wavelength
cutoff is :data:`CUTOFF_PIXELS` pixels of each grid: every grid resolves its roughness with the same number of
pixels per shortest wavelength, so finer grids carry more (shorter-wavelength) roughness and need more
iterations — the realistic use and the hard case for the solver. Results depend only on p̄/E*.
"""
from __future__ import annotations

import numpy as np

import surfaces

#: Side of the periodic square window [m].
LENGTH = 1e-3
#: Contact modulus E* [Pa] (results scale with p̄/E*; only the ratio matters).
E_STAR = 1e6
#: Default mean pressure of the benchmark [Pa]: 0.01 E*, i.e. A/A0 ≈ 0.2 at rms slope 0.1.
PRESSURE = 0.01 * E_STAR
#: Hurst exponent, spectral rms slope and short cutoff (in pixels of each grid) of the benchmark surface.
HURST, RMS_SLOPE, CUTOFF_PIXELS = 0.8, 0.1, 4
#: Steps of the benchmark's load sweep, p̄ = PRESSURE · k / SWEEP_STEPS for k = 1 … SWEEP_STEPS.
SWEEP_STEPS = 20


def rough_surface(n: int, rng=0, periodic: bool = True) -> surfaces.HeightField:
    """The benchmark surface on an n² grid (``rng`` 0: the one of docs/dev/benchmarks.md); ``periodic=False``: the
    same heights on a free-surface (non-periodic) grid."""
    grid = surfaces.Grid((n, n), (LENGTH, LENGTH), periodic=True)
    field = surfaces.self_affine(grid, hurst=HURST, rms_slope=RMS_SLOPE, short_cutoff=CUTOFF_PIXELS * LENGTH / n,
                                 rng=rng)
    if periodic:
        return field
    return surfaces.HeightField(surfaces.Grid((n, n), (LENGTH, LENGTH), periodic=False), field.heights)


def sweep_pressures(pressure: float = PRESSURE, steps: int = SWEEP_STEPS) -> np.ndarray:
    """The load sweep's mean pressures [Pa]: ``pressure`` · k / ``steps``, k = 1 … ``steps``."""
    return pressure * np.arange(1, steps + 1) / steps


def contact_patches(contact: np.ndarray, periodic: bool = True) -> int:
    """Number of contact patches of a boolean contact map: 4-connected pixels; on a ``periodic`` grid the
    patches that touch across the edges count once."""
    import scipy.ndimage
    import scipy.sparse
    import scipy.sparse.csgraph

    labels, count = scipy.ndimage.label(contact)
    if not periodic:
        return int(count)
    pairs = [(labels[0], labels[-1]), (labels[:, 0], labels[:, -1])]
    first = np.concatenate([a[(a > 0) & (b > 0)] for a, b in pairs])
    second = np.concatenate([b[(a > 0) & (b > 0)] for a, b in pairs])
    links = scipy.sparse.coo_matrix((np.ones(first.size), (first, second)), shape=(count + 1, count + 1))
    return int(scipy.sparse.csgraph.connected_components(links, directed=False)[0] - 1)    # minus the label 0
