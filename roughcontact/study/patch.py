"""The ridge and roughness scales of the study: the periodic patch (grid, ridge and roughness heights, the skin
under it), its 1-D profile across the ridges (:func:`profile_surface`, for resolution studies down to
sub-µm pixels), the default scene's patch as a test case (:func:`default_scene_patch`), and what is measured on
its solved gap — the ridge contact fraction A_R/A0 by morphological closing, the weighted gap slope, the
ridge-area equivalent gap d_eq,R."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.fft

from surfaces import Grid, fourier_synthesis, parallel_ridges, self_affine
from surfaces.selfaffine import SelfAffinePSD
from surfaces.validation import check_positive

from .apparent import apparent_contact
from .fingertip import skin_body
from .scene import Scene, load_scene, measured_topography


def closing_lengths(scene: Scene) -> tuple:
    """The closing diameters ℓ of A_R [m]: the scene's coarse-graining length, then its sensitivity factors on it."""
    length = scene.ridge_area.coarse_graining
    return (length, *(factor * length for factor in scene.ridge_area.sensitivity))


def patch_grid(scene: Scene):
    """The periodic patch grid: ``grid`` × ``grid`` pixels over ``periods`` ridge periods per side; a measured
    topography's own grid (with its boundary) instead."""
    if scene.roughness.topography:
        return measured_topography(scene.roughness).grid
    side = scene.preset.periods * scene.ridges.period
    return Grid((scene.preset.grid,) * 2, (side, side), periodic=True)


def resolved_short_cutoff(scene: Scene, grid=None) -> float:
    """The micro-roughness short cut-off in use [m]: the scene's, raised to ``pixels_per_cutoff`` pixels of
    ``grid`` (default: the patch grid); NaN for a measured topography, which keeps its own pixels."""
    if scene.roughness.topography:
        return float("nan")
    spacing = (patch_grid(scene) if grid is None else grid).spacing[0]
    cutoff = max(scene.roughness.short_cutoff, scene.preset.pixels_per_cutoff * spacing)
    if scene.roughness.enabled and cutoff >= scene.roughness.long_cutoff:
        raise ValueError(f"roughness.long_cutoff = {scene.roughness.long_cutoff!r} m is not above the shortest "
                         f"wavelength the preset resolves, {cutoff:g} m (presets.{scene.study.preset}.grid = "
                         f"{scene.preset.grid} px, pixels_per_cutoff = {scene.preset.pixels_per_cutoff:g}); "
                         "raise the grid or the long cut-off")
    return cutoff


def ridge_heights(scene: Scene, grid=None, realisation: int = 0) -> np.ndarray:
    """Heights [m] of the parallel ridges on ``grid`` (default: the patch grid), with the sweat pores of
    ``realisation`` (rng stream (seed + realisation, 1), apart from the roughness's); zero when disabled."""
    grid = patch_grid(scene) if grid is None else grid
    ridges = scene.ridges
    if not ridges.enabled:
        return np.zeros(grid.shape)
    return parallel_ridges(grid, period=ridges.period, height=ridges.height, ridge_width_ratio=ridges.width_ratio,
                           pore_density=ridges.pore_density, pore_diameter=ridges.pore_diameter,
                           pore_depth=ridges.pore_depth,
                           rng=np.random.default_rng((scene.study.seed + realisation, 1))).heights


def roughness_heights(scene: Scene, realisation: int, grid=None, short_cutoff: float | None = None) -> np.ndarray:
    """Heights [m] of the micro-roughness of ``realisation`` (rng seed + realisation) on ``grid`` (default: the
    patch grid) with the ``short_cutoff`` in use [m] (default: :func:`resolved_short_cutoff`); zero when
    disabled."""
    grid = patch_grid(scene) if grid is None else grid
    if not scene.roughness.enabled:
        return np.zeros(grid.shape)
    check_patch(scene, grid)
    return self_affine(grid, scene.roughness.hurst, rms_height=scene.roughness.rms_height,
                       long_cutoff=scene.roughness.long_cutoff,
                       short_cutoff=resolved_short_cutoff(scene, grid) if short_cutoff is None else short_cutoff,
                       rng=scene.study.seed + realisation).heights


