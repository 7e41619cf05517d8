"""What every contact solver takes, checked once: the body, the surface on its grid and its heights in the body's
dtype, the interaction law, and the :class:`Control` of a solve (what is fixed, the tolerance, the iteration limit,
the warm start, the callback). :class:`~roughcontact.solvers.problem.ContactProblem` calls the checks; the
methods take their results as they are."""
from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass
from typing import Callable

import numpy as np

from surfaces import HeightField
from surfaces.validation import check_bool, check_finite_array, check_integer, check_positive, check_real

from ..body import ElasticHalfSpace
from ..interactions import HardWall, Interaction
from ..io.results import ConvergenceWarning
from .result import ContactResult

#: The quantities a solve can fix: the external load as a mean pressure [Pa] or a total force [N], or the
#: penetration δ = max(h) − s [m] (displacement control).
CONTROLS = ("mean_pressure", "total_force", "penetration")
#: Relative tolerance below which a solve in float32 may not converge: its residual is computed from fields
#: resolved to ε32 ≈ 1.2e-7, so round-off may stop it near a few ε32 (a rough patch's Polonsky–Keer solve
#: stalls there; a smooth cosine's energy solve reached 1.2e-9, but not 1e-9, in 3000 steps).
FLOAT32_TOL_FLOOR = 4 * float(np.finfo(np.float32).eps)


@dataclass(frozen=True)
class Control:
    """How one solve is driven: ``kind`` (one of :data:`CONTROLS`) fixed at ``value`` (SI: Pa, N or m), so the
    external load ``mean_pressure`` <p> [Pa] (a total force over the grid's area; None under displacement control);
    the relative tolerance ``tol``, the iteration limit ``maxiter``, the warm start ``x0`` (a
    :class:`~roughcontact.solvers.ContactResult` for a smooth law's method, a pressure field [Pa] for
    Polonsky–Keer, or None), ``callback`` and ``warn`` (:func:`~roughcontact.solvers.solve_contact`).

    :meth:`ContactProblem.control <roughcontact.solvers.problem.ContactProblem.control>` makes it checked; the
    constructor and :meth:`at` do not check (a method's derived solves: its starts and corrections).
    """

    kind: str
    value: float
    mean_pressure: float | None
    tol: float
    maxiter: int = 10000
    x0: object = None
    callback: Callable | None = None
    warn: bool = True

    @property
    def penetration(self) -> float | None:
        """δ = max(h) − s [m] under displacement control, else None."""
        return self.value if self.kind == "penetration" else None

    def at(self, *, mean_pressure=None, penetration=None, **changes) -> Control:
        """This control at the mean pressure ``mean_pressure`` [Pa] or the penetration ``penetration`` [m] (one of
        them), with ``changes`` to its other fields."""
        if (mean_pressure is None) == (penetration is None):
            raise ValueError("give exactly one of mean_pressure, penetration")
        kind, value = ("mean_pressure", mean_pressure) if penetration is None else ("penetration", penetration)
        return dataclasses.replace(self, kind=kind, value=value, mean_pressure=mean_pressure, **changes)


def check_body(body) -> ElasticHalfSpace:
    """``body``, checked to be an :class:`~roughcontact.body.ElasticHalfSpace`."""
    if not isinstance(body, ElasticHalfSpace):
        raise TypeError(f"body must be an ElasticHalfSpace, got {type(body).__name__}")
    return body


def checked_surface(surface, body: ElasticHalfSpace) -> HeightField:
    """The topography ``surface`` (a HeightField on the body's grid, or an array of heights [m] of its shape) as a
    HeightField; an array's heights are taken in the body's dtype (rounded as a solve takes them)."""
    if isinstance(surface, HeightField):
        if surface.grid != body.grid:
            raise ValueError(f"surface.grid {surface.grid} differs from the body's grid {body.grid}")
        return surface
    heights = check_finite_array("surface", surface)
    if heights.shape != body.grid.shape:
        raise ValueError(f"surface has shape {heights.shape}, but the body's grid has shape {body.grid.shape}")
    return HeightField(body.grid, np.ascontiguousarray(heights, dtype=body.dtype))


def body_heights(heights: np.ndarray, body: ElasticHalfSpace) -> np.ndarray:
    """The heights h [m] as the solvers take them: C-contiguous in the body's dtype (no copy where they are),
    read-only."""
    heights = np.ascontiguousarray(heights, dtype=body.dtype)
    heights.flags.writeable = False
    return heights


def default_tolerance(dtype, interaction=None) -> float:
    """The default relative tolerance of a solve in ``dtype``: 1e-8 in float64; in float32 1e-6 for the hard wall
    (its round-off floor is near 1e-7) and 1e-5 with a smooth law (the energy's round-off stops the line search
    near 4e-6)."""
    if np.dtype(dtype) == np.float64:
        return 1e-8
    return 1e-5 if interaction is not None and interaction.smooth and not interaction.vanishes else 1e-6


