"""The layered field under an AC drive with a leaky stratum corneum: phasors at one frequency.

The stratum corneum conducts (``DielectricStack.sigma_sc`` [S/m]) as well as polarises; the insulator and the
air stay lossless. Under a sinusoidal drive of angular frequency ω = 2π f the quasi-static field is linear, and
every quantity is a phasor: U(t) = Re(√2 U e^{iωt}) with U the **RMS** voltage, D(t) = Re(√2 D̂ e^{iωt}). In the
stratum corneum the total (conduction + displacement) current is continuous with the air's displacement current
iω D̂, so its slab takes the complex permittivity

    ε*_sc = ε_sc + σ_sc / (i ω ε0),

and the layered model of :mod:`~roughcontact.electrostatics.field` holds with ε_sc → ε*_sc:

    (M(ω) + R) D̂ = U,   M̂(q, ω) = [tanh(q d_sc)/(ε*_sc q) + tanh(q d_i)/(eps_i q)] / ε0.

M(ω) is complex symmetric (not Hermitian): it is solved by COCG, the conjugate-orthogonal conjugate gradients
(CG with the bilinear form xᵀy in place of xᴴy), preconditioned with the diagonal of M + R. M(ω) acts on a
complex flux as two real FFT pairs on the grid's real-FFT backend (the real and imaginary parts; its multiplier
is even in q), cheaper than one complex FFT pair (2.1–2.3 real pairs, ``docs/guide/ac_drive.md``).

The force on the skin is the air-side virtual work of the instantaneous flux, σ(t) = ½ Σ_j D_j(t)² ∂R_j/∂g_k
(:meth:`StackField.attraction`). With D_j(t)² = |D̂_j|² + Re(D̂_j² e^{2iωt}) it is

    σ(t) = σ̄ + Re(σ̂₂ e^{2iωt}),   σ̄ = ½ Σ_j |D̂_j|² ∂R_j/∂g_k,   σ̂₂ = ½ Σ_j D̂_j² ∂R_j/∂g_k:

the time average and the complex amplitude of the 2ω component. The RMS convention makes σ̄ at ω → ∞ the
dielectric model's attraction at U exactly. ``frequency = 0`` is a DC voltage U: the stratum corneum is a
conductor in the steady state (its elastance vanishes, the Johnsen–Rahbek limit) and the force is constant
(σ̂₂ = 0); a sinusoid of vanishing frequency has the same σ̄ but |σ̂₂| = σ̄. ``frequency = inf`` is the
dielectric model.
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from numba import njit

from surfaces import HeightField
from surfaces.validation import check_real

from ..io.results import ConvergenceWarning
from .field import (DEFAULT_TOL, FieldSolution, StackField, _cg_curvature, _cg_direction, _cg_start, _cg_update,
                    _grid_and_gap)
from .stack import EPSILON_0, DielectricStack, check_frequency, slab_elastance


def inverse_permittivity(stack: DielectricStack, frequency) -> complex:
    """1/ε*_sc = i ω ε0 / (σ_sc + i ω ε0 ε_sc) (dimensionless): the stratum corneum's relative elastance factor.

    ``frequency`` [Hz]: ``inf`` (or σ_sc = 0) gives 1/ε_sc, the perfect dielectric; 0 gives 0 for σ_sc > 0 (DC:
    the layer is a conductor and carries no voltage)."""
    frequency = check_frequency(frequency)
    if frequency == math.inf or stack.sigma_sc == 0.0:
        return complex(1.0 / stack.eps_sc)
    admittance = 2j * math.pi * frequency * EPSILON_0               # i ω ε0 [S/m per unit permittivity]
    return admittance / (stack.sigma_sc + admittance * stack.eps_sc)


def crossover_frequency(stack: DielectricStack, rest_thickness: float) -> float:
    """f_c = σ_sc / (2π ε0 (ε_sc + d_sc/h_rest)) [Hz]: the corner of the series circuit stratum corneum (R‖C) |
    air + insulator (a capacitor of air-equivalent thickness ``rest_thickness`` h_rest [m]).

    Its time constant is R_sc (C_sc + C_rest) per unit area; the time-averaged attraction of a uniform gap is
    σ̄(ω) = σ̄_∞ + (σ̄_0 − σ̄_∞) / (1 + (f/f_c)²), halfway between its DC and dielectric limits at f_c."""
    rest_thickness = check_real("rest_thickness", rest_thickness, low=0.0, low_open=True)
    return stack.sigma_sc / (2 * math.pi * EPSILON_0 * (stack.eps_sc + stack.d_sc / rest_thickness))


def complex_elastance(stack: DielectricStack, q: np.ndarray, frequency, model: str = "layered") -> np.ndarray:
    """M̂(q, ω) ε0 [m] (complex): the solid layers' air-equivalent thickness seen by the flux mode q at
    ``frequency`` [Hz]; ``model="parallel_plate"`` its uniform value d_sc/ε*_sc + d_i/eps_i."""
    factor = inverse_permittivity(stack, frequency)
    if model == "parallel_plate":
        return np.full(q.shape, factor * stack.d_sc + stack.d_i / stack.eps_i)
    return factor * slab_elastance(q, stack.d_sc, 1.0) + slab_elastance(q, stack.d_i, stack.eps_i)


class ACStackField(StackField):
    """The operator M(ω) + R of one grid at one ``frequency`` [Hz], built once (FFT plan, complex multiplier) and
    solved for many gap fields by COCG. Solutions are at unit RMS voltage.

    ``fft_pairs`` counts the real FFT pairs of all solves (two per application of M(ω))."""

    def __init__(self, stack: DielectricStack, grid, frequency, model: str = "layered", backend: str = "pyfftw",
                 threads=None):
        self.frequency = check_frequency(frequency)
        super().__init__(stack, grid, model=model, backend=backend, threads=threads)
        padded = self.padded_grid
        self._complex_multiplier = complex_elastance(stack, np.hypot(*padded.wavevectors(real=True)),
                                                     self.frequency, model) / (EPSILON_0 * padded.size)
        self._complex_diagonal = complex(np.mean(complex_elastance(stack, np.hypot(*padded.wavevectors()),
                                                                   self.frequency, model)) / EPSILON_0)
        self._spectra = (np.empty_like(self._fft.spectrum), np.empty_like(self._fft.spectrum))
        self.fft_pairs = 0

    @property
    def pixel_elastance(self) -> complex:
        """The diagonal of M(ω) [m²/F] (complex): the Jacobi preconditioner's share of the solid layers."""
        return self._complex_diagonal

    def _transform(self, part: np.ndarray):
        """The backend's spectrum ← FFT of the real array ``part`` (a strided view; zero-padded on a free window,
        else copied by the backend into its own aligned buffer)."""
        source = part
        if self.padded:
            source = self._buffer
            source.fill(0.0)
            source[self._window] = part
        self._fft.forward(source)

    def apply_elastance(self, flux: np.ndarray, out: np.ndarray) -> np.ndarray:
        """out ← M(ω) D̂ [V] for a complex flux D̂ [C/m²] on the window (two real FFT pairs)."""
        real_spectrum, imaginary_spectrum = self._spectra
        self._transform(flux.real)
        real_spectrum[...] = self._fft.spectrum
        self._transform(flux.imag)
        _combine_spectra(self._fft.spectrum, real_spectrum, self._complex_multiplier, imaginary_spectrum)
        self._fft.backward(self._buffer)
        out.real[...] = self._buffer[self._window]
        self._fft.spectrum[...] = imaginary_spectrum
        self._fft.backward(self._buffer)
        out.imag[...] = self._buffer[self._window]
        self.fft_pairs += 2
        return out

    def solve_columns(self, column, initial=None, tol: float = DEFAULT_TOL, maxiter=None) -> tuple:
        """The unit-voltage flux phasor D̂₁ [C/m²/V] with (M(ω) + R) D̂₁ = 1 for the column elastance R [m²/F];
        returns ``(D̂₁, iterations, relative residual)``."""
        maxiter = 10 * column.size if maxiter is None else maxiter
        inverse_diagonal = 1.0 / (self._complex_diagonal + column)
        if self.model == "parallel_plate":
            self.residual = np.zeros(column.shape, complex)
            return inverse_diagonal, 0, 0.0
        flux = inverse_diagonal.copy() if initial is None else np.array(initial, dtype=complex)
        iterations, residual = self.conjugate_gradients(column, inverse_diagonal, flux, tol, maxiter)
        return flux, iterations, residual

    def conjugate_gradients(self, column, inverse_diagonal, flux, tol: float, maxiter: int) -> tuple:
        """COCG on (M(ω) + R) D̂₁ = 1 from ``flux`` (improved in place), preconditioned by ``inverse_diagonal``;
        returns (iterations, relative residual ‖1 − (M + R) D̂₁‖/√n), the residual field on ``self.residual``."""
        if self._work is None or self._work[0].shape != column.shape:
            self._work = tuple(np.empty(column.shape, complex) for _ in range(4))     # allocated once per grid
        product, residual, z, direction = (array.reshape(-1) for array in self._work)
        flat_flux, flat_column, flat_inverse = flux.reshape(-1), column.reshape(-1), inverse_diagonal.reshape(-1)
        # the dielectric CG's kernels run COCG on complex arrays: their sums are the bilinear rᵀz and pᵀAp; the
        # residual's norm rᴴr is taken apart (their r·r is the bilinear rᵀr)
        self.apply_elastance(flux, self._work[0])
        rz = _cg_start(flat_flux, product, flat_column, flat_inverse, residual, z, direction)[0]
        rr = np.vdot(residual, residual).real
        target = (tol * tol) * column.size
        iterations = 0
        while rr > target and iterations < maxiter:
            self.apply_elastance(self._work[3], self._work[0])
            curvature = _cg_curvature(direction, product, flat_column)
            if curvature == 0:
                break                               # a COCG breakdown: reported through the residual
            step = rz / curvature
            rz_old = rz
            rz = _cg_update(step, direction, product, flat_flux, residual, z, flat_inverse)[0]
            rr = np.vdot(residual, residual).real
            _cg_direction(direction, z, rz / rz_old)
            iterations += 1
        self.residual = self._work[1]
        return iterations, float(np.sqrt(rr / column.size))

    def attraction_phasors(self, gap: np.ndarray, unit_flux: np.ndarray) -> tuple:
        """(σ̄/U², σ̂₂/U²) [Pa/V²] per pixel for the unit-voltage flux phasor D̂₁ of ``gap``: the time average
        ½ Σ_j |D̂_j|² ∂R_j/∂g_k and the complex 2ω amplitude ½ Σ_j D̂_j² ∂R_j/∂g_k.

        The virtual-work kernel K(x) = ½ Σ_j x_j² ∂R_j/∂g_k of the dielectric field is linear in x²; with
        D̂ = a + ib: |D̂|² = a² + b², Re D̂² = a² − b², Im D̂² = ((a + b)² − (a − b)²)/2."""
        factor = self.slope_factor(gap)
        real, imaginary = np.ascontiguousarray(unit_flux.real), np.ascontiguousarray(unit_flux.imag)
        of_real, of_imaginary = self.attraction(gap, real, factor), self.attraction(gap, imaginary, factor)
        oscillation = (of_real - of_imaginary) + 0.5j * (self.attraction(gap, real + imaginary, factor)
                                                          - self.attraction(gap, real - imaginary, factor))
        return of_real + of_imaginary, oscillation