def patch_surface(scene: Scene, realisation: int, grid=None, short_cutoff: float | None = None) -> np.ndarray:
    """Heights [m] of the patch of ``realisation``: ridges plus micro-roughness on ``grid`` with ``short_cutoff``
    (defaults as :func:`roughness_heights`), or the measured topography."""
    if scene.roughness.topography:
        return measured_topography(scene.roughness).heights
    grid = patch_grid(scene) if grid is None else grid
    heights = ridge_heights(scene, grid, realisation) + roughness_heights(scene, realisation, grid, short_cutoff)
    if not heights.any():                       # (its pores missed, where ridges have no height of their own)
        raise ValueError(FLAT_PATCH)
    return heights


#: Why a patch without a height anywhere is refused.
FLAT_PATCH = "the patch is flat: enable ridges (ridges.enabled, ridges.height > 0) or roughness (roughness.enabled)"


def check_patch(scene: Scene, grid=None) -> None:
    """Refuse, before any solve, a synthetic patch that no realisation can make on ``grid`` (default: the patch
    grid): roughness longer than the patch side, or a patch flat in every realisation (neither roughness nor
    ridges with a height or pores; :func:`patch_surface` refuses a realisation flat by chance)."""
    if scene.roughness.topography:
        return
    grid = patch_grid(scene) if grid is None else grid
    roughness, ridges = scene.roughness, scene.ridges
    if roughness.enabled and roughness.long_cutoff > grid.lengths[0]:
        raise ValueError(f"roughness.long_cutoff = {roughness.long_cutoff!r} m exceeds the patch side "
                         f"{grid.lengths[0]:g} m (presets.{scene.study.preset}.periods x ridges.period); "
                         "valid range (short_cutoff, patch side]")
    relief = ridges.enabled and (ridges.height > 0 or ridges.pore_density * ridges.pore_depth > 0)
    if not (roughness.enabled or relief):
        raise ValueError(FLAT_PATCH)


def patch_body(scene: Scene, grid=None, threads=None):
    """The skin under the patch on ``grid`` (default: the patch grid): a half-space of ``skin.E_star``, or the
    layer bonded on it; in the preset's dtype, with ``threads`` FFT threads (default: ``roughcontact.fft``'s)."""
    grid = patch_grid(scene) if grid is None else grid
    return skin_body(grid, scene.skin, scene.skin.E_star, threads=threads, dtype=scene.preset.dtype)


@dataclass(frozen=True)
class ScenePatch:
    """The default scene's patch as a test case (:func:`default_scene_patch`): ``surface`` heights [m] on ``grid``,
    the skin ``body``, the screen's ``stack``, the apparent ``pressure`` [Pa] and ``area`` [m²] of the footprint."""

    scene: Scene
    grid: object
    surface: np.ndarray
    body: object
    stack: object
    pressure: float
    area: float


def default_scene_patch(grid_size: int, force: float, realisation: int = 0) -> ScenePatch:
    """The default scene's patch at the standard preset on ``grid_size``² pixels (one ridge period), loaded at the
    mean apparent pressure of its fingertip footprint at the normal force ``force`` [N] (one ring): the case of the
    benchmark and study scripts."""
    scene = load_scene(text=f"[presets.standard]\ngrid = {grid_size}\n", preset="standard")
    area, (pressure,) = apparent_contact(scene.fingerpad, force, 1)
    return ScenePatch(scene=scene, grid=patch_grid(scene), surface=patch_surface(scene, realisation),
                      body=patch_body(scene), stack=scene.screen.stack(), pressure=float(pressure), area=float(area))


def realisation_count(scene: Scene) -> int:
    """Distinct patches: the preset's realisations, one when nothing in the patch is random (a measured
    topography is one surface)."""
    if scene.roughness.topography:
        return 1
    pores = scene.ridges.enabled and scene.ridges.pore_density > 0
    return scene.preset.realisations if scene.roughness.enabled or pores else 1


