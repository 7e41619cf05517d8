"""Scale coupling: the micro-roughness reduced to an interface law that a ridge-scale solve uses.

The fully resolved study (:mod:`roughcontact.study`) puts ridges and micro-roughness in one grid. The coupled
path separates them (``docs/findings/equivalent_gap.md``, "Scale coupling"):

1. **Micro scale** (:func:`interface_law`). A periodic patch of the micro-roughness alone on the same skin is
   brought to a sequence of mean separations ū (from far to near, each solve started from the last, with the
   electrostatic attraction at the voltage U; displacement control). Each gives the mean traction p(ū) [Pa]
   that the interface transmits (contact minus attraction, positive compressive), its Eq. 25 gap e(ū) [m], its
   field-equivalent gap f(ū) [m] (the uniform gap whose Eq. 21 attraction is the patch's mean attraction in the
   scene's field model), its real contact fraction φ(ū), the fraction a_ℓ(ū) of its real contact closed with
   a disc of diameter ℓ (the study's A_R definition, :func:`roughcontact.study.ridge_area_fraction`) and its
   weighted mean-square gap slope.
2. **Ridge scale** (:func:`coupled_point`). The ridges alone, on a coarser grid, are pressed at the nominal
   pressure with :class:`InterfaceLaw` (traction p(ū), ū the ridge-scale gap) acting between them and the
   screen.
3. **Averages.** d_eq = Eq. 25 of the field e(ū(x)) (exact: Eq. 25 of the pixel-wise equivalent gaps is Eq. 25
   of the underlying field), the field-equivalent gap likewise from f(ū(x)), the mean gap that of ū (a periodic
   micro patch's mean gap is its separation), the real contact fraction the mean of φ(ū(x)), A_R/A0 the mean of
   a_ℓ(ū(x)).

:func:`coupled_chain` runs one realisation at one voltage over the scene's loads (one law serves them all).
Scale separation is the assumption: a ridge-scale pixel behaves like a micro patch at the same mean
separation; the micro-roughness's long-wavelength coupling to the ridge curvature is lost, and so is the lateral
field between ridge-scale pixels (the layered field acts within each micro patch only).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from surfaces import Grid

from ..interactions import ElectrostaticInteraction, Interaction
from ..solvers import solve_contact
from .apparent import apparent_scale, ring_count
from .patch import gap_slope, patch_body, ridge_area_fraction, ridge_equivalent_gap, ridge_heights, roughness_heights
from .plan import as_plan
from .records import PatchRecord, field_ratio, unit_attraction

#: Pixels per ridge period of the ridge-scale grid of :func:`coupled_chain`.
RIDGE_PIXELS_PER_PERIOD = 64
#: Mean separations tabulated by :func:`interface_law` in :func:`coupled_chain`.
LAW_NODES = 23


@dataclass(frozen=True)
class InterfaceLaw(Interaction):
    """Tabulated interface law of a rough micro patch at mean separations ū [m] (``separations``, strictly
    increasing): traction p(ū) [Pa] (positive compressive), Eq. 25 gap e(ū) [m], real contact fraction φ(ū),
    weighted mean-square gap slope s²(ū) (weights (ε_a c + g)⁻², as the study's gap slope), field-equivalent
    gap f(ū) [m] (Eq. 21 inverted at the patch's mean attraction in its field model) and, for each
    closing diameter of ``coarse_graining`` [m], the closed contact fraction a_ℓ(ū) (``ridge_area_fractions``,
    one tuple per diameter); ``converged``, whether every node's micro-patch solve converged.

    Between the nodes monotone cubic (PCHIP) interpolation; below the first node the cubic extrapolates; beyond
    the last node the traction follows the flat-plate attraction −σ_el(ū) of ``stack`` at ``voltage`` scaled to
    be continuous (0 at 0 V), e(ū) and f(ū) = ū shifted to be continuous, φ = a_ℓ = 0, s² that of the last node.
    Energy V(ū) = ∫_ū^∞ p dū'.
    """

    separations: tuple
    tractions: tuple
    equivalent_gaps: tuple
    contact_fractions: tuple
    slopes: tuple
    field_equivalent_gaps: tuple
    stack: object
    voltage: float
    length: float
    coarse_graining: tuple = ()
    ridge_area_fractions: tuple = ()
    converged: bool = True
    _splines: dict = field(default=None, repr=False, compare=False)

    def __post_init__(self):
        from scipy.interpolate import PchipInterpolator
        x = np.asarray(self.separations, float)
        if x.ndim != 1 or x.size < 3 or (np.diff(x) <= 0).any():
            raise ValueError(f"separations must be >= 3 strictly increasing values, got {self.separations!r}")
        columns = {"tractions": self.tractions, "equivalent_gaps": self.equivalent_gaps,
                   "contact_fractions": self.contact_fractions, "slopes": self.slopes,
                   "field_equivalent_gaps": self.field_equivalent_gaps,
                   **{f"ridge_area_fractions[{k}]": column for k, column in enumerate(self.ridge_area_fractions)}}
        for name, column in columns.items():
            if np.shape(column) != x.shape:
                raise ValueError(f"{name} has {np.shape(column)} values; it needs one per separation ({x.size})")
        if len(self.ridge_area_fractions) != len(self.coarse_graining):
            raise ValueError(f"ridge_area_fractions has {len(self.ridge_area_fractions)} columns; it needs one per "
                             f"coarse_graining length ({len(self.coarse_graining)})")
        traction = PchipInterpolator(x, np.asarray(self.tractions, float))
        object.__setattr__(self, "_splines", {
            "traction": traction, "stiffness": traction.derivative(), "antiderivative": traction.antiderivative(),
            **{name: PchipInterpolator(x, np.asarray(column, float)) for name, column in columns.items()
               if name != "tractions"}})

    @property
    def _tail_scale(self) -> float:
        """Factor on −σ_el beyond the table that makes the traction continuous there (0 at 0 V)."""
        sigma = float(self.stack.attraction(self.separations[-1], self.voltage))
        return -self.tractions[-1] / sigma if sigma > 0 else 0.0

    def _inside(self, name, gap):
        """``(spline of column name at gap clipped to the table, mask of gaps beyond the table)``."""
        gap = np.asarray(gap, dtype=float)
        return self._splines[name](np.minimum(gap, self.separations[-1])), gap > self.separations[-1]

    def traction(self, gap) -> np.ndarray:
        inside, far = self._inside("traction", gap)
        return np.where(far, -self._tail_scale * self.stack.attraction(gap, self.voltage), inside)

    def stiffness(self, gap) -> np.ndarray:
        inside, far = self._inside("stiffness", gap)
        return np.where(far, -self._tail_scale * self.stack.attraction_derivative(gap, self.voltage), inside)

    def energy(self, gap) -> np.ndarray:
        gap = np.asarray(gap, dtype=float)
        last = self.separations[-1]
        tail = self._tail_scale * self.stack.energy(np.maximum(gap, last), self.voltage)   # ∫_ū^∞ of the tail
        antiderivative = self._splines["antiderivative"]
        inside = antiderivative(last) - antiderivative(np.minimum(gap, last))
        return np.where(gap > last, tail, inside + self._tail_scale * float(self.stack.energy(last, self.voltage)))

    def _gap_column(self, name, gap) -> np.ndarray:
        """The gap column ``name`` [m] at mean separation ``gap``: ū shifted to be continuous beyond the table,
        clipped at 0."""
        inside, far = self._inside(name, gap)
        return np.maximum(np.where(far, np.asarray(gap) - self.separations[-1] + getattr(self, name)[-1],
                                   inside), 0.0)

    def equivalent_gap(self, gap) -> np.ndarray:
        """e(ū) [m]: the Eq. 25 gap of the micro patch at mean separation ū."""
        return self._gap_column("equivalent_gaps", gap)

    def field_equivalent_gap(self, gap) -> np.ndarray:
        """f(ū) [m]: the micro patch's field-equivalent gap at mean separation ū (clipped at 0, where the mean
        attraction would exceed full contact's)."""
        return self._gap_column("field_equivalent_gaps", gap)

    def contact_fraction(self, gap) -> np.ndarray:
        """φ(ū): the real contact fraction of the micro patch at mean separation ū."""
        inside, far = self._inside("contact_fractions", gap)
        return np.clip(np.where(far, 0.0, inside), 0.0, 1.0)

    def ridge_area_fraction(self, gap, index: int = 0) -> np.ndarray:
        """a_ℓ(ū): the micro patch's real contact closed with a disc of diameter ``coarse_graining[index]``."""
        inside, far = self._inside(f"ridge_area_fractions[{index}]", gap)
        return np.clip(np.where(far, 0.0, inside), 0.0, 1.0)

    def slope_squared(self, gap) -> np.ndarray:
        """s²(ū): the micro patch's mean-square gap slope weighted by (ε_a c + g)⁻²."""
        return np.maximum(self._inside("slopes", gap)[0], 0.0)


def interface_law(heights, body, stack, voltage: float, nodes: int = LAW_NODES, tol: float = 1e-7,
                  coarse_graining=(), field: str = "layered") -> InterfaceLaw:
    """The :class:`InterfaceLaw` of the periodic micro patch ``heights`` [m] on ``body`` at ``voltage`` [V] with
    the attraction's ``field`` model ("layered" or "parallel_plate"): ``nodes`` mean separations from 2 % of the
    rms height to the highest summit plus two rms heights, solved from far to near (displacement control, each
    from the last); closed contact fractions for each diameter of ``coarse_graining`` [m]."""
    if not isinstance(nodes, (int, np.integer)) or nodes < 3:
        raise ValueError(f"nodes = {nodes!r}; it must be an integer >= 3")
    heights = np.asarray(heights, float)
    mean, top, rms = heights.mean(), heights.max(), heights.std()
    if rms == 0:
        raise ValueError("heights are flat; an interface law needs a rough micro patch")
    separations = np.geomspace(0.02 * rms, top - mean + 2 * rms, nodes)
    law = ElectrostaticInteraction(stack, voltage=voltage, field=field) if voltage > 0 else None
    spacing, offset = body.grid.spacing, stack.eps_a * stack.dielectric_offset
    rows, previous, converged = [], None, True
    for separation in separations[::-1]:
        result = solve_contact(heights, body, penetration=top - mean - separation, interaction=law, tol=tol,
                               x0=previous, warn=False)
        gap, contact = np.asarray(result.gap), np.asarray(result.contact)
        rows.append((result.mean_pressure, stack.equivalent_gap(gap), result.contact_fraction,
                     gap_slope(gap, (offset + gap) ** -2.0, spacing) ** 2,
                     stack.gap_for_attraction(unit_attraction(stack, field, result, voltage), 1.0),
                     *(ridge_area_fraction(contact, spacing[0], length) for length in coarse_graining)))
        previous, converged = result, converged and bool(result.converged)
    columns = [tuple(float(v) for v in column[::-1]) for column in zip(*rows)]
    return InterfaceLaw(separations=tuple(float(s) for s in separations), tractions=columns[0],
                        equivalent_gaps=columns[1], contact_fractions=columns[2], slopes=columns[3],
                        field_equivalent_gaps=columns[4], stack=stack, voltage=float(voltage), length=float(rms),
                        coarse_graining=tuple(float(v) for v in coarse_graining),
                        ridge_area_fractions=tuple(columns[5:]), converged=converged)


@dataclass(frozen=True)
class CoupledPoint:
    """The coupled path at one nominal ``pressure`` [Pa] and ``voltage`` [V]: d_eq [m] (Eq. 25), the
    field-equivalent gap [m], the mean gap [m], the real contact fraction, A_R/A0 for each of the law's closing
    diameters, the weighted rms gap slope (ridge and micro scale in quadrature), and the ridge-scale solve's
    convergence, iterations and concave (unstable) steps."""
    pressure: float
    voltage: float
    equivalent_gap: float
    field_equivalent_gap: float
    mean_gap: float
    contact_fraction: float
    ridge_area_fractions: tuple
    gap_slope: float
    converged: bool
    iterations: int
    unstable_steps: int


def coupled_point(ridges, body, law: InterfaceLaw, pressure: float, tol: float = 1e-7, x0=None) -> tuple:
    """Solve the ridge heights ``ridges`` [m] on ``body`` at the nominal ``pressure`` [Pa] with ``law`` acting;
    returns ``(CoupledPoint, ContactResult)`` (the result to warm-start the next solve)."""
    result = solve_contact(ridges, body, mean_pressure=pressure, interaction=law, tol=tol, x0=x0, warn=False)
    separation = np.asarray(result.gap)
    gaps = law.equivalent_gap(separation)
    weights = (law.stack.eps_a * law.stack.dielectric_offset + gaps) ** -2.0   # the micro patch's mean weight
    slope = np.sqrt(gap_slope(separation, weights, body.grid.spacing) ** 2
                    + np.sum(weights * law.slope_squared(separation)) / np.sum(weights))
    point = CoupledPoint(
        pressure=float(pressure), voltage=law.voltage, equivalent_gap=law.stack.equivalent_gap(gaps),
        field_equivalent_gap=law.stack.equivalent_gap(law.field_equivalent_gap(separation)),
        mean_gap=float(separation.mean()), contact_fraction=float(np.mean(law.contact_fraction(separation))),
        ridge_area_fractions=tuple(float(np.mean(law.ridge_area_fraction(separation, k)))
                                   for k in range(len(law.coarse_graining))),
        gap_slope=float(slope),
        converged=bool(result.converged), iterations=int(result.iterations),
        unstable_steps=int(result.unstable_steps))
    return point, result


def ridge_grid(plan):
    """The ridge-scale grid of :func:`coupled_chain`: the patch of ``plan`` (a StudyPlan or a Scene) at
    :data:`RIDGE_PIXELS_PER_PERIOD` pixels per ridge period, or the patch grid where that is coarser."""
    plan = as_plan(plan)
    pixels = min(plan.grid.shape[0], RIDGE_PIXELS_PER_PERIOD * plan.scene.preset.periods)
    return Grid((pixels, pixels), plan.grid.lengths, periodic=True)


def coupled_chain(plan, realisation: int, voltage_index: int, threads: int | None = None,
                  apparent: tuple | None = None) -> tuple:
    """The coupled path's task of the study (the counterpart of :func:`roughcontact.study.solve_chain`): the
    micro-roughness of ``realisation`` reduced to one :class:`InterfaceLaw` at voltage
    ``loads.voltages[voltage_index]`` (:data:`LAW_NODES` nodes on the patch grid, the preset's tolerance, the
    scene's coarse-graining lengths), then :func:`ridge_chain` with it. ``plan``: the study's
    :class:`~roughcontact.study.plan.StudyPlan`, or a Scene (planned here). Returns one
    :class:`~roughcontact.study.PatchRecord` per load; the law's solves and seconds are counted in the first
    load's record. ``threads`` FFT threads (default: ``roughcontact.fft.default_threads``); ``apparent``, the
    scene's :func:`~roughcontact.study.apparent_scale` (computed when not given)."""
    plan = as_plan(plan)
    scene = plan.scene
    if not scene.roughness.enabled:
        raise ValueError("presets.*.scales = 'coupled' needs micro-roughness (roughness.enabled = true): without "
                         "it there is no interface law; use scales = 'resolved'")
    if scene.roughness.topography:
        raise ValueError("presets.*.scales = 'coupled' reduces synthetic micro-roughness to an interface law; a "
                         "measured topography (roughness.topography) is solved with scales = 'resolved'")
    if scene.ridges.enabled and scene.ridges.pore_density > 0:
        raise ValueError(f"ridges.pore_density = {scene.ridges.pore_density!r} 1/m² with presets.*.scales = "
                         "'coupled': the coupled path has no pores; set pore_density = 0 or scales = 'resolved'")
    start = time.perf_counter()
    law = interface_law(roughness_heights(scene, realisation, plan.grid, plan.short_cutoff), plan.body(threads),
                        scene.screen.stack(), plan.voltages[voltage_index], tol=scene.preset.tolerance,
                        coarse_graining=plan.closing_lengths, field=scene.screen.field)
    return ridge_chain(plan, law, threads, spent=(len(law.separations), time.perf_counter() - start),
                       apparent=apparent)


def ridge_chain(plan, law: InterfaceLaw, threads: int | None = None, grid=None, spent=(0, 0.0),
                apparent: tuple | None = None) -> tuple:
    """The ridges of ``plan``'s scene (a StudyPlan or a Scene) on ``grid`` (default :func:`ridge_grid`) pressed
    with ``law`` (its voltage) under every load in order, each ring's solve (:func:`coupled_point`) warm-started
    from its result at the previous load. Returns one :class:`~roughcontact.study.PatchRecord` per load,
    averaged over the rings as the resolved chain does; ``spent`` (solves, seconds) taken before, counted in the
    first record."""
    plan = as_plan(plan)
    scene = plan.scene
    grid = ridge_grid(plan) if grid is None else grid
    stack = law.stack
    ridges, body = ridge_heights(scene, grid), patch_body(scene, grid, threads=threads)
    previous = [None] * ring_count(scene)                       # each ring's result at the previous load
    records, (solves, seconds) = [], spent
    for _, pressures in apparent_scale(scene) if apparent is None else apparent:
        start, points = time.perf_counter(), []
        for k, pressure in enumerate(pressures):
            point, previous[k] = coupled_point(ridges, body, law, pressure, tol=scene.preset.tolerance,
                                               x0=previous[k])
            points.append(point)
        d_eq = stack.equivalent_gap(np.array([point.equivalent_gap for point in points]))   # rings of equal area
        d_field = stack.equivalent_gap(np.array([point.field_equivalent_gap for point in points]))
        fractions = tuple(float(np.mean(column)) for column in zip(*(p.ridge_area_fractions for p in points)))
        records.append(PatchRecord(
            equivalent_gap=d_eq, field_equivalent_gap=max(d_field, 0.0),       # (records.patch_record: ≥ 0)
            ridge_equivalent_gap=ridge_equivalent_gap(stack, d_field, fractions[0]),
            mean_gap=float(np.mean([p.mean_gap for p in points])),
            contact_fraction=float(np.mean([p.contact_fraction for p in points])), ridge_area_fractions=fractions,
            electrostatic_attraction=float(stack.attraction(d_field, law.voltage)),
            pixel_law_attraction=float(stack.attraction(d_eq, law.voltage)),
            field_ratio=field_ratio(stack, d_field, d_eq),
            gap_slope=float(np.mean([p.gap_slope for p in points])),
            converged=law.converged and all(p.converged for p in points),
            iterations=sum(p.iterations for p in points), unstable_steps=sum(p.unstable_steps for p in points),
            solves=solves + len(points),
            seconds=seconds + time.perf_counter() - start))
        solves, seconds = 0, 0.0
    return tuple(records)
