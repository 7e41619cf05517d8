"""Elastic response of the deformable body: surface displacement from surface pressure by FFT.

Fourier multipliers Φ(q) [m/Pa] with ũ(q) = Φ(q) p̃(q) (u positive into the body, p positive compressive;
``docs/reference/conventions.md``):

* periodic half-space: Φ = 2/(E* |q|) (Johnson 1985, Contact Mechanics, §2; docs/references.md §4); the q = 0 mode
  is undetermined and set to 0, so <u> = 0;
* free (non-periodic) surface: the grid is zero-padded to 2n per axis and convolved with the exact
  displacement of a uniform pressure on one rectangular pixel (Love 1929, Phil. Trans. A 228:377):
  u(x, y) = 1/(π E*) Σ± F(x ± dx/2, y ± dy/2), F(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|)
  (DC-FFT, Liu, Wang & Liu 2000, Wear 243:101; Hockney 1970) — the linear, not circular, convolution;
* a layer of thickness t on a rigid base or on a softer half-space: Φ(q) from :mod:`roughcontact.body.kernels`.
  Periodic: on a rigid base the uniform (q = 0) mode is the uniaxial-strain compression t/M (see
  :attr:`ElasticHalfSpace.uniform_compliance`), so <u> = <p> t/M; on a half-space it is set to 0. A layer much
  thicker than the window is the half-space (docs/guide/layered.md, "A layer much thicker than the window").
  Free surface: Love's coefficients of the layer's half-space plus the real-space correction of
  :func:`roughcontact.body.influence.free_surface_correction` (docs/guide/layered.md, "The free-surface kernel"), zero-padded
  like the half-space (wider, with a tapered continuation, where 2n would not give a positive multiplier).

Periodicity comes from the grid and is never changed: a 2-D grid must be periodic on both axes or on none
(mixed periodicity raises ``ValueError``); a profile (shape ``(n, 1)``, plane strain) must be periodic
along x.
"""
from __future__ import annotations

import functools

import numpy as np
from numba import njit

from surfaces import Grid
from surfaces.validation import check_choice, check_finite_array, check_positive, check_real

from ..fft import make_backend
from .influence import free_surface_correction, love_pixel_displacement
from .kernels import BOTTOMS, layer_on_half_space_compliance, layer_on_rigid_base_compliance

# A rigid base's uniform column t/M is kept while it is at most 1/sqrt(ε) ≈ 6.7e7 times the compliance of the
# longest wavelength of the window; beyond that the layer takes the half-space convention for q = 0
# (docs/guide/layered.md, "A layer much thicker than the window").
_COLUMN_LIMIT = 1.0 / np.sqrt(np.finfo(np.float64).eps)


@njit(cache=True)
def apply_multiplier(spectrum, multiplier):
    """spectrum ← spectrum · Φ (complex times real, in place, no temporary)."""
    for i in range(spectrum.shape[0]):
        for j in range(spectrum.shape[1]):
            spectrum[i, j] = spectrum[i, j] * multiplier[i, j]


@njit(cache=True)
def apply_foundation_multiplier(spectrum, multiplier, scaled_stiffness):
    """spectrum ← spectrum · Φ/(1 + κΦ) in place: the body on a foundation of stiffness κ per unit area
    (``scaled_stiffness`` = κ times the transform's size, which Φ holds divided out)."""
    for i in range(spectrum.shape[0]):
        for j in range(spectrum.shape[1]):
            compliance = multiplier[i, j]
            spectrum[i, j] *= compliance / (1.0 + scaled_stiffness * compliance)


@njit(cache=True)
def apply_inverse_multiplier(spectrum, multiplier, scale, zero_mode_stiffness):
    """spectrum ← spectrum / (scale · Φ) in place, and · ``zero_mode_stiffness`` where Φ = 0 (no stored 1/Φ)."""
    for i in range(spectrum.shape[0]):
        for j in range(spectrum.shape[1]):
            compliance = scale * multiplier[i, j]
            spectrum[i, j] *= 1.0 / compliance if compliance > 0 else zero_mode_stiffness