def ridge_area_fraction(contact: np.ndarray, spacing, length: float, periodic=(True, True)) -> float:
    """A_R/A0 of a contact mask: the fraction covered after a morphological closing (dilation, then erosion)
    with a disc of diameter ``length`` [m] on pixels of ``spacing`` [m] (dx, or (dx, dy) for non-square pixels:
    the disc is an ellipse of semi-axes ``length``/(2 dx) and ``length``/(2 dy) pixels); micro-contacts closer
    than ``length`` merge into one ridge contact. A disc that holds one pixel only leaves the mask as it is.
    Periodic convolutions by FFT (counts rounded), so the cost does not grow with the disc; a non-periodic axis
    (``periodic``) is padded with a disc's width of no contact first, so that contacts at opposite edges do not
    merge."""
    contact = np.asarray(contact, dtype=float)
    dx, dy = (spacing, spacing) if np.ndim(spacing) == 0 else spacing
    radius = 0.5 * length / dx                           # in pixels of dx; dy/dx stretches the other axis
    aspect = dy / dx
    if radius < min(1.0, aspect):
        return float(np.mean(contact))
    window = tuple(slice(0, n) for n in contact.shape)
    pads = [int(np.ceil(radius / step)) + 1 for step in (1.0, aspect)]
    contact = np.pad(contact, [(0, 0 if wraps else 2 * pad) for wraps, pad in zip(periodic, pads)])
    rows, columns = (np.fft.fftfreq(n, 1 / n) for n in contact.shape)     # signed pixel offsets, wrapped
    disc = (rows[:, None] ** 2 + (aspect * columns[None, :]) ** 2 <= radius ** 2).astype(float)
    kernel = scipy.fft.rfft2(disc)

    def covered(mask):
        return scipy.fft.irfft2(scipy.fft.rfft2(mask) * kernel, s=contact.shape)

    dilated = (covered(contact) > 0.5).astype(float)
    return float(np.mean((covered(dilated) > disc.sum() - 0.5)[window]))


class PatchScaleWarning(UserWarning):
    """A patch narrower than the A_R closing length or the ridge period (:func:`patch_scale_message`)."""


def surface_window(scene: Scene, grid) -> tuple:
    """``(Lx, Ly)`` [m] of the surface a patch on ``grid`` holds: for a mirrored measured scan the scan's, half
    the patch's along each mirrored axis (both, for a map; ``surfaces.HeightField.mirrored``), else the patch's."""
    if scene.roughness.topography and scene.roughness.boundary == "mirrored":
        return tuple(0.5 * length for length in grid.lengths)
    return tuple(grid.lengths)


def patch_scale_message(scene: Scene, grid) -> str:
    """Why the patch on ``grid`` cannot give ridge-scale numbers, "" when it can: its surface
    (:func:`surface_window`) is narrower than the A_R closing length ℓ (contacts closer than ℓ merge, so the
    closing covers the whole patch once a contact sits in each stretch of ℓ: A_R/A0 tends to 100 %) or than the
    ridge period (no ridge pattern: d_eq, d_field and A_R describe a part of one ridge, and the friction law fed
    with them is not the fingerpad's)."""
    (lx, ly), length, period = surface_window(scene, grid), scene.ridge_area.coarse_graining, scene.ridges.period
    side, scales, effects = min(lx, ly), [], []
    if side < length:
        scales.append(f"the A_R closing length ridge_area.coarse_graining = {length * 1e6:g} µm")
        effects.append("A_R/A0 closes over the whole patch (it tends to 100 %)")
    if side < period:
        scales.append(f"the ridge period ridges.period = {period * 1e6:g} µm")
        effects.append("it holds no ridge pattern")
    if not scales:
        return ""
    mirrored = " (the scan; the patch is its mirror images)" if (lx, ly) != tuple(grid.lengths) else ""
    return (f"the patch's surface, {lx * 1e6:.3g} x {ly * 1e6:.3g} µm{mirrored}, is narrower than "
            f"{' and than '.join(scales)}: {', '.join(effects)}, so d_eq, d_field and A_R describe a part of one "
            "ridge, not the ridge scale, and the friction law fed with them is not the fingerpad's; scan at least "
            "one ridge period, or lower ridge_area.coarse_graining below the patch for the contact on a ridge top")


def gap_slope(gap, weights, spacing, periodic=(True, True)) -> float:
    """rms gap slope |∇g| weighted by ``weights`` (central differences, periodic or second-order one-sided at
    a non-periodic edge)."""
    gx, gy = ((np.roll(gap, -1, axis) - np.roll(gap, 1, axis)) / (2 * spacing[axis]) if periodic[axis]
              else np.gradient(gap, spacing[axis], axis=axis, edge_order=2) for axis in (0, 1))
    return float(np.sqrt(np.sum(weights * (gx ** 2 + gy ** 2)) / np.sum(weights)))