def checked_interaction(interaction) -> Interaction:
    """The law to solve with (HardWall() for None), checked."""
    if interaction is None:
        return HardWall()
    if not isinstance(interaction, Interaction):
        raise TypeError(f"interaction must be an Interaction (roughcontact.interactions), got "
                        f"{type(interaction).__name__}")
    if type(interaction) is Interaction:
        raise ValueError("interaction = Interaction() is the abstract base class; pass a law such as HardWall(), "
                         "ElectrostaticInteraction(stack, voltage) or a subclass that implements energy, traction "
                         "and stiffness")
    if interaction.smooth:
        length = getattr(interaction, "length", None)
        if isinstance(length, bool) or not isinstance(length, (int, float, np.floating, np.integer)) \
                or not math.isfinite(length) or length <= 0:
            raise ValueError(f"interaction {type(interaction).__name__} needs length, the gap scale [m] over which "
                             f"it varies, a finite float > 0 (valid range (0, inf)); got {length!r}")
        strength = interaction.strength
        if strength is not None and not (isinstance(strength, (int, float, np.floating)) and strength >= 0):
            raise ValueError(f"interaction {type(interaction).__name__}.strength, its largest attraction [Pa], must "
                             f"be None or a float >= 0 (valid range [0, inf)); got {strength!r}")
    kernel = interaction.kernel
    if kernel is not None and not (isinstance(kernel, tuple) and hasattr(type(kernel), "_fields")
                                   and callable(getattr(type(kernel), "at", None))
                                   and all(type(value) is float for value in kernel)):
        raise TypeError(f"interaction {type(interaction).__name__}.kernel must be None or a NamedTuple of floats "
                        f"whose class has at(gap, kernel) -> (V, p_int, k) (roughcontact.interactions); got "
                        f"{kernel!r:.80}")
    return interaction


def checked_control(body: ElasticHalfSpace, interaction: Interaction, *, mean_pressure=None, total_force=None,
                    penetration=None, tol=None, maxiter=10000, x0=None, callback=None, warn=True) -> Control:
    """The :class:`Control` of a solve of a checked problem (``body``, ``interaction``), checked: exactly one of
    ``mean_pressure``, ``total_force`` (> 0 for the hard wall; any sign with a smooth law) and ``penetration``
    (any sign); ``tol`` in (0, 1) (by default :func:`default_tolerance`; below :data:`FLOAT32_TOL_FLOOR` in
    float32 a ConvergenceWarning up front), ``maxiter`` >= 0, ``x0`` on the grid (a ContactResult for a smooth
    law; for the hard wall also a pressure field, finite and >= 0), ``callback`` callable or None, ``warn`` a
    bool."""
    given = {name: value for name, value in (("mean_pressure", mean_pressure), ("total_force", total_force),
                                             ("penetration", penetration)) if value is not None}
    if len(given) != 1:
        raise ValueError(f"give exactly one of mean_pressure, total_force, penetration; got {sorted(given) or 'none'}")
    (kind, value), = given.items()
    # the hard wall cannot pull; a law that vanishes (0 V) takes any sign, as its smooth neighbours
    value = check_positive(kind, value) if kind != "penetration" and not interaction.smooth else check_real(kind, value)
    load = None if kind == "penetration" else value / body.grid.area if kind == "total_force" else value
    tol = default_tolerance(body.dtype, interaction) if tol is None else \
        check_real("tol", tol, low=0.0, high=1.0, low_open=True, high_open=True)
    maxiter = check_integer("maxiter", maxiter, low=0)
    if body.dtype == np.float32 and tol < FLOAT32_TOL_FLOOR:
        warnings.warn(f"tol = {tol!r} is below float32's round-off floor {FLOAT32_TOL_FLOOR:.2g}: the residual may "
                      f"not get there (the solve may stall or run to maxiter = {maxiter}); use tol >= "
                      f"{FLOAT32_TOL_FLOOR:.2g} or a float64 body", ConvergenceWarning, stacklevel=4)
    if callback is not None and not callable(callback):
        raise TypeError(f"callback must be callable, got {type(callback).__name__}")
    return Control(kind, value, load, tol, maxiter, _checked_start(x0, interaction, body.grid.shape), callback,
                   check_bool("warn", warn))


def _checked_start(x0, interaction: Interaction, shape: tuple):
    """The warm start ``x0`` checked for the method that solves ``interaction``: a smooth law's takes a ContactResult
    (its gap), the hard wall's a ContactResult (its pressure for Polonsky–Keer, its gap on the gap) or an array's
    pressure [Pa] (returned as that array)."""
    if x0 is None:
        return None
    if interaction.smooth and not interaction.vanishes:
        if not isinstance(x0, ContactResult):
            raise TypeError(f"x0 of a smooth interaction must be a ContactResult (its gap starts the solve), got "
                            f"{type(x0).__name__}")
        if x0.gap.shape != shape:
            raise ValueError(f"x0 has shape {x0.gap.shape}, but the grid has shape {shape}")
        return x0
    if isinstance(x0, ContactResult):
        pressure = check_finite_array("x0", x0.pressure, nonnegative=True)
        if pressure.shape != shape:
            raise ValueError(f"x0 has shape {pressure.shape}, but the grid has shape {shape}")
        return x0
    pressure = check_finite_array("x0", x0, nonnegative=True)
    if pressure.shape != shape:
        raise ValueError(f"x0 has shape {pressure.shape}, but the grid has shape {shape}")
    return pressure