@njit(cache=True)
def _combine_spectra(spectrum, real_spectrum, multiplier, imaginary_spectrum):
    """For a flux a + ib with spectra A (``real_spectrum``) and B (``spectrum``) and the complex multiplier m
    (even in q): spectrum ← Re(m) A − Im(m) B (the product's real part), imaginary_spectrum ← Im(m) A + Re(m) B."""
    rows, columns = spectrum.shape
    for i in range(rows):
        for j in range(columns):
            m, a, b = multiplier[i, j], real_spectrum[i, j], spectrum[i, j]
            spectrum[i, j] = m.real * a - m.imag * b
            imaginary_spectrum[i, j] = m.imag * a + m.real * b


@dataclass(frozen=True)
class ACFieldSolution(FieldSolution):
    """The field of the stack over one gap field under a sinusoidal drive of RMS ``voltage`` U [V] at
    ``frequency`` [Hz] (``solve_ac_field``; 0 is a DC voltage U, inf the dielectric model). SI units.

    ``flux`` is the RMS phasor D̂ [C/m²] (complex), ``attraction`` the time-averaged attraction σ̄ [Pa] per pixel
    and ``oscillation`` the complex amplitude σ̂₂ [Pa] of its 2ω component, σ(t) = σ̄ + Re(σ̂₂ e^{2iωt}) (zero at
    DC). ``mean_attraction``, ``electrostatic_force`` and ``field_equivalent_gap`` are those of σ̄ (the uniform gap
    whose Eq. 21 attraction at U is ⟨σ̄⟩)."""

    frequency: float
    oscillation: np.ndarray

    @property
    def energy(self):
        raise AttributeError("a lossy stack has no interaction energy whose gradient is the time-averaged force "
                             "(docs/dev/roadmap.md, 'AC drive'); ACFieldSolution has no energy")

    @property
    def oscillation_amplitude(self) -> np.ndarray:
        """|σ̂₂| [Pa] per pixel: the amplitude of the attraction's 2ω component."""
        return np.abs(self.oscillation)

    @property
    def ac_equivalent_gap(self) -> float:
        """The uniform gap d [m] whose time-averaged attraction under the same drive equals ⟨σ̄⟩: the series circuit
        |a + d/ε_a| = U √(ε0/(2 ε_a ⟨σ̄⟩)) with a = d_sc/ε*_sc + d_i/ε_i solved for d (``field_equivalent_gap`` at
        ω = ∞). Negative above full contact's attraction; ``nan`` at U = 0 and where not even a negative d reaches
        ⟨σ̄⟩."""
        if self.voltage == 0.0:
            return float("nan")
        stack = self.stack
        offset = inverse_permittivity(stack, self.frequency) * stack.d_sc + stack.d_i / stack.eps_i    # a [m]
        thickness = abs(self.voltage) * math.sqrt(EPSILON_0 / (2 * stack.eps_a * self.mean_attraction))   # |h| [m]
        if thickness < abs(offset.imag):
            return float("nan")
        return float(stack.eps_a * (math.sqrt(thickness ** 2 - offset.imag ** 2) - offset.real))

    @property
    def mean_oscillation(self) -> float:
        """|⟨σ̂₂⟩| [Pa]: the amplitude of the 2ω component of the mean attraction (pixels oscillate out of phase,
        so it is at most ⟨|σ̂₂|⟩; it equals ⟨σ̄⟩ for a uniform gap and for a lossless stack)."""
        return float(np.abs(np.mean(self.oscillation)))


