"""Self-affine Gaussian roughness by Fourier synthesis of an isotropic PSD.

Spectrum (docs/references.md §3.1, convention of ``docs/reference/conventions.md``), with ``q = 2π/λ``:

    C(q) = 0                               q < q_L  (long-wavelength cutoff λ_L)
    C(q) = C0                              q_L <= q < q_r  (roll-off λ_r: flat plateau)
    C(q) = C0 (q/q_r)^(-2(1+H))            q_r <= q < q_s  (short-wavelength cutoff λ_s)
    C(q) = 0                               q >= q_s  (no short cutoff: the grid's Nyquist wavevector ends it)

in [m^4] for a surface; a profile (grid ``(n, 1)``) uses the 1-D PSD ``C₁ = C0 (q/q_r)^(-(1+2H))`` [m^3].
Moments: surface ``m_k = 2π ∫ q^(2k+1) C dq``, profile ``m_k = 2 ∫ q^(2k) C₁ dq``; ``h_rms² = m_0``,
``h'_rms² = m_1`` (rms gradient), ``h''_rms² = m_2`` (rms Laplacian).

Synthesis on a periodic Lx×Ly grid: ``h(x) = Σ_q ĥ_q e^{iq·x}`` with ``ĥ_q = sqrt(C(q) (2π)²/(Lx Ly)) ξ_q``
(profile: ``sqrt(C₁(q) 2π/L) ξ_q``), ξ_q standard complex Gaussian (``<|ξ|²> = 1``), ``ĥ_{-q} = conj(ĥ_q)``.
Random numbers belong to integer wavevectors, not to array positions: canonical modes (``ky > 0``, or
``ky = 0, kx > 0``) are drawn shell by shell in ``s = max(|kx|, |ky|)`` from one Generator, so a finer grid of
the same physical size reproduces every Fourier mode of a coarser one exactly. Nyquist modes carry no power.
Non-periodic axes: the field is synthesised on a periodic grid twice as long on those axes and cropped.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace

import numpy as np
import scipy.fft

from .validation import check_bool, check_positive, check_real, check_rng
from .grid import MAX_LENGTH, MIN_LENGTH, Grid
from .heightfield import HeightField

# A mode within this relative distance of a cutoff counts as on the cutoff (inside at λ_L, outside at λ_s),
# so that a cutoff placed exactly on a grid wavenumber does not depend on floating-point rounding.
_EDGE = 1e-9


def _power_integral(exponent: float, low: float, high: float) -> float:
    """``∫_low^high q^exponent dq`` (``high`` may be infinite when the integral converges)."""
    if math.isinf(high):
        if exponent >= -1:
            raise ValueError(f"the spectral moment diverges without a short cutoff (∫^∞ q^{exponent:g} dq); "
                             "give short_cutoff")
        return -low ** (exponent + 1) / (exponent + 1)
    if abs(exponent + 1) < 1e-12:
        return math.log(high / low)
    return (high ** (exponent + 1) - low ** (exponent + 1)) / (exponent + 1)


@dataclass(frozen=True)
class SelfAffinePSD:
    """Isotropic self-affine PSD with plateau and cutoffs; callable as ``C(q)`` [m^4] (profile: [m^3]).

    Parameters
    ----------
    hurst : float
        Hurst exponent H in (0, 1].
    prefactor : float
        Plateau value C0 = C(q) for λ_r <= 2π/q <= λ_L [m^4] (profile: [m^3]).
    long_cutoff, rolloff, short_cutoff : float
        Wavelengths λ_L >= λ_r > λ_s > 0 [m]; ``rolloff == long_cutoff`` means no plateau;
        ``short_cutoff=None`` means none (moments that then diverge raise ``ValueError``).
    profile : bool
        True for the 1-D PSD of a profile, ``C₁ ∝ q^-(1+2H)``.
    """

    hurst: float
    prefactor: float
    long_cutoff: float
    rolloff: float
    short_cutoff: float
    profile: bool = False

    def __post_init__(self):
        object.__setattr__(self, "hurst", check_real("hurst", self.hurst, low=0.0, high=1.0, low_open=True))
        object.__setattr__(self, "prefactor", check_real("prefactor", self.prefactor, low=0.0))
        short = check_positive("short_cutoff", self.short_cutoff, allow_none=True)
        rolloff = _check_wavelength("rolloff", self.rolloff, short or 0.0, None,
                                    "rolloff must exceed short_cutoff", low_open=True)
        long = _check_wavelength("long_cutoff", self.long_cutoff, rolloff, None,
                                 "long_cutoff must be >= rolloff")
        object.__setattr__(self, "short_cutoff", short)
        object.__setattr__(self, "rolloff", rolloff)
        object.__setattr__(self, "long_cutoff", long)
        object.__setattr__(self, "profile", check_bool("profile", self.profile))

    @property
    def exponent(self) -> float:
        """Power-law exponent of C above the roll-off: ``-2(1+H)`` (surface) or ``-(1+2H)`` (profile)."""
        return -(1 + 2 * self.hurst) if self.profile else -2 * (1 + self.hurst)

    @property
    def cutoff_wavevectors(self) -> tuple:
        """``(q_L, q_r, q_s) = 2π/(λ_L, λ_r, λ_s)`` [rad/m]; ``q_s = inf`` without a short cutoff."""
        q_short = math.inf if self.short_cutoff is None else 2 * np.pi / self.short_cutoff
        return 2 * np.pi / self.long_cutoff, 2 * np.pi / self.rolloff, q_short

    def __call__(self, q):
        """``C(q)`` [m^4] (profile ``C₁(q)`` [m^3]) at angular wavevector magnitude ``q`` [rad/m]."""
        q = np.asarray(q, dtype=float)
        q_long, q_rolloff, q_short = self.cutoff_wavevectors
        inside = (q >= q_long * (1 - _EDGE)) & (q < q_short * (1 - _EDGE))
        with np.errstate(divide="ignore"):
            tail = self.prefactor * (np.maximum(q, q_rolloff) / q_rolloff) ** self.exponent
        return np.where(inside, tail, 0.0)

    def moment(self, order: int) -> float:
        """Analytic spectral moment: surface ``2π ∫ q^(2k+1) C dq``, profile ``2 ∫ q^(2k) C₁ dq``."""
        q_long, q_rolloff, q_short = self.cutoff_wavevectors
        weight_power = 2 * order if self.profile else 2 * order + 1
        prefactor = 2.0 if self.profile else 2 * np.pi
        plateau = _power_integral(weight_power, q_long, q_rolloff)
        tail = q_rolloff ** -self.exponent * _power_integral(weight_power + self.exponent, q_rolloff, q_short)
        return float(prefactor * self.prefactor * (plateau + tail))

    @property
    def rms_height(self) -> float:
        """``sqrt(m_0)`` [m]."""
        return math.sqrt(self.moment(0))

    @property
    def rms_slope(self) -> float:
        """rms gradient ``sqrt(m_1)`` [-]."""
        return math.sqrt(self.moment(1))

    @property
    def rms_curvature(self) -> float:
        """rms Laplacian ``sqrt(m_2)`` [1/m]."""
        return math.sqrt(self.moment(2))

    def scaled(self, *, rms_height=None, rms_slope=None) -> "SelfAffinePSD":
        """Copy whose prefactor gives the analytic rms height [m] or rms slope [-] (exactly one)."""
        order, target = _amplitude_target(rms_height, rms_slope)
        unit = SelfAffinePSD(self.hurst, 1.0, self.long_cutoff, self.rolloff, self.short_cutoff, self.profile)
        return SelfAffinePSD(self.hurst, target ** 2 / unit.moment(order), self.long_cutoff, self.rolloff,
                             self.short_cutoff, self.profile)

    def to_dict(self) -> dict:
        return asdict(self)


def _check_wavelength(name, value, low, high, reason, low_open=False):
    """``check_real`` with the physical reason appended to the message."""
    try:
        return check_real(name, value, low=low, high=high, low_open=low_open)
    except ValueError as error:
        raise ValueError(f"{error} ({reason})") from None


def _amplitude_target(rms_height, rms_slope) -> tuple:
    """``(moment order, target)`` from exactly one of ``rms_height`` [m] and ``rms_slope`` [-]."""
    given = {name: value for name, value in (("rms_height", rms_height), ("rms_slope", rms_slope))
             if value is not None}
    if len(given) != 1:
        raise ValueError(f"give exactly one of rms_height, rms_slope; got {sorted(given) or 'none'}")
    (name, value), = given.items()
    if name == "rms_height":                # a length, in the range of the grid's (its square a power in float64)
        return 0, check_real(name, value, low=MIN_LENGTH, high=MAX_LENGTH)
    return 1, check_positive(name, value)


def _check_prefactor_amplitude(spectrum: "SelfAffinePSD") -> None:
    """A ``prefactor`` amplitude whose spectrum's analytic rms height [m] lies outside the lengths a grid may hold
    ([MIN_LENGTH, MAX_LENGTH], as ``rms_height``) is refused before synthesis, naming the prefactor range that fits
    (the rms height goes as its square root; computed from the unit spectrum's, so that nothing overflows)."""
    unit_rms = replace(spectrum, prefactor=1.0).rms_height
    rms = math.sqrt(spectrum.prefactor) * unit_rms
    if not MIN_LENGTH <= rms <= MAX_LENGTH:
        low, high = ((bound / unit_rms) ** 2 for bound in (MIN_LENGTH, MAX_LENGTH))
        raise ValueError(f"prefactor = {spectrum.prefactor!r} m^4 gives heights of rms {rms:.3g} m, outside "
                         f"[{MIN_LENGTH:g}, {MAX_LENGTH:g}] m; valid range here [{low:.3g}, {high:.3g}] m^4")


def _stream_index(kx: np.ndarray, ky: np.ndarray, profile: bool) -> np.ndarray:
    """Position of the canonical mode ``(|kx|, 0)`` or ``(kx, ky > 0)`` in the shell-ordered random stream.

    Surface: shells ``s = max(|kx|, ky)`` hold ``4s`` canonical modes, preceded by ``2s(s-1)`` of the inner
    shells; inside a shell the order runs anticlockwise from ``(s, 0)``: right edge ``(s, 1..s-1)``, top edge
    ``(s..-s, s)``, left edge ``(-s, s-1..1)``. Profile: ``|kx| - 1``. Independent of the grid size.
    """
    kx = np.where(ky == 0, np.abs(kx), kx)
    s = np.maximum(np.abs(kx), ky)
    if profile:
        return s - 1
    rank = np.select([ky == 0, (kx == s) & (ky < s), ky == s],
                     [0, ky, 2 * s - kx], default=4 * s - ky)
    return 2 * s * (s - 1) + rank


def _synthesise_periodic(grid: Grid, spectrum, generator, order, target, block_rows: int = 256) -> tuple:
    """Heights on the periodic ``grid`` and the normalisation factor applied (1 if ``target`` is None).

    Works on the rfft half spectrum in blocks of ``block_rows`` rows, so that apart from the random stream
    and the spectrum itself no full-size temporaries are made.
    """
    profile = grid.is_profile
    nx, ny = grid.shape
    kx, ky = grid.mode_indices(real=True)
    qx, qy = grid.wavevectors(real=True)
    to_modal_power = (2 * np.pi / grid.lengths[0]) if profile else (2 * np.pi) ** 2 / grid.area
    coefficients = np.zeros((nx, ky.size), dtype=complex)
    blocks = [slice(start, min(start + block_rows, nx)) for start in range(0, nx, block_rows)]
    shells = 0
    for rows in blocks:                                   # pass 1: amplitudes sqrt(<|ĥ_q|²>)
        power = np.asarray(spectrum(np.hypot(qx[rows], qy)), dtype=float)
        if power.shape != (rows.stop - rows.start, ky.size) or not np.all(np.isfinite(power)) \
                or (power < 0).any():
            raise ValueError("spectrum(q) must return finite values >= 0 of the same shape as q [m^4] "
                             "(profile: [m^3])")
        if nx % 2 == 0:
            power[kx[rows, 0] == -(nx // 2), :] = 0.0     # Nyquist row
        if ny % 2 == 0:
            power[:, ny // 2] = 0.0                       # Nyquist column
        if rows.start == 0:
            power[0, 0] = 0.0                             # mean height
        live = power > 0
        if live.any():
            shells = max(shells, int(np.max(np.maximum(np.abs(kx[rows]), ky), where=live, initial=0)))
        coefficients.real[rows] = np.sqrt(power * to_modal_power)
    n_draws = shells if profile else 2 * shells * (shells + 1)
    xi = generator.standard_normal((n_draws, 2)).view(complex)[:, 0] / np.sqrt(2)
    moment = 0.0
    weight = np.full(ky.size, 2.0)
    weight[0] = 1.0                                       # the ky = 0 column holds both ±kx explicitly
    for rows in blocks:                                   # pass 2: ĥ_q = amplitude · ξ_q
        block = coefficients[rows]
        index = np.where(block.real > 0, _stream_index(kx[rows], ky, profile), 0)
        values = xi[index] if n_draws else np.zeros(block.shape, dtype=complex)
        conjugate = (ky == 0) & (kx[rows] < 0)
        values[conjugate] = values[conjugate].conj()
        block *= values
        if target is not None:
            modal_power = np.abs(block) ** 2 * weight
            if order == 1:
                modal_power *= qx[rows] ** 2 + qy ** 2
            moment += float(modal_power.sum())
    del xi
    scale = 1.0
    if target is not None:
        if moment == 0:
            raise ValueError("the spectrum has no power on this grid's wavevectors; cannot normalise")
        scale = target / math.sqrt(moment)
    coefficients *= scale * grid.size
    heights = scipy.fft.irfft2(coefficients, s=grid.shape, overwrite_x=True)
    return heights, scale


def _synthesise(grid: Grid, spectrum, rng, rms_height, rms_slope) -> tuple:
    """Heights on ``grid`` (padded and cropped on non-periodic axes) and their metadata record."""
    if not isinstance(grid, Grid):
        raise TypeError(f"grid must be a surfaces.Grid, got {type(grid).__name__}")
    if getattr(spectrum, "profile", grid.is_profile) != grid.is_profile:
        raise ValueError(f"spectrum.profile = {spectrum.profile} does not match the grid (shape {grid.shape}); "
                         "a profile grid (n, 1) needs a 1-D PSD and a surface grid a 2-D PSD")
    order, target = (None, None) if rms_height is None and rms_slope is None else \
        _amplitude_target(rms_height, rms_slope)
    generator, seed = check_rng(rng)
    padding = tuple(1 if (periodic or n == 1) else 2 for n, periodic in zip(grid.shape, grid.periodic))
    parent = Grid(tuple(n * p for n, p in zip(grid.shape, padding)),
                  tuple(length * p for length, p in zip(grid.lengths, padding)), True)
    heights, scale = _synthesise_periodic(parent, spectrum, generator, order, target)
    spectrum_record = spectrum.to_dict() if hasattr(spectrum, "to_dict") else repr(spectrum)
    metadata = {"spectrum": spectrum_record, "normalisation_factor": scale, "padding": list(padding),
                "seed": seed}
    return heights[:grid.shape[0], :grid.shape[1]], metadata


def fourier_synthesis(grid: Grid, spectrum, rng=None, *, rms_height=None, rms_slope=None) -> HeightField:
    """Gaussian random field with isotropic PSD ``spectrum(q)`` [m^4] (profile grid: 1-D PSD [m^3]).

    ``spectrum`` is any callable of the angular wavevector magnitude [rad/m], e.g. :class:`SelfAffinePSD`.
    Giving ``rms_height`` [m] or ``rms_slope`` [-] rescales the realisation so that its discrete spectral
    moment (``Σ_q |ĥ_q|²`` or ``Σ_q q² |ĥ_q|²``) equals the target exactly. Non-periodic axes are
    synthesised on a periodic grid of twice the length (same pixel size) and cropped to the window; the
    normalisation then applies to that parent field.
    """
    if not callable(spectrum):
        raise TypeError(f"spectrum must be a callable C(q), got {type(spectrum).__name__}")
    heights, metadata = _synthesise(grid, spectrum, rng, rms_height, rms_slope)
    return HeightField(grid, heights, {"generator": "fourier_synthesis", "rms_height": rms_height,
                                       "rms_slope": rms_slope, **metadata})


def self_affine(grid: Grid, hurst: float, *, rms_height=None, rms_slope=None, prefactor=None,
                long_cutoff=None, rolloff=None, short_cutoff=None, normalise: bool = True,
                rng=None) -> HeightField:
    """Self-affine Gaussian roughness on ``grid`` [m] (spectrum: module docstring, docs/references.md §3.1).

    Parameters
    ----------
    hurst : float
        Hurst exponent H in (0, 1].
    rms_height, rms_slope, prefactor : float
        Amplitude, exactly one: rms height [m] (in [1e-50, 1e50], the range of a grid's lengths), rms
        gradient [-], or plateau PSD value C0 [m^4] (profile: [m^3]).
    long_cutoff : float, optional
        λ_L [m]; no power at longer wavelengths. Default: the largest window length (the fundamental).
        At most that length.
    rolloff : float, optional
        λ_r [m], ``short_cutoff < rolloff <= long_cutoff``; flat plateau between λ_L and λ_r.
        Default: ``long_cutoff`` (pure power law).
    short_cutoff : float, optional
        λ_s [m], at least two pixels; no power at shorter wavelengths. Default None: no cutoff, every
        non-Nyquist mode of the grid carries power, so a finer grid adds shorter wavelengths while keeping
        the coarse modes (with a ``prefactor`` amplitude).
    normalise : bool
        True (default): the realisation is rescaled so its discrete rms height or rms slope equals the
        target exactly — a Hurst spectrum puts most of the height variance into a handful of long-wavelength
        modes, so an unnormalised sample can miss the requested rms height by several per cent or more.
        False: the prefactor is set from the analytic moment (:class:`SelfAffinePSD`; this needs
        ``short_cutoff``) and the realisation is left alone, so the ensemble is unbiased Gaussian (use this
        for ensemble statistics). A ``prefactor`` amplitude is never rescaled.
        Refinement consistency: a ``prefactor`` amplitude keeps every coarse mode on any finer grid; an rms
        amplitude does so when ``short_cutoff`` is given (then all grids realise the same modes and scale).
    rng : None, int or numpy.random.Generator
        Random source; an int seed (or the fresh seed drawn for None) is stored in the metadata.
    """
    if not isinstance(grid, Grid):
        raise TypeError(f"grid must be a surfaces.Grid, got {type(grid).__name__}")
    axes = [0] if grid.is_profile else [0, 1]
    window = max(grid.lengths[axis] for axis in axes)
    pixel = max(grid.spacing[axis] for axis in axes)
    if window <= 2 * pixel:
        raise ValueError(f"grid shape {grid.shape} (lengths {grid.lengths} m) is too coarse for a self-affine "
                         f"surface: its longest wavelength {window:g} m is not above two pixels "
                         f"({2 * pixel:g} m); valid grids have at least 3 pixels along each axis (a profile along x)")
    if short_cutoff is not None:
        short_cutoff = _check_wavelength("short_cutoff", short_cutoff, 2 * pixel * (1 - _EDGE), window,
                                         f"at least two pixels (2 dx = {2 * pixel:g} m) and at most the window")
    shortest = 2 * pixel * (1 - _EDGE) if short_cutoff is None else short_cutoff
    if long_cutoff is None:
        long_cutoff = window
    long_cutoff = _check_wavelength("long_cutoff", long_cutoff, shortest, window * (1 + _EDGE),
                                    f"above short_cutoff (or two pixels) and at most the window length {window:g} m",
                                    low_open=True)
    if rolloff is None:
        rolloff = long_cutoff
    rolloff = _check_wavelength("rolloff", rolloff, shortest, long_cutoff,
                                "between short_cutoff (or two pixels) and long_cutoff", low_open=True)
    amplitudes = {name: value for name, value in
                  (("rms_height", rms_height), ("rms_slope", rms_slope), ("prefactor", prefactor))
                  if value is not None}
    if len(amplitudes) != 1:
        raise ValueError("give exactly one amplitude of rms_height [m], rms_slope [-], prefactor [m^4]; "
                         f"got {sorted(amplitudes) or 'none'}")
    normalise = check_bool("normalise", normalise)
    spectrum = SelfAffinePSD(hurst, 1.0 if prefactor is None else check_positive("prefactor", prefactor),
                             long_cutoff, rolloff, short_cutoff, grid.is_profile)
    exact = normalise and prefactor is None
    if prefactor is not None:
        _check_prefactor_amplitude(spectrum)
    if prefactor is None and (short_cutoff is not None or not normalise):
        if short_cutoff is None:
            raise ValueError("short_cutoff = None with normalise=False and an rms amplitude: the prefactor comes "
                             "from the analytic moment of a band-limited spectrum; give short_cutoff in the valid "
                             f"range [{2 * pixel:g}, {rolloff:g}) m or use normalise=True")
        spectrum = spectrum.scaled(rms_height=rms_height, rms_slope=rms_slope)
    heights, metadata = _synthesise(grid, spectrum, rng, rms_height if exact else None,
                                    rms_slope if exact else None)
    metadata["spectrum"]["prefactor"] *= metadata["normalisation_factor"] ** 2   # the PSD actually realised
    return HeightField(grid, heights, {"generator": "self_affine", "hurst": spectrum.hurst,
                                       "rms_height": rms_height, "rms_slope": rms_slope,
                                       "normalise": normalise, **metadata})
