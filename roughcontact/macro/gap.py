"""Equivalent air-gap models d_eq(F_N, U) [m] for the sliding-friction model (seed Eqs. 25, 46).

A gap model is any callable ``gap_model(normal_force, voltage) -> gap`` (N, V -> m) that broadcasts over its
arguments and returns finite gaps >= 0. The friction code (:mod:`roughcontact.macro.friction`) only ever calls
it, so a bottom-up contact simulation plugs in as a :class:`TabulatedGap` or a plain function.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from surfaces.validation import check_broadcast, check_finite_array, check_positive, check_real, plain


def _inputs(normal_force, voltage):
    return check_broadcast(normal_force=normal_force, voltage=voltage)


@dataclass(frozen=True)
class ConstantGap:
    """d_eq = ``gap`` [m] for every load and voltage."""

    gap: float

    def __post_init__(self):
        object.__setattr__(self, "gap", check_real("gap", self.gap, low=0.0))

    def __call__(self, normal_force, voltage) -> np.ndarray:
        force, _ = _inputs(normal_force, voltage)
        return np.full(force.shape, self.gap)


@dataclass(frozen=True)
class LinearGap:
    """d_eq = max(d_a0 − c₁ F_N, 0) [m] (Eq. 46), independent of the voltage.

    ``gap_at_zero_load`` d_a0 [m] >= 0, ``slope`` c₁ [m/N] (any sign). A gap cannot be negative: beyond
    F_N = d_a0/c₁ (6.2 N for Table 1) the linear law is saturated at d_eq = 0, the direct-contact
    (Strong–Troxel) limit of Eq. 23.
    """

    gap_at_zero_load: float
    slope: float

    def __post_init__(self):
        object.__setattr__(self, "gap_at_zero_load", check_real("gap_at_zero_load", self.gap_at_zero_load, low=0.0))
        object.__setattr__(self, "slope", check_real("slope", self.slope))

    @classmethod
    def paper_table1(cls) -> LinearGap:
        """Table 1: d_a0 = 3.1 µm, c₁ = 0.5 µm/N."""
        return cls(gap_at_zero_load=3.1e-6, slope=0.5e-6)

    def __call__(self, normal_force, voltage) -> np.ndarray:
        force, _ = _inputs(normal_force, voltage)
        return np.maximum(self.gap_at_zero_load - self.slope * force, 0.0)


@dataclass(frozen=True)
class PowerLawGap:
    """d_eq = min(d_ref (F_N/F_ref)^(−exponent), max_gap) [m], independent of the voltage.

    The form Guo et al. (2019) reported for a fingertip on a 3M screen. The power law diverges as F_N → 0, so it
    is capped at ``max_gap`` [m] (default 1 mm, where σ_el is below 1e-6 of its contact value for Table-1
    layers); F_N must be >= 0.
    """

    gap_ref: float
    force_ref: float
    exponent: float
    max_gap: float = 1e-3

    def __post_init__(self):
        object.__setattr__(self, "gap_ref", check_positive("gap_ref", self.gap_ref))
        object.__setattr__(self, "force_ref", check_positive("force_ref", self.force_ref))
        object.__setattr__(self, "exponent", check_real("exponent", self.exponent))
        object.__setattr__(self, "max_gap", check_positive("max_gap", self.max_gap))

    @classmethod
    def through(cls, force_1, gap_1, force_2, gap_2, max_gap=1e-3) -> PowerLawGap:
        """The power law through two points (F₁ [N], d₁ [m]) and (F₂ [N], d₂ [m])."""
        force_1, force_2 = check_positive("force_1", force_1), check_positive("force_2", force_2)
        gap_1, gap_2 = check_positive("gap_1", gap_1), check_positive("gap_2", gap_2)
        if force_1 == force_2:
            raise ValueError(f"force_1 and force_2 must differ, both are {force_1!r} N")
        return cls(gap_ref=gap_1, force_ref=force_1, exponent=-np.log(gap_2 / gap_1) / np.log(force_2 / force_1),
                   max_gap=max_gap)

    @classmethod
    def guo2019(cls) -> PowerLawGap:
        """Guo et al. (2019) at 150 Vpp as quoted by the seed: 2.5 µm at 0.5 N to 1.5 µm at 4.5 N."""
        return cls.through(0.5, 2.5e-6, 4.5, 1.5e-6)

    def __call__(self, normal_force, voltage) -> np.ndarray:
        force, _ = _inputs(normal_force, voltage)
        if (force < 0).any():
            raise ValueError(f"normal_force must be >= 0 for a power-law gap; minimum is {plain(force.min())} N "
                             "(valid range [0, inf))")
        with np.errstate(divide="ignore"):
            gap = self.gap_ref * (force / self.force_ref) ** (-self.exponent)
        return np.minimum(gap, self.max_gap)


def table_axis(name, values, minimum, nonnegative=False) -> np.ndarray:
    """``values`` checked as a table axis: finite, 1-D, strictly increasing, at least ``minimum`` entries."""
    axis = check_finite_array(name, values, nonnegative=nonnegative)
    if axis.ndim != 1 or axis.size < minimum or (np.diff(axis) <= 0).any():
        raise ValueError(f"{name} must be a strictly increasing 1-D array of >= {minimum} values, got {axis!r}")
    return axis


def locate(name, axis, values):
    """Interval index and fraction of ``values`` on the table ``axis`` (index 0 and fraction 0 for a single-entry
    axis); ``ValueError`` outside it (no extrapolation)."""
    if axis.size == 1:       # e.g. a single voltage: the gap does not depend on it
        return np.zeros(values.shape, dtype=int), np.zeros(values.shape)
    if (values < axis[0]).any() or (values > axis[-1]).any():
        raise ValueError(f"{name} outside the table: values span [{plain(values.min())}, {plain(values.max())}], "
                         f"valid range [{plain(axis[0])}, {plain(axis[-1])}]")
    index = np.clip(np.searchsorted(axis, values, side="right") - 1, 0, axis.size - 2)
    return index, (values - axis[index]) / (axis[index + 1] - axis[index])


@dataclass(frozen=True)
class TabulatedGap:
    """d_eq(F_N, |U|) [m] bilinearly interpolated in a table, e.g. from a bottom-up contact simulation.

    ``normal_forces`` [N] (strictly increasing, >= 2 values) and ``voltages`` [V] (strictly increasing, >= 0,
    one value for a voltage-independent gap) span ``gaps`` [m] of shape (len(normal_forces), len(voltages)).
    Points outside the table raise ``ValueError`` (no extrapolation).
    """

    normal_forces: np.ndarray
    voltages: np.ndarray
    gaps: np.ndarray

    def __post_init__(self):
        forces = table_axis("normal_forces", self.normal_forces, 2)
        voltages = table_axis("voltages", self.voltages, 1, nonnegative=True)
        gaps = check_finite_array("gaps", self.gaps, nonnegative=True)
        if gaps.shape != (forces.size, voltages.size):
            raise ValueError(f"gaps has shape {gaps.shape}; it must be (len(normal_forces), len(voltages)) = "
                             f"{(forces.size, voltages.size)}")
        for name, value in (("normal_forces", forces), ("voltages", voltages), ("gaps", gaps)):
            value.flags.writeable = False
            object.__setattr__(self, name, value)

    def __setstate__(self, state):
        """Unpickling: the table checked again and its arrays read-only, as when it was made."""
        for name, value in state.items():
            object.__setattr__(self, name, value)
        self.__post_init__()

    def __eq__(self, other):
        return type(other) is type(self) and all(
            np.array_equal(getattr(self, k), getattr(other, k)) for k in ("normal_forces", "voltages", "gaps"))

    __hash__ = None

    def __call__(self, normal_force, voltage) -> np.ndarray:
        force, voltage = _inputs(normal_force, voltage)
        i, u = locate("normal_force", self.normal_forces, force)
        j, v = locate("|voltage|", self.voltages, np.abs(voltage))
        if self.voltages.size == 1:
            return (1 - u) * self.gaps[i, 0] + u * self.gaps[i + 1, 0]
        return ((1 - u) * (1 - v) * self.gaps[i, j] + u * (1 - v) * self.gaps[i + 1, j]
                + (1 - u) * v * self.gaps[i, j + 1] + u * v * self.gaps[i + 1, j + 1])