def ridge_equivalent_gap(stack, equivalent_gap: float, ridge_area_fraction: float) -> float:
    """d_eq,R [m]: the uniform gap over A_R that carries the attraction σ̄_el A0 of ``equivalent_gap`` d_eq [m]
    over A0, σ_el(d_eq,R) A_R = σ_el(d_eq) A0, i.e. (c + d_eq,R/ε_a)² = (A_R/A0)(c + d_eq/ε_a)² (seed Eq. 21);
    0 where A_R/A0 (``ridge_area_fraction``) is too small for a positive gap."""
    electrical = np.sqrt(ridge_area_fraction) * stack.electrical_thickness(equivalent_gap)
    return max(float(stack.eps_a * (electrical - stack.dielectric_offset)), 0.0)


def profile_grid(scene: Scene, pixel: float) -> Grid:
    """The periodic profile grid of one ridge period at ``pixel`` [m] (rounded to a whole number of pixels):
    ``Grid((n, 1), (L, L/n))``, the ridge-normal line through the patch."""
    pixel = check_positive("pixel", pixel)
    period = scene.ridges.period
    n = int(round(period / pixel))
    if n < 8:
        raise ValueError(f"pixel = {pixel!r} m leaves {n} pixels on the ridge period {period:g} m; valid: at most "
                         f"{period / 8:g} m (8 pixels)")
    return Grid((n, 1), (period, period / n), periodic=True)


def profile_roughness_spectrum(scene: Scene, period: float):
    """C₁(q) [m³], the line-profile PSD of the scene's isotropic roughness on a ``period`` × ``period`` patch:
    the patch spectrum C(q) summed over the modes across the line, C₁(q_x) = (2π/L) Σ_ky C(√(q_x² + q_y²)).
    A row of the periodic 2-D patch has exactly this spectrum, so its rms height (Σ over all modes) and short
    cut-off (no q_x ≥ q_s) are the patch's; below the long cut-off the oblique modes leave a plateau."""
    roughness = scene.roughness
    surface = SelfAffinePSD(roughness.hurst, 1.0, roughness.long_cutoff, roughness.long_cutoff,
                            roughness.short_cutoff)
    q_y = 2 * np.pi / period * np.arange(-int(period / roughness.short_cutoff) - 1,
                                          int(period / roughness.short_cutoff) + 2)

    def line_spectrum(q):
        q = np.asarray(q, dtype=float)
        return 2 * np.pi / period * surface(np.hypot(q[..., None], q_y)).sum(axis=-1)
    return line_spectrum


def profile_surface(scene: Scene, pixel: float, realisation: int = 0, threads=None) -> tuple:
    """``(heights (n, 1) [m], grid, body)``: one ridge period of the scene's patch as a 1-D profile across the
    ridges at ``pixel`` [m] (:func:`profile_grid`), and the skin under it (:func:`patch_body`, plane strain).

    The ridges are the patch's cross-section (pores of ``realisation`` included when enabled); the roughness
    is a Gaussian profile with the line spectrum of the patch's 2-D spectrum (:func:`profile_roughness_spectrum`),
    normalised to the scene's rms height, rng seed + ``realisation``. (A row of the patch varies about its own
    mean by 1.4 % less: its k_x = 0 modes, 2.7 % of the default spectrum's variance, shift it as a whole and are
    left out of a profile; the profile keeps the patch's rms height instead.) Its random numbers belong to
    wavenumbers (``surfaces.fourier_synthesis``), so every pixel size samples the same band-limited profile: the
    short cut-off is the scene's (``ValueError`` where it is under two pixels), never raised with the pixel."""
    grid = profile_grid(scene, pixel)
    n, period = grid.shape[0], grid.lengths[0]
    across = Grid((1, n), (period / n, period), periodic=True)        # the patch's ridges vary along y
    heights = ridge_heights(scene, grid=across, realisation=realisation).T
    roughness = scene.roughness
    if roughness.enabled:
        if roughness.short_cutoff < 2 * grid.spacing[0]:
            raise ValueError(f"pixel = {pixel!r} m does not resolve roughness.short_cutoff = "
                             f"{roughness.short_cutoff!r} m; valid: pixel <= {roughness.short_cutoff / 2:g} m")
        if roughness.long_cutoff > period:
            raise ValueError(f"roughness.long_cutoff = {roughness.long_cutoff!r} m exceeds the ridge period "
                             f"{period:g} m; valid range (short_cutoff, ridges.period]")
        heights = heights + fourier_synthesis(grid, profile_roughness_spectrum(scene, period),
                                              rng=scene.study.seed + realisation,
                                              rms_height=roughness.rms_height).heights
    return heights, grid, patch_body(scene, grid=grid, threads=threads)