@njit(cache=True)
def _apply_multiplier_quadratic(spectrum, multiplier, n_last):
    """spectrum ← spectrum · Φ in place; returns Σ_q Φ |spectrum|² over the full spectrum (Parseval: the half
    spectrum's columns 0 < j < n_last/2 stand for two), accumulated in float64."""
    total = 0.0
    for i in range(spectrum.shape[0]):
        for j in range(spectrum.shape[1]):
            value = spectrum[i, j]
            weight = 1.0 if (j == 0 or 2 * j == n_last) else 2.0
            total += weight * float(multiplier[i, j]) * (float(value.real) ** 2 + float(value.imag) ** 2)
            spectrum[i, j] = value * multiplier[i, j]
    return total


@njit(cache=True)
def _all_finite(values):
    """True if no entry is NaN or ±inf (one pass, no temporary)."""
    for i in range(values.size):
        if not np.isfinite(values[i]):
            return False
    return True


@njit(cache=True)
def _pressure_work(pressure, displacement):
    """Σ p u in float64 (no temporary; numpy's dot would go through a possibly multi-threaded BLAS)."""
    total = 0.0
    for i in range(pressure.size):
        total += float(pressure[i]) * float(displacement[i])
    return total


def _taper(n, extra) -> np.ndarray:
    """Weights of the offsets 0 … n + extra pixels: 1 up to n − 1 (the window's) and, with ``extra`` > 0, a raised
    cosine beyond that reaches 0 at n + extra (the free-surface layered kernel's continuation into a wider
    padding)."""
    if extra == 0:
        return np.ones(n + 1)
    s = np.clip((np.arange(n + extra + 1) - (n - 1)) / (extra + 1), 0.0, 1.0)
    return 0.5 * (1.0 + np.cos(np.pi * s))


