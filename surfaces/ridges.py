"""Synthetic fingerprint ridges as a physical height field [m] (see ``docs/guide/fingerprint.md``).

Construction (SFinGe-like, Cappelli et al. ICPR 2000; references in ``docs/guide/fingerprint.md``):

1. **Orientation field** of the ridges from singular points, Sherlock & Monro (1993) zero-pole model
   ``θ(z) = θ∞ + ½ [Σ_cores arg(z − z_c) − Σ_deltas arg(z − z_d)]`` (mod π), evaluated as the
   single-valued doubled-angle vector ``exp(2iθ)``. The generation domain is periodic (FFT); the zero-pole
   field is made periodic by blending it with its periodic images in a seam band (outside the window on
   non-periodic grids).
2. **Ridge growth**: random noise is grown by iterated orientation-steered Gabor filtering and clipping,
   ``f ← clip(γ Σ_k w_k(x) [G_k * f](x) / max|…|, −1, 1)``, with an FFT filter bank of ``K`` orientations
   (and of ridge frequencies when the period varies) interpolated linearly per pixel: first with broad
   filters (independent ridge domains nucleate; where domains of different phase meet, minutiae — ridge
   endings, bifurcations — remain), then with a narrow radial band that pins the ridge period. The growth
   runs on a coarse grid of about ``_PIXELS_PER_PERIOD`` pixels per ridge period.
3. **Phase and cross-section**: the analytic (one-sided) Gabor bank applied once to the grown pattern and
   interpolated exactly (zero-padded spectrum) to the full grid gives the local ridge phase ψ (0 on crests,
   π in furrows). The height is the smooth profile ``h = H/2 (1 + cos(ψ + a sin ψ))``, whose warp ``a`` sets the
   ridge/furrow width ratio (widths at mid-height), tapered to mid-height where the ridge amplitude vanishes
   (minutiae cores).
4. **Sweat pores**: dimples of given opening diameter and depth on random crest pixels at the given density.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.fft

from .validation import check_choice, check_finite_array, check_integer, check_positive, check_real, check_rng
from .grid import Grid
from .heightfield import HeightField

PATTERNS = ("arch", "tented_arch", "left_loop", "right_loop", "whorl")
_ALIASES = {"loop": "left_loop"}

# Published defaults (sources in docs/guide/fingerprint.md).
RIDGE_PERIOD = 0.45e-3          # [m] ≈ 0.43–0.48 mm adult mean ridge breadth (Kralík & Novotný 2003)
RIDGE_HEIGHT = 50e-6            # [m] crest-to-furrow height, ~50–100 µm (OCT, Adams et al. 2013)
RIDGE_WIDTH_RATIO = 1.5         # ridge width / furrow width: 0.27 mm ridges, 0.18 mm furrows at 0.45 mm period
PORE_DENSITY = 5.0e6            # [1/m²] = 500 cm⁻² (palm glands 518 cm⁻², Taylor & Machado-Moreira 2013)
PORE_DIAMETER = 120e-6          # [m] opening diameter, 88–220 µm (Ashbaugh 1999)
PORE_DEPTH = 20e-6              # [m] dimple depth seen by a flat counter-face (modelling choice, see docs)

_MIN_PIXELS_PER_PERIOD = 4.0    # below this the ridge profile cannot be resolved
_PIXELS_PER_PERIOD = 8.0        # resolution of the coarse growth grid
_N_ORIENTATIONS = 16            # orientation bins of the Gabor bank (11.25° apart)
# Growth stages (radial std of the Gabor lobe relative to the ridge wavenumber, angular std [rad], iterations):
# broad filters nucleate ridge domains (and so minutiae), then a narrow radial band pins the period.
_GROWTH_STAGES = ((0.25, 0.3, 20), (0.1, 0.4, 20))
_FREQUENCY_STEP = 1.1           # ratio of neighbouring ridge-frequency bins when the period varies
_GROWTH_GAIN = 3.0              # γ: over-amplification before clipping (SFinGe-style growth)
_SEAM_PERIODS = 3.0             # width of the periodic blending band of the orientation field, in periods
_TAPER = 0.3                    # ridge amplitude (relative to its median) below which the profile fades


# ---------------------------------------------------------------------------------------------------------
# Orientation field
# ---------------------------------------------------------------------------------------------------------
def _points(name, points):
    """Singular points as a tuple of ``(x, y)`` pairs [m], from a sequence of pairs (or none)."""
    array = check_finite_array(name, points) if len(points) else np.zeros((0, 2))
    if array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(f"{name} must be a sequence of (x, y) pairs in m, i.e. of shape (k, 2); got shape "
                         f"{array.shape}")
    return tuple((float(x), float(y)) for x, y in array)


@dataclass(frozen=True)
class RidgePattern:
    """Singular points of a fingerprint class and the zero-pole orientation field they define.

    ``cores`` and ``deltas`` are ``(x, y)`` positions [m] in the window's coordinates (pixel ``(0, 0)`` at the
    origin; y points towards the finger tip); ``rotation`` is θ∞ [rad]. Orientation θ is the ridge direction
    measured from the x axis, in ``[0, π)``.
    """

    pattern: str
    cores: tuple
    deltas: tuple
    rotation: float = 0.0

    def doubled_angle(self, x, y) -> np.ndarray:
        """``exp(2iθ)`` of the zero-pole model (Sherlock & Monro 1993) at broadcastable ``x``, ``y`` [m]."""
        z = np.asarray(x) + 1j * np.asarray(y)
        u = np.full(np.broadcast(z).shape, np.exp(2j * self.rotation), dtype=complex)
        for core in self.cores:                       # exp(i arg w) = w/|w|
            w = z - complex(*core)
            u *= w / np.maximum(np.abs(w), 1e-300)
        for delta in self.deltas:
            w = z - complex(*delta)
            u *= np.conj(w) / np.maximum(np.abs(w), 1e-300)
        return u

    def orientation(self, grid: Grid, seam_width=None) -> np.ndarray:
        """Ridge orientation θ [rad, in [0, π)] on ``grid``, exactly as :func:`fingerprint` uses it.

        On a periodic axis the model is blended with its periodic image over a band of ``seam_width`` [m]
        (default three ridge periods of 0.45 mm) at each end, so the field is periodic; elsewhere, and on
        non-periodic axes, it is the zero-pole field itself.
        """
        seam = _SEAM_PERIODS * RIDGE_PERIOD if seam_width is None else check_positive("seam_width", seam_width)
        return _periodised_orientation(self, grid, seam).astype(float)

    def distance_to_singular_points(self, grid: Grid) -> np.ndarray:
        """Distance [m] of every pixel to the nearest core or delta (minimum image on periodic axes)."""
        x, y = grid.meshgrid()
        distance = np.full(grid.shape, np.inf)
        for px, py in self.cores + self.deltas:
            dx, dy = x - px, y - py
            if grid.periodic[0]:
                dx -= grid.lengths[0] * np.round(dx / grid.lengths[0])
            if grid.periodic[1]:
                dy -= grid.lengths[1] * np.round(dy / grid.lengths[1])
            distance = np.minimum(distance, np.hypot(dx, dy))
        return distance


def ridge_pattern(grid: Grid, pattern: str = "left_loop", cores=None, deltas=None,
                  rotation: float = 0.0) -> RidgePattern:
    """Singular points of ``pattern`` at default positions relative to the window (or the given ones).

    Defaults are physical offsets from the window centre ``c`` (y towards the finger tip), sized for a
    finger pad (core-delta distances of 10–15 ridge periods, as in typical loops), so a small window sees only
    part of the pattern: ``arch`` — a core 14 mm below ``c`` with its delta 40 mm below, so the window sees the
    gently arched ridges above a core; ``tented_arch`` — core at ``c + (0, 1 mm)``, delta straight below at
    ``c − (0, 2 mm)``; ``left_loop`` — core at ``c + (0, 1.5 mm)``, delta at ``c + (5, −3) mm`` (ridges enter
    and leave on the left); ``right_loop`` — its mirror image; ``whorl`` — cores at ``c ± (0, 0.8 mm)``,
    deltas at ``c + (±6, −3.5) mm``. ``cores``/``deltas`` override
    them ((x, y) pairs [m]); ``rotation`` θ∞ [rad] rotates the far field.
    """
    if not isinstance(grid, Grid):
        raise TypeError(f"grid must be a surfaces.Grid, got {type(grid).__name__}")
    pattern = check_choice("pattern", _ALIASES.get(pattern, pattern), set(PATTERNS) | set(_ALIASES))
    rotation = check_real("rotation", rotation)
    cx, cy = 0.5 * grid.lengths[0], 0.5 * grid.lengths[1]
    mm = 1e-3
    defaults = {
        "arch": ([(cx, cy - 14 * mm)], [(cx, cy - 40 * mm)]),
        "tented_arch": ([(cx, cy + 1 * mm)], [(cx, cy - 2 * mm)]),
        "left_loop": ([(cx, cy + 1.5 * mm)], [(cx + 5 * mm, cy - 3 * mm)]),
        "right_loop": ([(cx, cy + 1.5 * mm)], [(cx - 5 * mm, cy - 3 * mm)]),
        "whorl": ([(cx, cy + 0.8 * mm), (cx, cy - 0.8 * mm)],
                  [(cx - 6 * mm, cy - 3.5 * mm), (cx + 6 * mm, cy - 3.5 * mm)]),
    }[pattern]
    cores = _points("cores", defaults[0] if cores is None else cores)
    deltas = _points("deltas", defaults[1] if deltas is None else deltas)
    return RidgePattern(pattern, cores, deltas, rotation)


def _seam_weights(n: int, spacing: float, length: float, seam: float, periodic: bool) -> dict:
    """Per-axis weights ``{image shift: weight(x)}`` of a periodic partition of unity (C¹, sin² ramps)."""
    if not periodic or n == 1:
        return {0: np.ones(n)}
    x = np.arange(n) * spacing
    seam = min(seam, 0.5 * length)
    # weight of the image on the other side: ½ at the seam (x = 0 ≡ L), 0 beyond `seam` from it
    near_end = 0.5 * np.sin(0.5 * np.pi * np.clip((x - (length - seam)) / seam, 0.0, 1.0)) ** 2
    near_start = 0.5 * np.sin(0.5 * np.pi * np.clip((seam - x) / seam, 0.0, 1.0)) ** 2
    return {0: 1.0 - near_end - near_start, -1: near_end, 1: near_start}


def _periodised_orientation(model: RidgePattern, grid: Grid, seam: float, origin=(0.0, 0.0),
                            rows_per_block: int = 128) -> np.ndarray:
    """θ [rad, float32] of ``exp(2iθ)`` blended with its periodic images so that it is periodic on ``grid``.

    ``origin`` [m] is the position of the window's origin in the grid's coordinates. Evaluated in blocks of
    rows so the temporaries stay small.
    """
    x, y = grid.coordinates()
    x, y = x - origin[0], y - origin[1]
    weights_x = _seam_weights(grid.shape[0], grid.spacing[0], grid.lengths[0], seam, grid.periodic[0])
    weights_y = _seam_weights(grid.shape[1], grid.spacing[1], grid.lengths[1], seam, grid.periodic[1])
    theta = np.empty(grid.shape, dtype=np.float32)
    for start in range(0, grid.shape[0], rows_per_block):
        block = slice(start, min(start + rows_per_block, grid.shape[0]))
        u = np.zeros((block.stop - block.start, grid.shape[1]), dtype=complex)
        for shift_x, wx in weights_x.items():
            rows = np.flatnonzero(wx[block])
            for shift_y, wy in weights_y.items():
                cols = np.flatnonzero(wy)
                if rows.size == 0 or cols.size == 0:
                    continue
                image = model.doubled_angle(x[block][rows, None] + shift_x * grid.lengths[0],
                                            y[None, cols] + shift_y * grid.lengths[1])
                u[np.ix_(rows, cols)] += wx[block][rows, None] * wy[None, cols] * image
        theta[block] = np.mod(0.5 * np.angle(u), np.pi)
    return theta


# ---------------------------------------------------------------------------------------------------------
# Ridge cross-section
# ---------------------------------------------------------------------------------------------------------
def ridge_fraction(ridge_width_ratio: float) -> float:
    """Fraction of the period occupied by the ridge (at mid-height), ``r = ρ/(1 + ρ)`` for ratio ρ."""
    return ridge_width_ratio / (1.0 + ridge_width_ratio)


_RATIO_RANGE = (0.43, 2.33)     # warp |a| < 1 (monotone, smooth profile) needs 0.3 ≤ r ≤ 0.7


def _check_ratio(ridge_width_ratio):
    return check_real("ridge_width_ratio", ridge_width_ratio, low=_RATIO_RANGE[0], high=_RATIO_RANGE[1])


def ridge_profile(cos_phase: np.ndarray, height: float, ridge_width_ratio: float) -> np.ndarray:
    """Cross-section ``h = H/2 (1 + cos(ψ + a sin ψ))`` [m] from ``cos ψ`` (ψ = 0 crest, π furrow centre).

    The warp ``a = (π/2 − π r)/sin(π r)`` puts mid-height at ``ψ = ±π r`` so the ridge (above mid-height)
    covers the fraction ``r = ρ/(1+ρ)`` of the period, ρ = ridge/furrow width ratio; ``|a| < 1`` keeps the
    profile monotone between crest and furrow and infinitely smooth, with rounded crests (flatter for wider
    ridges). Crest at ``H``, furrow bottom at 0.
    """
    r = ridge_fraction(ridge_width_ratio)
    warp = (0.5 * np.pi - np.pi * r) / np.sin(np.pi * r)
    phase = np.arccos(np.clip(cos_phase, -1.0, 1.0))
    return 0.5 * height * (1.0 + np.cos(phase + warp * np.sin(phase)))


def _check_period(name, period, grid):
    period = check_positive(name, period)
    minimum = _MIN_PIXELS_PER_PERIOD * max(grid.spacing[0], grid.spacing[1] if not grid.is_profile else 0.0)
    if period < minimum:
        raise ValueError(f"{name} = {period!r} m is below {_MIN_PIXELS_PER_PERIOD:g} pixels; valid range "
                         f"[{minimum:g}, inf) m on this grid (spacing {grid.spacing} m)")
    return period


def parallel_ridges(grid: Grid, period: float = RIDGE_PERIOD, height: float = RIDGE_HEIGHT,
                    ridge_width_ratio: float = RIDGE_WIDTH_RATIO, orientation: float = 0.0,
                    offset: float = 0.0, pore_density: float = 0.0, pore_diameter: float = PORE_DIAMETER,
                    pore_depth: float = PORE_DEPTH, rng=None) -> HeightField:
    """Straight ridges with the fingerprint cross-section (:func:`ridge_profile`), zero mean [m].

    ``period`` [m], crest-to-furrow ``height`` [m], ``orientation`` [rad] = ridge direction from the x axis,
    ``offset`` [m] = position of a crest along the ridge normal from the origin. On a periodic axis the ridge
    wavevector ``2π/period (−sin θ, cos θ)`` must be a grid mode (else ``ValueError`` with the nearest period).
    ``pore_density`` [1/m²] sweat pores (default none) of ``pore_diameter`` and ``pore_depth`` [m] are carved on
    the crests as in :func:`fingerprint` (crest pixels drawn with ``rng``; their centres in the metadata).
    """
    if not isinstance(grid, Grid):
        raise TypeError(f"grid must be a surfaces.Grid, got {type(grid).__name__}")
    period = _check_period("period", period, grid)
    height = check_real("height", height, low=0.0)
    ratio = _check_ratio(ridge_width_ratio)
    orientation = check_real("orientation", orientation)
    offset = check_real("offset", offset)
    normal = np.array([-np.sin(orientation), np.cos(orientation)])
    q = 2 * np.pi / period * normal
    for axis in range(2):
        if grid.periodic[axis] and grid.shape[axis] > 1:
            modes = q[axis] * grid.lengths[axis] / (2 * np.pi)
            if abs(modes - np.round(modes)) > 1e-9 * max(1.0, abs(modes)):
                nearest = abs(normal[axis]) * grid.lengths[axis] / max(1, round(abs(modes)))
                raise ValueError(
                    f"period = {period!r} m with orientation = {orientation!r} rad is not periodic on axis {axis} "
                    f"(length {grid.lengths[axis]!r} m holds {modes:.6g} periods); valid: an integer number of "
                    f"periods, e.g. period = {nearest:.9g} m")
    pore_density, pore_diameter, pore_depth = _check_pores(pore_density, pore_diameter, pore_depth, ratio, period)
    rng, seed = check_rng(rng)
    x, y = grid.meshgrid()
    cos_phase = np.cos(q[0] * x + q[1] * y - 2 * np.pi * offset / period)
    h, pores = _carve_pores(ridge_profile(cos_phase, height, ratio), grid, _crest(cos_phase, ratio), pore_density,
                            pore_diameter, pore_depth, rng)
    return HeightField(grid, h - h.mean(), {
        "generator": "surfaces.parallel_ridges", "period": period, "height": height,
        "ridge_width_ratio": ratio, "orientation": orientation, "offset": offset, "pore_density": pore_density,
        "pore_diameter": pore_diameter, "pore_depth": pore_depth, "seed": seed if pores.size else None,
        "pore_centres": pores.tolist()})


# ---------------------------------------------------------------------------------------------------------
# Gabor filter bank
# ---------------------------------------------------------------------------------------------------------
def _bins(values, low, high, spacing, periodic_bins=None):
    """Lower bin index and linear weight of the upper bin for values on a regular bin axis."""
    t = (values - low) / spacing
    if periodic_bins is not None:
        t = np.mod(t, periodic_bins)
        lower = np.floor(t).astype(np.int32)
        return lower, (t - lower).astype(np.float32)
    t = np.clip(t, 0.0, high)
    lower = np.minimum(np.floor(t).astype(np.int32), max(int(high) - 1, 0))
    return lower, (t - lower).astype(np.float32)


def _gabor_lobe(qx, qy, angle, wavenumber, radial, angular):
    """One lobe of the Gabor transfer function centred at ``wavenumber·n(angle)`` (peak 1), polar separable.

    Gaussian in ``|q| − |wavenumber|`` (std ``radial·|wavenumber|``) and in the angle between ``q`` and
    ``sign(wavenumber)·n`` (std ``angular`` [rad]), so that the radial peak sits at ``|wavenumber|`` in every
    direction (no frequency bias when bins are interpolated).
    """
    q = np.hypot(qx, qy)
    normal = angle + 0.5 * np.pi + (np.pi if wavenumber < 0 else 0.0)   # ridge normal for ridge direction
    off_axis = np.angle(np.exp(1j * (np.arctan2(qy, qx) - normal)))
    return np.exp(-0.5 * (((q - abs(wavenumber)) / (radial * abs(wavenumber))) ** 2 + (off_axis / angular) ** 2))


class _Steering:
    """Per-pixel bilinear weights over (orientation, frequency) bins; orientation bins wrap around π."""

    def __init__(self, theta, wavenumber, wavenumbers):
        self.n_theta = _N_ORIENTATIONS
        self.angles = np.arange(self.n_theta) * np.pi / self.n_theta
        self.wavenumbers = wavenumbers
        self.theta_lower, self.theta_weight = _bins(theta, 0.0, None, np.pi / self.n_theta, self.n_theta)
        if len(wavenumbers) > 1:
            step = np.log(wavenumbers[1] / wavenumbers[0])
            self.q_lower, self.q_weight = _bins(np.log(wavenumber), np.log(wavenumbers[0]),
                                                len(wavenumbers) - 1, step)
        else:
            self.q_lower = self.q_weight = None

    def weight(self, k, j):
        """Weights of bin (orientation k, frequency j) and whether the upper orientation neighbour wraps."""
        w = np.zeros(self.theta_lower.shape, dtype=np.float32)
        lower = self.theta_lower == k
        w[lower] = 1.0 - self.theta_weight[lower]
        from_below = self.theta_lower == (k - 1) % self.n_theta
        w[from_below] = self.theta_weight[from_below]
        if self.q_lower is not None:
            wq = np.zeros_like(w)
            lower, upper = self.q_lower == j, self.q_lower == j - 1
            wq[lower] = 1.0 - self.q_weight[lower]
            wq[upper] = self.q_weight[upper]
            w *= wq
        # pixels near θ = π take bin 0 as their upper neighbour with the normal reversed
        wrapped = from_below & (k == 0)
        return w, wrapped


def _grow(steering, qx, qy, shape, rng):
    """Iterated steered Gabor filtering and clipping of white noise, in ``_GROWTH_STAGES`` (field in [−1, 1])."""
    field = rng.standard_normal(shape)
    weights = [[steering.weight(k, j)[0] for j in range(len(steering.wavenumbers))]
               for k in range(steering.n_theta)]
    for radial, angular, iterations in _GROWTH_STAGES:
        transfer = [[_gabor_lobe(qx, qy, a, q, radial, angular) + _gabor_lobe(qx, qy, a, -q, radial, angular)
                     for q in steering.wavenumbers] for a in steering.angles]
        for _ in range(iterations):
            spectrum = scipy.fft.rfft2(field)
            filtered = np.zeros(shape)
            for k in range(steering.n_theta):
                for j in range(len(steering.wavenumbers)):
                    filtered += weights[k][j] * scipy.fft.irfft2(transfer[k][j] * spectrum, s=shape)
            field = np.clip(_GROWTH_GAIN * filtered / np.abs(filtered).max(), -1.0, 1.0)
    return field


def _embed(coarse_spectrum, full_shape):
    """Slices mapping the coarse FFT modes into the full FFT array (same physical size)."""
    slices = []
    for n_c, n_f in zip(coarse_spectrum.shape, full_shape):
        half = (n_c + 1) // 2
        slices.append(((slice(0, half), slice(0, half)), (slice(half, n_c), slice(n_f - (n_c - half), n_f))))
    return slices


def _analytic_ridges(grown, coarse_grid, steering, full_grid, workers):
    """Steered analytic response ``z = c + i s`` of ``grown`` (last-stage filters), interpolated to ``full_grid``."""
    spectrum = scipy.fft.fft2(grown)
    qx, qy = coarse_grid.wavevectors()
    slices = _embed(spectrum, full_grid.shape)
    buffer = np.zeros(full_grid.shape, dtype=np.complex64)
    response = np.zeros(full_grid.shape, dtype=np.complex64)
    for k, angle in enumerate(steering.angles):
        for j, q in enumerate(steering.wavenumbers):
            weight, wrapped = steering.weight(k, j)
            selected = weight > 0
            if not selected.any():
                continue
            lobe = 2.0 * _gabor_lobe(qx, qy, angle, q, *_GROWTH_STAGES[-1][:2]) * spectrum
            buffer[...] = 0
            for (src_x, dst_x) in slices[0]:
                for (src_y, dst_y) in slices[1]:
                    buffer[dst_x, dst_y] = lobe[src_x, src_y]
            z = scipy.fft.ifft2(buffer, workers=workers, overwrite_x=True)
            z[wrapped] = np.conj(z[wrapped])          # normal reversed: odd part changes sign
            response[selected] += weight[selected] * z[selected]
    return response


# ---------------------------------------------------------------------------------------------------------
# Pores
# ---------------------------------------------------------------------------------------------------------
def _check_pores(density, diameter, depth, ratio, period):
    """Checked pore density [1/m²], diameter (at most the ridge width at ``period``) and depth [m]."""
    return (check_real("pore_density", density, low=0.0),
            check_real("pore_diameter", diameter, low=0.0, low_open=True, high=ridge_fraction(ratio) * period),
            check_real("pore_depth", depth, low=0.0))


def _crest(cos_phase, ratio) -> np.ndarray:
    """The crest band where pores sit: the middle half of each ridge's width."""
    return cos_phase > np.cos(0.25 * np.pi * ridge_fraction(ratio))


