"""Scale coupling: the micro-roughness reduced to an interface law that a ridge-scale solve uses.

The fully resolved study (:mod:`roughcontact.study`) puts ridges and micro-roughness in one grid. The coupled
path separates them (``docs/equivalent_gap.md``, "Scale coupling"):

1. **Micro scale.** A periodic patch of the micro-roughness alone on the same skin is brought to a sequence of
   mean separations ū (displacement control, from far to near, each solve started from the last, with the
   electrostatic attraction at the voltage U). Each gives the mean traction p(ū) [Pa] that the interface
   transmits (contact minus attraction, positive compressive), its Eq. 25 gap e(ū) [m] and its real contact
   fraction φ(ū).
2. **Ridge scale.** The ridges alone, on a coarser grid, are pressed at the nominal pressure with
   :class:`InterfaceLaw` (traction p(ū), ū the ridge-scale gap) acting between them and the screen.
3. **Averages.** d_eq = Eq. 25 of the field e(ū(x)) (exact: Eq. 25 of the pixel-wise equivalent gaps is Eq. 25
   of the underlying field); the real contact fraction is the mean of φ(ū(x)).

Scale separation is the assumption: a ridge-scale pixel behaves like a micro patch at the same mean
separation; the micro-roughness's long-wavelength coupling to the ridge curvature is lost.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .interactions import Interaction


@dataclass(frozen=True)
class InterfaceLaw(Interaction):
    """Tabulated interface law of a rough micro patch: traction p(ū) [Pa] (positive compressive), Eq. 25 gap
    e(ū) [m] and real contact fraction φ(ū) at mean separations ū [m] (``separations``, strictly increasing).

    Between the nodes monotone cubic (PCHIP) interpolation; below the first node the cubic extrapolates; beyond
    the last node the traction follows the flat-plate attraction −σ_el(ū) of ``stack`` at ``voltage`` scaled to
    be continuous (0 at 0 V), e(ū) = ū shifted to be continuous, φ = 0. Energy V(ū) = ∫_ū^∞ p dū'.
    """

    separations: tuple
    tractions: tuple
    equivalent_gaps: tuple
    contact_fractions: tuple
    stack: object
    voltage: float
    length: float
    _splines: dict = field(default=None, repr=False, compare=False)

    def __post_init__(self):
        from scipy.interpolate import PchipInterpolator
        x = np.asarray(self.separations, float)
        if x.ndim != 1 or x.size < 3 or (np.diff(x) <= 0).any():
            raise ValueError(f"separations must be >= 3 strictly increasing values, got {self.separations!r}")
        traction = PchipInterpolator(x, np.asarray(self.tractions, float))
        object.__setattr__(self, "_splines", {
            "traction": traction, "stiffness": traction.derivative(), "antiderivative": traction.antiderivative(),
            "equivalent_gap": PchipInterpolator(x, np.asarray(self.equivalent_gaps, float)),
            "contact_fraction": PchipInterpolator(x, np.asarray(self.contact_fractions, float))})

    @property
    def _tail_scale(self) -> float:
        """Factor on −σ_el beyond the table that makes the traction continuous there (0 at 0 V)."""
        sigma = float(self.stack.pressure(self.separations[-1], self.voltage))
        return -self.tractions[-1] / sigma if sigma > 0 else 0.0

    def _split(self, gap):
        gap = np.asarray(gap, dtype=float)
        return gap, gap > self.separations[-1]

    def traction(self, gap) -> np.ndarray:
        gap, far = self._split(gap)
        inside = self._splines["traction"](np.minimum(gap, self.separations[-1]))
        return np.where(far, -self._tail_scale * self.stack.pressure(gap, self.voltage), inside)

    def stiffness(self, gap) -> np.ndarray:
        gap, far = self._split(gap)
        inside = self._splines["stiffness"](np.minimum(gap, self.separations[-1]))
        return np.where(far, -self._tail_scale * self.stack.pressure_derivative(gap, self.voltage), inside)

    def energy(self, gap) -> np.ndarray:
        gap, far = self._split(gap)
        last = self.separations[-1]
        tail = self._tail_scale * self.stack.energy(np.maximum(gap, last), self.voltage)   # ∫_ū^∞ of the tail
        antiderivative = self._splines["antiderivative"]
        inside = antiderivative(last) - antiderivative(np.minimum(gap, last))
        return np.where(far, tail, inside + self._tail_scale * float(self.stack.energy(last, self.voltage)))

    def equivalent_gap(self, gap) -> np.ndarray:
        """e(ū) [m]: the Eq. 25 gap of the micro patch at mean separation ū."""
        gap, far = self._split(gap)
        last = self.separations[-1]
        inside = self._splines["equivalent_gap"](np.minimum(gap, last))
        return np.maximum(np.where(far, gap - last + self.equivalent_gaps[-1], inside), 0.0)

    def contact_fraction(self, gap) -> np.ndarray:
        """φ(ū): the real contact fraction of the micro patch at mean separation ū."""
        gap, far = self._split(gap)
        inside = self._splines["contact_fraction"](np.minimum(gap, self.separations[-1]))
        return np.clip(np.where(far, 0.0, inside), 0.0, 1.0)


def interface_law(heights, body, stack, voltage: float, nodes: int = 24, tol: float = 1e-7) -> InterfaceLaw:
    """The :class:`InterfaceLaw` of the periodic micro patch ``heights`` [m] on ``body`` at ``voltage`` [V]:
    ``nodes`` mean separations from 2 % of the rms height to the highest summit plus two rms heights, solved
    from far to near (displacement control, each from the last)."""
    from .contact import solve_contact
    from .interactions import ElectrostaticInteraction
    heights = np.asarray(heights, float)
    mean, top, rms = heights.mean(), heights.max(), heights.std()
    far = top - mean + 2 * rms
    separations = np.geomspace(0.02 * rms, far, nodes)
    law = ElectrostaticInteraction(stack, voltage=voltage) if voltage > 0 else None
    rows, previous = [], None
    for separation in separations[::-1]:
        result = solve_contact(heights, body, penetration=top - mean - separation, interaction=law, tol=tol,
                               x0=previous, warn=False)
        rows.append((result.mean_pressure, stack.equivalent_gap(result.gap), result.contact_fraction))
        previous = result
    tractions, gaps, fractions = (tuple(float(v) for v in column[::-1]) for column in zip(*rows))
    return InterfaceLaw(separations=tuple(float(s) for s in separations), tractions=tractions,
                        equivalent_gaps=gaps, contact_fractions=fractions, stack=stack, voltage=float(voltage),
                        length=float(rms))


@dataclass(frozen=True)
class CoupledPoint:
    """The coupled path at one nominal pressure [Pa] and voltage [V]: d_eq [m] (Eq. 25), the real contact
    fraction, the ridge-scale mean separation [m] and whether the ridge-scale solve converged."""
    pressure: float
    voltage: float
    equivalent_gap: float
    contact_fraction: float
    mean_separation: float
    converged: bool


def coupled_point(ridges, body, law: InterfaceLaw, pressure: float, tol: float = 1e-7, x0=None) -> tuple:
    """Solve the ridge heights ``ridges`` [m] on ``body`` at the nominal ``pressure`` [Pa] with ``law`` acting;
    returns ``(CoupledPoint, ContactResult)`` (the result to warm-start the next solve)."""
    from .contact import solve_contact
    result = solve_contact(ridges, body, mean_pressure=pressure, interaction=law, tol=tol, x0=x0, warn=False)
    separation = np.asarray(result.gap)
    point = CoupledPoint(pressure=float(pressure), voltage=law.voltage,
                         equivalent_gap=law.stack.equivalent_gap(law.equivalent_gap(separation)),
                         contact_fraction=float(np.mean(law.contact_fraction(separation))),
                         mean_separation=float(separation.mean()), converged=bool(result.converged))
    return point, result