class ElasticHalfSpace:
    """Surface Green's function of the elastic body on ``grid``, applied by FFT on pre-planned buffers.

    Parameters
    ----------
    grid : surfaces.Grid
        Surface grid; its periodicity selects periodic (both axes) or free-surface (neither) convolution, for the
        half-space and every layered body.
    E_star : float
        Contact modulus E* = E/(1 − ν²) [Pa] of the half-space, or of the layer when ``thickness`` is set.
    thickness : float, optional
        Layer thickness [m]; with ``poisson`` and ``bottom`` a layer on a rigid base, with
        ``substrate_E_star``/``substrate_poisson`` a layer bonded on an elastic half-space.
    poisson : float, optional
        Poisson ratio of the layer (required with ``thickness``), in (−1, 0.5].
    bottom : {"bonded", "frictionless"}
        Interface between the layer and a rigid base.
    substrate_E_star, substrate_poisson : float, optional
        Contact modulus [Pa] and Poisson ratio of the half-space under the layer.
    backend : {"pyfftw", "scipy"}
        FFT backend (:mod:`roughcontact.fft`); ``threads`` FFT threads (default: the cores this process may run
        on); ``planner_effort`` FFTW planner flag (default ``FFTW_MEASURE``, plans cached as wisdom on disk).
    dtype : float64 or float32
        Precision of the buffers, of the pressure and of the displacement in a solve.

    Not thread-safe: the FFT buffers are shared state. Pickles by its parameters (plans are rebuilt).
    """

    def __init__(self, grid, E_star, *, thickness=None, poisson=None, bottom="bonded", substrate_E_star=None,
                 substrate_poisson=None, backend="pyfftw", threads=None, dtype=np.float64,
                 planner_effort=None):
        if not isinstance(grid, Grid):
            raise TypeError(f"grid must be a surfaces.Grid, got {type(grid).__name__}")
        self._parameters = dict(thickness=thickness, poisson=poisson, bottom=bottom,
                                substrate_E_star=substrate_E_star, substrate_poisson=substrate_poisson,
                                backend=backend, threads=threads, dtype=np.dtype(dtype).name,
                                planner_effort=planner_effort)
        self.grid = grid
        self.E_star = check_positive("E_star", E_star)
        self.periodic = self._check_periodicity(grid)
        self.layer = self._check_layer(thickness, poisson, bottom, substrate_E_star, substrate_poisson)
        nx, ny = grid.shape
        layered_spectrum = None
        if self.periodic:
            self.transform_shape = (nx, ny)
        elif self.layer is None:
            self.transform_shape = (2 * nx, 2 * ny)
        else:
            layered_spectrum, self.transform_shape = self._layered_free_surface_spectrum()
        self._transform_size = self.transform_shape[0] * self.transform_shape[1]   # N of the FFT pair's 1/N
        self._fft = make_backend(backend, self.transform_shape, dtype, threads, planner_effort)
        self.dtype = self._fft.dtype
        self._padded = None if self.periodic else self._fft.work_array()   # free surface: the padded grid
        self._multiplier = self._fourier_multiplier(layered_spectrum).astype(self.dtype, copy=False)
        self._multiplier.flags.writeable = False
        self._pending = False              # a quadratic_form's K p awaits its backward transform

    # -- construction helpers ------------------------------------------------------------------------------
    @staticmethod
    def _check_periodicity(grid) -> bool:
        px, py = grid.periodic
        if grid.is_profile:
            if not px:
                raise ValueError(f"a profile grid (shape {grid.shape}, plane strain) must be periodic along x; "
                                 f"got periodic = {grid.periodic} (the free plane-strain kernel is not defined)")
            return True
        if px != py:
            raise ValueError(f"mixed periodicity {grid.periodic} is not supported; use a grid periodic on both "
                             "axes or on none")
        return px

    def _check_layer(self, thickness, poisson, bottom, substrate_E_star, substrate_poisson):
        check_choice("bottom", bottom, BOTTOMS)
        on_substrate = substrate_E_star is not None or substrate_poisson is not None
        if thickness is None:
            if poisson is not None or on_substrate:
                raise ValueError("poisson / substrate_E_star / substrate_poisson describe a layer and need "
                                 "thickness; got thickness = None")
            return None
        layer = {"thickness": check_positive("thickness", thickness),
                 "poisson": check_real("poisson", poisson, low=-1.0, high=0.5, low_open=True)}
        if on_substrate:
            layer.update(kind="layer on half-space",
                         substrate_E_star=check_positive("substrate_E_star", substrate_E_star),
                         substrate_poisson=check_real("substrate_poisson", substrate_poisson, low=-1.0,
                                                      high=0.5, low_open=True))
        else:
            layer.update(kind="layer on rigid base", bottom=bottom)
            if self.periodic:
                layer["uniform_mode"] = self._uniform_mode(layer["thickness"], layer["poisson"], bottom)
        return layer

    def _uniform_mode(self, thickness, poisson, bottom) -> str:
        """``"column"`` (⟨u⟩ = ⟨p⟩ t/M) or ``"half-space"`` (⟨u⟩ = 0) for a layer on a rigid base: the column is
        dropped when it exceeds the compliance of the window's longest wavelength by more than _COLUMN_LIMIT."""
        window = max(length for length, n in zip(self.grid.lengths, self.grid.shape) if n > 1) \
            if self.grid.size > 1 else max(self.grid.lengths)
        longest = layer_on_rigid_base_compliance(2 * np.pi / window, self.E_star, poisson, thickness, bottom=bottom)
        column = layer_on_rigid_base_compliance(0.0, self.E_star, poisson, thickness, bottom="bonded")
        return "column" if column <= _COLUMN_LIMIT * longest else "half-space"

    def compliance(self, q) -> np.ndarray:
        """Fourier multiplier Φ(q) [m/Pa] at wavevector magnitudes ``q`` > 0 [rad/m] (ũ = Φ p̃)."""
        q = np.asarray(q, dtype=float)
        if self.layer is None:
            return 2.0 / (self.E_star * q)
        layer = self.layer
        if layer["kind"] == "layer on rigid base":
            return layer_on_rigid_base_compliance(q, self.E_star, layer["poisson"], layer["thickness"],
                                                          bottom=layer["bottom"])
        return layer_on_half_space_compliance(q, self.E_star, layer["poisson"], layer["thickness"],
                                                      layer["substrate_E_star"], layer["substrate_poisson"])

    def _fourier_multiplier(self, layered_spectrum=None) -> np.ndarray:
        """Φ on the half spectrum of the transform grid, including the 1/N of the unnormalised FFT pair
        (``layered_spectrum``: the free-surface layered body's, made before the FFT plan)."""
        if layered_spectrum is not None:
            return layered_spectrum / self._transform_size
        if not self.periodic:
            return self._free_surface_multiplier() / self._transform_size
        qx, qy = self.grid.wavevectors(real=True)
        q = np.hypot(qx, qy)
        multiplier = np.zeros(q.shape)
        positive = q > 0
        multiplier[positive] = self.compliance(q[positive])
        if self.layer is not None and self.layer["kind"] == "layer on rigid base":
            multiplier[0, 0] = self.uniform_compliance
        return multiplier / self._transform_size

    @property
    def uniform_compliance(self) -> float:
        """⟨u⟩/⟨p⟩ [m/Pa] of a periodic layer on a rigid base (0 on a free surface, which has no separate uniform
        mode): the uniaxial-strain column t/M, M = E*(1 − ν)²/(1 − 2ν), whatever the bottom condition (by
        symmetry a uniform load on a laterally periodic layer moves nothing sideways; it is not the q → 0 limit
        of the frictionless Φ(q), t/E*, for which the layer can spread over a long wavelength). 0 for the half-space and the layer on a
        half-space (q = 0 mode undetermined, set to 0), and for a layer so thick that the column would exceed the
        compliance of the window's longest wavelength 6.7e7-fold (``layer["uniform_mode"] == "half-space"``;
        ``docs/guide/layered.md``, "A layer much thicker than the window")."""
        if self.layer is None or self.layer.get("uniform_mode") != "column":
            return 0.0
        # the uniaxial column is the q → 0 limit of the *bonded* layer (no lateral strain at the base)
        return float(layer_on_rigid_base_compliance(0.0, self.E_star, self.layer["poisson"], self.layer["thickness"],
                                                    bottom="bonded"))

    @functools.cached_property
    def _zero_mode_stiffness(self) -> float:
        """Multiplier of the preconditioner K⁻¹ on modes with Φ = 0: the smallest stiffness of the others (with
        the 1/N of the FFT pair), so that the preconditioner is positive definite. 1/Φ itself is not stored:
        :func:`apply_inverse_multiplier` divides."""
        n_total = self._transform_size
        largest = float(self._multiplier.max())
        return 1.0 / (largest * n_total * n_total) if largest > 0 else 1.0 / n_total

    def _free_surface_multiplier(self) -> np.ndarray:
        """FFT of the Love pixel influence coefficients laid out for the padded (linear) convolution, made
        row by row in the padded work array and transformed with the half-space's own plan (no 2n × 2n
        temporaries; with ``dtype=float32`` the transform is in float32 too, i.e. Φ to ~1e-7 relative)."""
        nx, ny = self.grid.shape
        dx, dy = self.grid.spacing
        offsets_x = np.fft.fftfreq(2 * nx, 1.0 / (2 * nx)) * dx     # 0, dx, …, −dx: wrapped distances
        offsets_y = np.fft.fftfreq(2 * ny, 1.0 / (2 * ny)) * dy
        for row, offset in zip(self._padded, offsets_x):
            row[:] = love_pixel_displacement(offset, offsets_y, dx, dy, self.E_star)
        self._fft.forward(self._padded)
        return self._fft.spectrum.real.astype(np.float64)   # coefficients are even in x and y → real spectrum

    def _layered_free_surface_spectrum(self) -> tuple:
        """``(spectrum, transform_shape)`` of a layered body on a free surface (``docs/guide/layered.md``, "The
        free-surface kernel"): Love's coefficients of the layer's half-space plus
        :func:`roughcontact.body.influence.free_surface_correction` (b = 2/E0* − 2/E* on a half-space E0*, −2/E* on a
        rigid base), laid out for the linear convolution and transformed in float64. The window needs the offsets
        up to n − 1 pixels only; if the 2n padding's spectrum is not positive (a stiff layer far stiffer than its
        substrate on a coarse grid: the truncated 1/r tail of the substrate's response outweighs the layer's small
        high-q compliance), the padding grows to 3n, then 4n, with the kernel continued beyond n − 1 pixels and
        tapered to zero by a raised cosine, until it is; ``ValueError`` if it never is."""
        from scipy import fft

        on_substrate = self.layer["kind"] == "layer on half-space"
        slope = 2.0 / self.layer["substrate_E_star"] - 2.0 / self.E_star if on_substrate else -2.0 / self.E_star
        (nx, ny), (dx, dy) = self.grid.shape, self.grid.spacing
        for mx, my in ((0, 0), (nx // 2, ny // 2), (nx, ny)):       # offsets beyond the window's, per axis
            x, y = np.arange(nx + mx + 1) * dx, np.arange(ny + my + 1) * dy
            coefficients = (love_pixel_displacement(x[:, None], y[None, :], dx, dy, self.E_star)
                            + free_surface_correction(self.compliance, self.E_star, slope, self.layer["thickness"],
                                                      x, y, dx, dy))
            layout = coefficients * np.outer(_taper(nx, mx), _taper(ny, my))
            shape = (2 * (nx + mx), 2 * (ny + my))
            rows = np.abs(np.fft.fftfreq(shape[0], 1.0 / shape[0])).astype(int)
            columns = np.abs(np.fft.fftfreq(shape[1], 1.0 / shape[1])).astype(int)
            spectrum = fft.rfft2(layout[rows][:, columns]).real      # even in x and y → real spectrum
            if spectrum.min() > 0:
                return spectrum, shape
        raise ValueError(f"the free-surface kernel of the layer {self.layer} on grid {self.grid} is not positive "
                         f"on a padded grid up to {shape}: smallest Fourier multiplier {spectrum.min():.3g} of "
                         f"largest {spectrum.max():.3g}; refine the grid (pixel {dx:g} m x {dy:g} m)")

    def padded_operator(self) -> PaddedOperator:
        """The free surface's operator on its zero-padded transform grid as a periodic body: a
        :class:`PaddedOperator` sharing this body's FFT buffers. ``ValueError`` on a periodic body (its own
        operator is periodic already)."""
        if self.periodic:
            raise ValueError(f"padded_operator() is the free surface's operator on its padded grid; this body on "
                             f"{self.grid} is periodic, its own operator is that periodic operator")
        return PaddedOperator(self)

    def coarsened(self) -> ElasticHalfSpace:
        """A new half-space: the same body on ``grid.coarsened(2)`` (the solver's nested cold start);
        ``ValueError`` if the grid's pixel counts are odd."""
        return ElasticHalfSpace(self.grid.coarsened(2), self.E_star, **self._parameters)

    # -- pickling: parameters only ---------------------------------------------------------------------------
    def __getstate__(self):
        return {"grid": self.grid, "E_star": self.E_star, **self._parameters}

    def __setstate__(self, state):
        self.__init__(state.pop("grid"), state.pop("E_star"), **state)

    def __repr__(self):
        kind = "periodic" if self.periodic else "free surface"
        layer = "" if self.layer is None else f", layer={self.layer}"
        return (f"ElasticHalfSpace(grid={self.grid}, E_star={self.E_star:g} Pa, {kind}{layer}, "
                f"backend={self._fft.name!r}, dtype={self.dtype.name})")

    @property
    def description(self) -> dict:
        """Plain-data description for result parameters."""
        return {"E_star": self.E_star, "periodic": self.periodic, "layer": self.layer,
                "backend": self._fft.name, "threads": self._fft.threads, "dtype": self.dtype.name,
                "transform_shape": list(self.transform_shape)}

    @property
    def backend(self) -> str:
        return self._fft.name

    @functools.cached_property
    def pixel_compliance(self) -> float:
        """Displacement of a pixel under unit pressure on that pixel alone [m/Pa] (diagonal of K).

        The unit impulse has a flat spectrum, so this is Σ_q Φ_q / N over the full transform grid, summed from the
        stored half spectrum without a transform (it may be read between :meth:`quadratic_form` and
        :meth:`pending_displacement_into`) and cached."""
        n_last = self.transform_shape[1]
        columns = np.arange(self._multiplier.shape[1])
        weights = np.where((columns == 0) | (2 * columns == n_last), 1.0, 2.0)
        return float(np.sum(self._multiplier.astype(np.float64) * weights))

    # -- the operator ------------------------------------------------------------------------------------------
    def empty(self) -> np.ndarray:
        """Uninitialised array of ``grid.shape`` in this dtype that the periodic FFT uses without copying."""
        return self._fft.empty() if self.periodic else np.empty(self.grid.shape, self.dtype)

    def displacement_into(self, pressure: np.ndarray, out: np.ndarray) -> np.ndarray:
        """Write u = K p [m] for ``pressure`` [Pa] (``grid.shape``, this dtype) into ``out``; ``out`` is returned.

        No allocation; with arrays from :meth:`empty` (periodic grids) no copy either. Free surface: p is
        placed in the corner of the zero-padded 2n buffer and u read back from the same corner. Shapes and
        finiteness are checked (``ValueError``; one pass over p, no allocation).
        """
        self._check_shape("pressure", pressure)
        self._check_shape("out", out)
        if not _all_finite(pressure.reshape(-1)):
            raise ValueError("pressure must be finite everywhere (found NaN or inf); valid range: finite reals [Pa]")
        return self._displacement_into(pressure, out)

    def _displacement_into(self, pressure, out):
        """:meth:`displacement_into` without its checks: the solvers' inner loop, whose arrays are its own."""
        self._forward(pressure)
        apply_multiplier(self._fft.spectrum, self._multiplier)
        return self._backward_into(out)

    def _foundation_displacement_into(self, pressure, out, stiffness):
        """The displacement [m] of the body resting on a foundation of stiffness ``stiffness`` κ [Pa/m] per unit area
        under ``pressure`` [Pa] into ``out``: the multiplier Φ/(1 + κΦ). A solver's preconditioner (the hard wall
        on the gap, :mod:`roughcontact.solvers.projected_cg_gap`: the points held at the wall pin the surface);
        unchecked, as :meth:`_displacement_into`."""
        self._forward(pressure)
        apply_foundation_multiplier(self._fft.spectrum, self._multiplier, stiffness * self._transform_size)
        return self._backward_into(out)

    def stiffness_into(self, displacement: np.ndarray, out: np.ndarray) -> np.ndarray:
        """Write the pressure [Pa] that the inverse multiplier 1/Φ assigns to ``displacement`` [m] into ``out``.

        The exact inverse of K on a periodic grid (except for the q = 0 mode, given the smallest stiffness
        of the other modes when Φ(0) = 0); on a free surface the inverse of the padded operator. Used as the
        conjugate-gradient preconditioner; ``out`` may be ``displacement``.
        """
        self._forward(displacement)
        apply_inverse_multiplier(self._fft.spectrum, self._multiplier, float(self._transform_size) ** 2,
                                  self._zero_mode_stiffness)
        return self._backward_into(out)

    def quadratic_form(self, pressure: np.ndarray) -> float:
        """⟨p, K p⟩ = Σ_x p (K p) [Pa·m] over the grid points, by Parseval from one forward transform
        (= 2 U / pixel area, U the elastic energy of p). K p is left pending in the spectrum: a
        :meth:`pending_displacement_into` right after this call completes the convolution for the cost of
        the backward transform alone."""
        self._forward(pressure)
        self._pending = True
        return _apply_multiplier_quadratic(self._fft.spectrum, self._multiplier, self.transform_shape[1])

    def pending_displacement_into(self, out: np.ndarray) -> np.ndarray:
        """Write K p for the ``p`` of the last :meth:`quadratic_form` into ``out`` (its backward transform)."""
        if not self._pending:
            raise RuntimeError("no pending displacement: call quadratic_form(p) first (any other transform in "
                               "between discards it)")
        return self._backward_into(out)

    def _check_shape(self, name, array):
        if np.shape(array) != self.grid.shape:
            raise ValueError(f"{name} has shape {np.shape(array)}, but grid.shape is {self.grid.shape}")

    def _forward(self, source):
        """Forward transform of ``source`` (zero-padded to the transform grid on a free surface)."""
        self._pending = False
        if self.periodic:
            self._fft.forward(source)
            return
        nx, ny = self.grid.shape
        padded = self._padded
        padded[nx:, :] = 0                                      # backward() filled the padding last time
        padded[:nx, ny:] = 0
        padded[:nx, :ny] = source
        self._fft.forward(padded)

    def _backward_into(self, out):
        """Backward transform of the spectrum into ``out`` (its n-corner on a free surface)."""
        self._pending = False
        if self.periodic:
            self._fft.backward(out)
            return out
        nx, ny = self.grid.shape
        self._fft.backward(self._padded)
        np.copyto(out, self._padded[:nx, :ny])
        return out

    def displacement(self, pressure) -> np.ndarray:
        """Surface displacement u [m] (positive into the body) under ``pressure`` [Pa] (compressive > 0)."""
        pressure = check_finite_array("pressure", pressure)
        if pressure.shape != self.grid.shape:
            raise ValueError(f"pressure has shape {pressure.shape}, but grid.shape is {self.grid.shape}")
        out = np.empty(self.grid.shape, self.dtype)
        return self.displacement_into(pressure.astype(self.dtype, copy=False), out)

    def elastic_energy(self, pressure, displacement) -> float:
        """Stored elastic energy U = ½ ∫ p u dA [J] of a pressure [Pa] and its displacement [m]."""
        p, u = np.ravel(pressure), np.ravel(displacement)
        if p.shape != u.shape:
            raise ValueError(f"pressure and displacement differ in size: {p.size} vs {u.size}")
        return 0.5 * self.grid.pixel_area * _pressure_work(p, u)


class PaddedOperator:
    """A free surface's operator K_T on its zero-padded transform grid ``shape`` (the body's ``transform_shape``),
    as a periodic body: the Fourier multiplier Φ_T of :class:`ElasticHalfSpace` without the window, so it has an
    exact inverse and a positive uniform mode Φ_T(0) (``uniform_compliance``). Made by
    :meth:`ElasticHalfSpace.padded_operator`.

    A traction on the window alone (zero on the padding) gives the window the free surface's displacement K p: the
    padded convolution is the linear one. A solve on the whole transform grid that leaves the padding's
    displacement free and acts on the window only therefore has zero traction on the padding at its minimum,
    and its window is the free surface's (the smooth contact solve, ``docs/guide/interactions.md``).

    Arrays are of ``shape`` in ``dtype``; :meth:`empty` gives ones the FFT uses in place. Shares the body's FFT
    buffers: not thread-safe, and a transform discards the body's pending :meth:`~ElasticHalfSpace.quadratic_form`.
    """

    def __init__(self, body: ElasticHalfSpace):
        self._body = body
        self.shape, self.dtype = body.transform_shape, body.dtype
        self._size = float(body.transform_shape[0] * body.transform_shape[1])
        #: Φ_T(0) [m/Pa]: the mean displacement of the transform grid per unit mean traction
        self.uniform_compliance = float(body._multiplier[0, 0]) * self._size
        #: the largest Φ_T(q) [m/Pa]
        self.largest_compliance = float(body._multiplier.max()) * self._size
        #: the displacement of a pixel under unit pressure on it alone [m/Pa] (the body's)
        self.pixel_compliance = body.pixel_compliance

    def empty(self) -> np.ndarray:
        """An uninitialised array of ``shape`` in ``dtype`` that the FFT uses without copying."""
        return self._body._fft.empty()

    def displacement_into(self, pressure: np.ndarray, out: np.ndarray) -> np.ndarray:
        """Write u = K_T p [m] for ``pressure`` [Pa] on the transform grid into ``out`` (returned); shapes and
        finiteness checked (``ValueError``), as :meth:`ElasticHalfSpace.displacement_into`."""
        for name, array in (("pressure", pressure), ("out", out)):
            if np.shape(array) != self.shape:
                raise ValueError(f"{name} has shape {np.shape(array)}, but the transform grid's shape is {self.shape}")
        if not _all_finite(pressure.reshape(-1)):
            raise ValueError("pressure must be finite everywhere (found NaN or inf); valid range: finite reals [Pa]")
        return self._displacement_into(pressure, out)

    def _displacement_into(self, pressure, out):
        """:meth:`displacement_into` without its checks: the solvers' inner loop, whose arrays are its own."""
        fft = self._body._fft
        self._body._pending = False
        fft.forward(pressure)
        apply_multiplier(fft.spectrum, self._body._multiplier)
        fft.backward(out)
        return out

    def _foundation_displacement_into(self, pressure, out, stiffness):
        """:meth:`ElasticHalfSpace._foundation_displacement_into` on the transform grid: Φ_T/(1 + κΦ_T)."""
        fft = self._body._fft
        self._body._pending = False
        fft.forward(pressure)
        apply_foundation_multiplier(fft.spectrum, self._body._multiplier, stiffness * self._size)
        fft.backward(out)
        return out

    def stiffness_into(self, displacement: np.ndarray, out: np.ndarray) -> np.ndarray:
        """Write p = K_T⁻¹ u [Pa] for ``displacement`` [m] on the transform grid into ``out`` (returned; it may be
        ``displacement``): the exact inverse, Φ_T being positive at every q."""
        fft = self._body._fft
        self._body._pending = False
        fft.forward(displacement)
        apply_inverse_multiplier(fft.spectrum, self._body._multiplier, self._size ** 2, 0.0)
        fft.backward(out)
        return out