def _distance2(dx, dy, grid):
    """Squared distance of a separation (dx, dy) [m], minimum image on periodic axes."""
    if grid.periodic[0]:
        dx -= grid.lengths[0] * round(dx / grid.lengths[0])
    if grid.periodic[1]:
        dy -= grid.lengths[1] * round(dy / grid.lengths[1])
    return dx * dx + dy * dy


def _carve_pores(h, grid, crest, density, diameter, depth, rng):
    """Subtract (in place) ``round(density·area)`` quartic dimples ``D (1 − (2r/d)²)²`` of opening diameter
    ``d`` centred on random ``crest`` pixels at least ``1.25 d`` apart; return ``h`` and the centres [m]."""
    n_pores = int(round(density * grid.area))
    candidates = np.flatnonzero(crest)
    if n_pores == 0:
        return h, np.zeros((0, 2))
    if candidates.size == 0:
        raise ValueError("no ridge-crest pixels to place pores on; increase the resolution or set pore_density=0")
    dx, dy = grid.spacing
    min_distance = 1.25 * diameter     # separate rims; 1000 cm⁻² needs ~0.2 mm spacing along 0.45 mm-period ridges
    cells = [max(1, int(length // min_distance)) for length in grid.lengths]
    occupied = {}                                       # hash of placed centres by cell (side >= min_distance)
    centres = []
    for index in rng.permutation(candidates):
        i, j = np.unravel_index(index, grid.shape)
        x, y = i * dx, j * dy
        cell = (int(x / grid.lengths[0] * cells[0]), int(y / grid.lengths[1] * cells[1]))
        neighbours = {((cell[0] + ox) % cells[0] if grid.periodic[0] else cell[0] + ox,
                       (cell[1] + oy) % cells[1] if grid.periodic[1] else cell[1] + oy)
                      for ox in (-1, 0, 1) for oy in (-1, 0, 1)}
        if any(_distance2(x - px, y - py, grid) < min_distance ** 2
               for key in neighbours for px, py in occupied.get(key, ())):
            continue
        centres.append((x, y))
        occupied.setdefault(cell, []).append((x, y))
        if len(centres) == n_pores:
            break
    if len(centres) < n_pores:
        raise ValueError(f"pore_density = {density!r} 1/m² does not fit on the ridge crests of this window "
                         f"with pore_diameter = {diameter!r} m (placed {len(centres)} of {n_pores})")
    radius = 0.5 * diameter
    ri, rj = int(np.ceil(radius / dx)), int(np.ceil(radius / dy))
    oi, oj = np.meshgrid(np.arange(-ri, ri + 1), np.arange(-rj, rj + 1), indexing="ij")
    rho2 = ((oi * dx) ** 2 + (oj * dy) ** 2) / radius ** 2
    dimple = np.where(rho2 < 1.0, depth * (1.0 - rho2) ** 2, 0.0)
    for x, y in centres:
        ii, jj = int(round(x / dx)) + oi, int(round(y / dy)) + oj
        if grid.periodic[0]:
            ii %= grid.shape[0]
        if grid.periodic[1]:
            jj %= grid.shape[1]
        inside = (ii >= 0) & (ii < grid.shape[0]) & (jj >= 0) & (jj < grid.shape[1])
        h[ii[inside], jj[inside]] -= dimple[inside]
    return h, np.array(centres)


# ---------------------------------------------------------------------------------------------------------
# The generator
# ---------------------------------------------------------------------------------------------------------
def _generation_grid(grid: Grid, seam: float):
    """Periodic domain the ridges are grown on: the grid itself, or the window padded by ``seam`` [m] on each
    side of a non-periodic axis (so the orientation seam lies outside the window)."""
    shape, lengths, offsets = [], [], []
    for n, length, d, periodic in zip(grid.shape, grid.lengths, grid.spacing, grid.periodic):
        if periodic:
            shape.append(n)
            lengths.append(length)
            offsets.append(0)
            continue
        n_ext = scipy.fft.next_fast_len(n + 2 * int(np.ceil(seam / d)), real=False)
        shape.append(n_ext)
        lengths.append(n_ext * d)
        offsets.append((n_ext - n) // 2)
    return Grid(tuple(shape), tuple(lengths), True), tuple(offsets)


def _coarse_grid(grid: Grid, period: float) -> Grid:
    """Same periodic domain with about ``_PIXELS_PER_PERIOD`` pixels per ridge period (never finer)."""
    shape = tuple(min(n, scipy.fft.next_fast_len(int(np.ceil(length / period * _PIXELS_PER_PERIOD)), real=True))
                  for n, length in zip(grid.shape, grid.lengths))
    return Grid(shape, grid.lengths, True)


def _period_map(ridge_period, grid):
    """Ridge period [m]: a scalar, or an array of ``grid.shape`` (smooth variation), checked."""
    if np.ndim(ridge_period) == 0:
        return _check_period("ridge_period", ridge_period, grid)
    period = check_finite_array("ridge_period", ridge_period)
    if period.shape != grid.shape:
        raise ValueError(f"ridge_period map has shape {period.shape}, but grid.shape is {grid.shape}")
    _check_period("ridge_period (minimum of the map)", period.min(), grid)
    return period


def _pad_to_domain(values, domain_shape, offsets):
    """Place a window-sized map into the generation domain, extending it by its edge values."""
    return np.pad(values, [(o, n - w - o) for o, n, w in zip(offsets, domain_shape, values.shape)], mode="edge")


def _steering(model, target: Grid, seam, origin, period, period_map) -> _Steering:
    """Orientation and ridge-wavenumber (2π/period) bins on ``target`` (the coarse or full generation grid).

    ``period_map`` is the period map on the full generation domain (None for a constant ``period``); it is
    sampled at the nearest full-domain pixel of each ``target`` pixel.
    """
    theta = _periodised_orientation(model, target, seam, origin)
    if period_map is None:
        return _Steering(theta, None, [2 * np.pi / period])
    sample = tuple(np.round(np.arange(m) * (n / m)).astype(int) for m, n in zip(target.shape, period_map.shape))
    local = period_map[np.ix_(*sample)]
    q_min, q_max = 2 * np.pi / local.max(), 2 * np.pi / local.min()
    n_q = 1 + int(np.ceil(np.log(q_max / q_min) / np.log(_FREQUENCY_STEP)))
    wavenumbers = q_min * (q_max / q_min) ** (np.arange(n_q) / max(n_q - 1, 1))
    return _Steering(theta, 2 * np.pi / local, list(wavenumbers))


def fingerprint(grid: Grid, pattern: str = "left_loop", ridge_period=RIDGE_PERIOD,
                ridge_height: float = RIDGE_HEIGHT, ridge_width_ratio: float = RIDGE_WIDTH_RATIO,
                pore_density: float = PORE_DENSITY, pore_diameter: float = PORE_DIAMETER,
                pore_depth: float = PORE_DEPTH, cores=None, deltas=None, rotation: float = 0.0, rng=None,
                threads=None) -> HeightField:
    """Synthetic fingerprint height field [m], zero mean, crests towards the counter-face (SI units; defaults
    and sources in ``docs/guide/fingerprint.md``).

    Parameters
    ----------
    pattern : ``"arch"``, ``"tented_arch"``, ``"left_loop"`` (alias ``"loop"``), ``"right_loop"``, ``"whorl"``.
    ridge_period : ridge-to-ridge distance [m] (default 0.45 mm), scalar or map of ``grid.shape`` (smooth).
    ridge_height : crest-to-furrow height H [m] (default 50 µm).
    ridge_width_ratio : ridge width / furrow width at mid-height, in [0.43, 2.33] (default 1.5).
    pore_density : sweat pores per area [1/m²] on ridge crests (default 5e6 = 500 cm⁻²); 0 for none.
    pore_diameter, pore_depth : opening diameter (default 120 µm) and depth (default 20 µm) of the dimples [m].
    cores, deltas, rotation : singular points (x, y) [m] and θ∞ [rad]; see :func:`ridge_pattern`.
    rng : None, int seed or ``numpy.random.Generator`` (an int seed, or the fresh one drawn for None, is
        stored in the metadata).
    threads : FFT threads for ``scipy.fft`` (None: all cores), as ``threads`` in ``roughcontact``.

    Notes
    -----
    The metadata records all parameters, the singular points and the pore centres [m]. On a periodic grid
    the ridges are continuous across the boundary and the orientation field is blended with its periodic
    image over a band of three ridge periods at each edge (see :meth:`RidgePattern.orientation`).
    """
    model = ridge_pattern(grid, pattern, cores, deltas, rotation)
    if grid.is_profile:
        raise ValueError(f"grid must be two-dimensional for a fingerprint; got shape {grid.shape}")
    period = _period_map(ridge_period, grid)
    ridge_height = check_real("ridge_height", ridge_height, low=0.0)
    ratio = _check_ratio(ridge_width_ratio)
    pore_density, pore_diameter, pore_depth = _check_pores(pore_density, pore_diameter, pore_depth, ratio,
                                                           float(np.min(period)))
    rng, seed = check_rng(rng)
    threads = -1 if threads is None else check_integer("threads", threads, low=1)   # scipy.fft's workers

    seam = _SEAM_PERIODS * float(np.max(period))
    domain, offsets = _generation_grid(grid, seam)
    coarse = _coarse_grid(domain, float(np.min(period)))
    window = tuple(slice(o, o + n) for o, n in zip(offsets, grid.shape))

    origin = tuple(o * d for o, d in zip(offsets, grid.spacing))
    period_map = None if np.ndim(period) == 0 else _pad_to_domain(period, domain.shape, offsets)
    qx, qy = coarse.wavevectors(real=True)
    grown = _grow(_steering(model, coarse, seam, origin, period, period_map), qx, qy, coarse.shape, rng)
    z = _analytic_ridges(grown, coarse, _steering(model, domain, seam, origin, period, period_map), domain,
                         threads)[window]
    amplitude = np.abs(z)
    cos_phase = z.real / np.maximum(amplitude, 1e-30)
    taper = np.clip(amplitude / (_TAPER * np.median(amplitude)), 0.0, 1.0)
    h = ridge_profile(cos_phase, ridge_height, ratio)
    h = 0.5 * ridge_height + taper * (h - 0.5 * ridge_height)

    crest = _crest(cos_phase, ratio) & (taper >= 1.0)
    h, pores = _carve_pores(h, grid, crest, pore_density, pore_diameter, pore_depth, rng)
    return HeightField(grid, h - h.mean(), {
        "generator": "surfaces.fingerprint", "pattern": model.pattern,
        "ridge_period": period if np.ndim(period) == 0 else "map", "ridge_height": ridge_height,
        "ridge_width_ratio": ratio, "pore_density": pore_density, "pore_diameter": pore_diameter,
        "pore_depth": pore_depth, "cores": model.cores, "deltas": model.deltas,
        "rotation": model.rotation, "seam_width": seam, "seed": seed,
        "pore_centres": pores.tolist()})