def solve_ac_field(stack: DielectricStack, gap, lengths=None, voltage: float = 1.0, *, frequency,
                   model: str = "layered", periodic=True, tol: float = DEFAULT_TOL, maxiter=None,
                   backend: str = "pyfftw") -> ACFieldSolution:
    """The field of ``stack`` over the air-gap field ``gap`` [m] under a sinusoidal drive of RMS ``voltage`` U [V]
    at ``frequency`` [Hz] (module docstring): 0 is a DC voltage U, ``math.inf`` the dielectric model (then
    ``attraction`` equals :func:`~roughcontact.electrostatics.field.solve_field`'s).

    ``gap``, ``lengths``, ``periodic``, ``model``, ``tol``, ``maxiter`` and ``backend`` as for ``solve_field``.
    """
    shape = np.shape(gap.heights if isinstance(gap, HeightField) else gap)
    grid, gap = _grid_and_gap(gap, lengths, periodic)
    voltage = check_real("voltage", voltage)
    field = ACStackField(stack, grid, frequency, model=model, backend=backend, threads=1)
    unit_flux, iterations, residual = field.solve_flux(gap, tol=tol, maxiter=maxiter)
    if residual > tol:
        warnings.warn(f"AC field solve stopped at relative residual {residual:.3g} > tol = {tol:g} after "
                      f"{iterations} iterations", ConvergenceWarning, stacklevel=2)
    mean, oscillation = field.attraction_phasors(gap, unit_flux)
    if field.frequency == 0.0:
        oscillation = np.zeros_like(oscillation)        # a DC voltage: the force does not oscillate
    squared_voltage = voltage ** 2
    return ACFieldSolution(model=field.model, voltage=voltage, stack=stack, grid=grid,
                           flux=(voltage * unit_flux).reshape(shape),
                           attraction=(squared_voltage * mean).reshape(shape), iterations=iterations,
                           residual=residual, frequency=field.frequency,
                           oscillation=(squared_voltage * oscillation).reshape(shape))
