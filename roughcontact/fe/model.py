"""The seed's finite-element fingertip (Figs. 6–7, Eq. 34): a plane-strain hyperelastic finger section pressed
onto a rigid smooth plate and slid along it with local Coulomb friction, solved with FElupe.

FElupe (GPL-3.0-or-later) is imported inside :meth:`FingertipModel._build` only; see ``roughcontact/fe/__init__``.

Model. Plane strain, bilinear quadrilaterals with the nearly-incompressible (u, p̄, J̄) formulation of constant
pressure and volume ratio per cell (``SolidBodyNearlyIncompressible``); one Ogden body per tissue on the shared
displacement field. The rigid bone's contour nodes are tied to a reference point (penalty multi-point
constraint, rotation locked); the plate is a rigid plane through a second reference point, which is fixed;
contact is node-to-plane with a penalty λ_n = ``penalty`` × μ_skin and Coulomb friction with an elastic slip γ
= ``elastic_slip`` × the node spacing at the contact (λ_t = μ f_n/γ), return mapping and consistent tangent.

Protocol (seed: "pressed ... by a normal force per unit width applied to the inner bone layer ... then moved
tangentially while keeping the normal force constant until the whole contact length is slipping"):

1. approach: the bone moves down in steps of ``approach_step`` × the half-height until the plate carries f_N;
2. press: a point load on the bone brings the normal force to f_N exactly (bone x held). The press is
   frictionless: L0 depends on f_N alone, the path of the press does not matter (a frictionless hyperelastic
   contact keeps no history), and the stick reference of each contact node is its pressed place;
3. slide: the bone's x is displacement-controlled (so the path can pass a maximum of f_T) while the point load
   keeps f_N; stopped at the first increment in which every node in contact slips (the onset of full slip).

Internally the FE problem is written in mm, N and MPa (well-scaled residuals for the Newton tolerance); inputs
and results are SI, forces per unit width in N/m.
"""
from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field

import numpy as np

from surfaces.validation import check_real

from ..io.results import ConvergenceWarning
from .analysis import contact_length
from .geometry import FingerSection, MeshResolution, SectionMesh, mesh_section
from .materials import FingerMaterials

_MM = 1e-3            # metres per millimetre (the FE problem's length unit)
_MPA = 1e6            # pascals per megapascal
_N_PER_MM = 1e3       # N/m per N/mm
#: Seed Sect. 4.3: the local Coulomb coefficient of the FE model.
SEED_FRICTION = 0.35
#: Valid normal forces per unit width (low, high] [N/m]: the FE section presses to 1000 N/m at μ up to 2.5 (the
#: default sweep: 25–400 N/m; a finger's 0.5–2 N is 53–163 N/m over its footprint's width).
NORMAL_FORCE_RANGE = (0.0, 1000.0)
#: Largest local friction coefficient accepted (μ_eff = μ0 (1 + F_el/F_N) of the default scene reaches 2.4).
MAX_FRICTION = 3.0
#: Largest bone travel per increment [m] (a fraction of the contact length, which is 4–10 mm).
MAX_TRAVEL_STEP = 1e-3
#: Most increments of one slide (max_travel / travel_step).
MAX_INCREMENTS = 10_000
#: Increments to full slip aimed at by :func:`default_travel_step`.
TRAVEL_INCREMENTS = 25
_VERBOSE = 0


class FEConvergenceError(RuntimeError):
    """The FE model's Newton solve failed where the protocol cannot go on (the press)."""


def default_travel_step(normal_force: float, friction: float) -> float:
    """Travel step [m] for about :data:`TRAVEL_INCREMENTS` increments to full slip: the bone's travel to full slip
    estimated as 1.2 mm (μ f_N / 8.75 N/m)^0.65 (a fit to the default mesh's runs, μ = 0.26–2.4, f_N = 25–400
    N/m, within a factor 1.5), clipped to [20 µm, :data:`MAX_TRAVEL_STEP`]."""
    travel = 1.2e-3 * (friction * normal_force / 8.75) ** 0.65
    return float(np.clip(travel / TRAVEL_INCREMENTS, 20e-6, MAX_TRAVEL_STEP))


class _Predictor:
    """FElupe plugin, the warm start of every substep: the unknowns move on by the change over the last
    converged substep (a linear extrapolation of the path), so Newton starts near the solution (23 % fewer
    Newton iterations on the coarse mesh at 100 N/m). Placed after the cutback plugin, whose checkpoint keeps
    the converged state a cutback goes back to."""

    def __init__(self):
        self.last = None

    def before_substep(self, context, state):
        now = [field.values.copy() for field in context.x0.fields]
        if self.last is not None:
            for field, current, previous in zip(context.x0.fields, now, self.last):
                field.values += current - previous
        self.last = now


def check_normal_force(normal_force) -> float:
    """f_N [N/m] checked against :data:`NORMAL_FORCE_RANGE`."""
    low, high = NORMAL_FORCE_RANGE
    return check_real("normal_force", normal_force, low=low, high=high, low_open=True)


@dataclass(frozen=True)
class ContactSnapshot:
    """The contact at one converged increment: nodal abscissae ``x`` [m] (deformed, sorted), normal forces
    ``normal`` and tangential forces ``tangential`` of the plate on the nodes [N/m], gaps ``gap`` [m] and the
    state ``slip`` (True where the node slides)."""

    x: np.ndarray
    normal: np.ndarray
    tangential: np.ndarray
    gap: np.ndarray
    slip: np.ndarray

    @property
    def in_contact(self) -> np.ndarray:
        return self.normal > 0

    def length(self, edge: str = "pressure") -> float:
        """Contact length L [m] (:func:`~roughcontact.fe.analysis.contact_length`)."""
        return contact_length(self.x, self.normal, self.gap, edge)


@dataclass(frozen=True)
class SlidingRun:
    """One press-and-slide run at normal force per unit width ``normal_force`` f_N [N/m].

    Per converged sliding increment (index 0: pressed, before tangential travel): ``travel`` of the bone [m],
    ``tangential_force`` f_T = Σ tangential nodal forces [N/m], ``contact_normal_force`` Σ f_n [N/m],
    ``bone_tangential_force`` the force that drives the bone (its tie's reaction) [N/m], ``length`` L (pressure
    edges) and ``length_gap`` (gap zero crossings) [m], ``slipping`` the fraction of contact nodes that slide.
    ``full_slip`` whether the last increment is the onset of full slip; ``snapshots`` the contact at every
    increment; ``points`` (the deformed mesh, [m]) at the pressed state and at the last increment; ``cells``,
    ``material`` of the mesh; ``friction`` μ; ``seconds`` the wall time, ``cpu_seconds`` the processor time of the
    run's process; ``converged`` False if a Newton solve
    failed before full slip (warned).
    """

    normal_force: float
    travel: np.ndarray
    tangential_force: np.ndarray
    contact_normal_force: np.ndarray
    bone_tangential_force: np.ndarray
    length: np.ndarray
    length_gap: np.ndarray
    slipping: np.ndarray
    full_slip: bool
    converged: bool
    friction: float
    snapshots: tuple = field(repr=False)
    pressed_points: np.ndarray = field(repr=False)
    final_points: np.ndarray = field(repr=False)
    cells: np.ndarray = field(repr=False)
    material: np.ndarray = field(repr=False)
    seconds: float = 0.0
    cpu_seconds: float = 0.0

    @property
    def initial_length(self) -> float:
        """L0: contact length before tangential loading [m]."""
        return float(self.length[0])

    @property
    def sliding_length(self) -> float:
        """Contact length at the onset of full slip [m] (nan if it was not reached)."""
        return float(self.length[-1]) if self.full_slip else float("nan")

    @property
    def relative_reduction(self) -> float:
        """1 − L_slide/L0 at the onset of full slip."""
        return 1.0 - self.sliding_length / self.initial_length


@dataclass(frozen=True)
class PressedContact:
    """Frictionless press at ``normal_force`` f_N [N/m]: the ``snapshot`` and the bone's ``indentation`` [m]."""

    normal_force: float
    snapshot: ContactSnapshot
    indentation: float

    @property
    def length(self) -> float:
        return self.snapshot.length()


@dataclass(frozen=True)
class FingertipModel:
    """The FE fingertip: ``section`` geometry, ``materials``, ``resolution`` of the mesh, Coulomb ``friction`` μ,
    contact ``penalty`` (λ_n / μ_skin, dimensionless), ``elastic_slip`` (γ / contact node spacing), ``tie``
    (bone-tie penalty / λ_n), Newton ``tolerance`` (residual norm relative to the normal force),
    ``approach_step`` (the bone's downward step while pressing / the section's half-height)."""

    section: FingerSection = field(default_factory=FingerSection)
    materials: FingerMaterials = field(default_factory=FingerMaterials)
    resolution: MeshResolution = field(default_factory=MeshResolution)
    friction: float = SEED_FRICTION
    penalty: float = 1000.0
    elastic_slip: float = 0.01
    tie: float = 100.0
    tolerance: float = 1e-6
    approach_step: float = 0.05

    def __post_init__(self):
        for name, kind in (("section", FingerSection), ("materials", FingerMaterials),
                           ("resolution", MeshResolution)):
            if not isinstance(getattr(self, name), kind):
                raise TypeError(f"{name} must be a {kind.__name__}, got {type(getattr(self, name)).__name__}")
        check_real("friction", self.friction, low=0.0, high=MAX_FRICTION, low_open=True)
        check_real("penalty", self.penalty, low=0.0, low_open=True)
        check_real("elastic_slip", self.elastic_slip, low=0.0, low_open=True)
        check_real("tie", self.tie, low=0.0, low_open=True)
        check_real("tolerance", self.tolerance, low=0.0, low_open=True)
        check_real("approach_step", self.approach_step, low=0.0, high=0.5, low_open=True)

    @property
    def mesh(self) -> SectionMesh:
        return mesh_section(self.section, self.resolution)

    def _build(self, friction: float):
        """The FElupe objects of a fresh model (all in mm, N, MPa)."""
        import felupe as fem

        mesh = self.mesh
        bone_point, plate_point = len(mesh.points), len(mesh.points) + 1
        lowest = mesh.points[:, 1].min()
        points = np.vstack([mesh.points, [[0.0, self.section.bone_offset], [0.0, lowest]]]) / _MM
        whole = fem.Mesh(points, mesh.cells, "quad")
        displacement = fem.FieldPlaneStrain(fem.RegionQuad(whole), dim=2)
        field = fem.FieldContainer([displacement])
        bodies = []
        for label, material in enumerate(self.materials.by_label()):
            cells = mesh.cells[mesh.material == label]
            if len(cells) == 0:
                continue
            part = fem.FieldContainer([fem.FieldPlaneStrain(fem.RegionQuad(fem.Mesh(points, cells, "quad")), dim=2)])
            part.link(field)
            umat = fem.Hyperelastic(fem.ogden, mu=[m / _MPA for m in material.mu], alpha=list(material.alpha))
            bodies.append(fem.SolidBodyNearlyIncompressible(umat, part, bulk=material.bulk / _MPA))
        candidates = mesh.lower_surface
        lowest_node = candidates[np.argmin(points[candidates, 1])]
        spacing = np.min(np.linalg.norm(points[candidates] - points[lowest_node], axis=1)[candidates != lowest_node])
        normal_multiplier = self.penalty * self.materials.skin.shear_modulus / _MPA
        contact = fem.ContactRigidPlane(field, candidates, plate_point, normal=[0.0, 1.0], friction=friction,
                                        multiplier=normal_multiplier,
                                        elastic_slip=self.elastic_slip * spacing if friction > 0 else None)
        tie = fem.MultiPointConstraint(field, mesh.bone, bone_point, multiplier=self.tie * normal_multiplier)
        on = np.arange(whole.npoints)
        boundaries = {"plate": fem.Boundary(displacement, mask=on == plate_point),
                      "bone_x": fem.Boundary(displacement, mask=on == bone_point, skip=(0, 1)),
                      "bone_y": fem.Boundary(displacement, mask=on == bone_point, skip=(1, 0))}
        load = fem.PointLoad(field, [bone_point])
        return dict(fem=fem, field=field, displacement=displacement, bodies=bodies, contact=contact, tie=tie,
                    boundaries=boundaries, load=load, points=points, bone_point=bone_point, plate_point=plate_point,
                    candidates=candidates)

    def _run_step(self, model, items, ramp, boundaries, record=None):
        """Solve the substeps of one step with cutback; ``record(model)`` after each; False if a solve failed
        (the model is then at the last converged substep) or if ``record`` returned True (stop)."""
        fem = model["fem"]
        from felupe.tools import EventDispatcher

        step = fem.Step(items, ramp=ramp, boundaries=boundaries)
        plugins = [fem.LinesearchPlugin(), fem.CutbackPlugin(max_cutbacks=8), _Predictor()]
        if _VERBOSE:
            plugins.append(fem.ProgressPlugin(verbose=_VERBOSE))
        dispatcher = EventDispatcher(plugins=plugins)
        states = step.generate_states(x0=model["field"], dispatcher=dispatcher, tol=self.tolerance * model["force"],
                                      maxiter=16)
        try:
            for _ in states:
                if record is not None and record(model):
                    return True
        except Exception as error:   # FElupe raises NewtonConvergenceError after its cutbacks
            model["error"] = f"{type(error).__name__}: {error}"
            return False
        return True

    @staticmethod
    def _snapshot(model) -> ContactSnapshot:
        contact, u = model["contact"], model["displacement"].values
        candidates, plate = model["candidates"], model["plate_point"]
        deformed = model["points"][candidates] + u[candidates]
        gap = deformed[:, 1] - (model["points"][plate, 1] + u[plate, 1])
        force = contact.results.force
        nodal = (np.zeros((len(candidates), 2)) if force is None
                 else -force.toarray().reshape(-1, 2)[candidates])                  # plate on body [N/mm]
        order = np.argsort(deformed[:, 0])
        slip = np.asarray(contact.results.slip, bool)
        return ContactSnapshot(x=deformed[order, 0] * _MM, normal=nodal[order, 1] * _N_PER_MM,
                               tangential=nodal[order, 0] * _N_PER_MM, gap=gap[order] * _MM, slip=slip[order])

    def _press(self, model, normal_force: float) -> bool:
        """Approach and press to f_N [N/m] (steps 1–2 of the protocol): the bone moves down in steps of
        ``approach_step`` × the half-height until the plate carries f_N, then a point load brings the force to
        f_N exactly (frictionless, so the path does not matter)."""
        model["force"] = normal_force / _N_PER_MM
        b = model["boundaries"]
        items = [*model["bodies"], model["tie"], model["contact"]]
        pulp = self.section.half_height - self.section.bone_half_height + self.section.bone_offset
        depth = np.arange(0.0, 0.9 * pulp, self.approach_step * self.section.half_height) / _MM
        carried = []

        def record(model) -> bool:
            carried.append(self._snapshot(model).normal.sum())
            return carried[-1] >= normal_force

        if not self._run_step(model, items, {b["bone_y"]: -depth}, b, record) or carried[-1] < normal_force:
            model.setdefault("error", f"the plate carries {carried[-1]:.4g} N/m at 90 % of the pulp's depth")
            return False
        ramp = np.outer(np.linspace(carried[-1], normal_force, 3) / _N_PER_MM, [0.0, -1.0])
        return self._run_step(model, [*items, model["load"]], {model["load"]: ramp},
                              {"plate": b["plate"], "bone_x": b["bone_x"]})

    def press(self, normal_force: float) -> PressedContact:
        """Frictionless press to f_N [N/m] (the Hertz check): the contact and the bone's indentation."""
        normal_force = check_normal_force(normal_force)
        model = self._build(friction=0.0)
        if not self._press(model, normal_force):
            raise FEConvergenceError(f"normal_force = {normal_force:g} N/m: the press did not converge "
                                     f"({model.get('error')})")
        indentation = -model["displacement"].values[model["bone_point"], 1] * _MM
        return PressedContact(normal_force=normal_force, snapshot=self._snapshot(model), indentation=indentation)

    def slide(self, normal_force: float, travel_step: float | None = None, max_travel: float = 30e-3
              ) -> SlidingRun:
        """Press to f_N [N/m], then move the bone by ``travel_step`` [m] per increment (default:
        :func:`default_travel_step`) at constant f_N until every contact node slides (or ``max_travel`` [m]:
        then ``full_slip`` is False, warned). :class:`FEConvergenceError` if the press fails."""
        normal_force = check_normal_force(normal_force)
        max_travel = check_real("max_travel", max_travel, low=0.0, high=0.1, low_open=True)
        if travel_step is None:
            travel_step = default_travel_step(normal_force, self.friction)
        check_real("travel_step", travel_step, low=max_travel / MAX_INCREMENTS, high=MAX_TRAVEL_STEP)
        start, cpu = time.perf_counter(), time.process_time()
        model = self._build(friction=self.friction)
        model["contact"].friction = 0.0          # a frictionless press: L0 depends on f_N alone
        if not self._press(model, normal_force):
            raise FEConvergenceError(f"normal_force = {normal_force:g} N/m: the press did not converge "
                                     f"({model.get('error')})")
        model["contact"].friction = self.friction  # the stick reference of every contact node: its pressed place
        pressed_points = (model["points"] + model["displacement"].values) * _MM
        snapshots, travel, bone_force = [self._snapshot(model)], [0.0], [0.0]

        def record(model) -> bool:
            if model["displacement"].values[model["bone_point"], 0] * _MM == travel[-1]:
                return False                     # the ramp's leading zero (lets the cutback halve increment 1)
            snapshot = self._snapshot(model)
            snapshots.append(snapshot)
            u = model["displacement"].values
            travel.append(u[model["bone_point"], 0] * _MM)
            tie = model["tie"].assemble.vector(model["field"]).toarray().reshape(-1, 2)
            bone_force.append(tie[model["bone_point"], 0] * _N_PER_MM)
            contact = snapshot.in_contact
            return bool(contact.any() and snapshot.slip[contact].all())

        b = model["boundaries"]
        items = [*model["bodies"], model["tie"], model["contact"], model["load"]]
        steps = int(np.ceil(max_travel / travel_step))
        ramp = {b["bone_x"]: np.linspace(0.0, steps * travel_step / _MM, steps + 1),
                model["load"]: np.tile([0.0, -normal_force / _N_PER_MM], (steps + 1, 1))}
        converged = self._run_step(model, items, ramp, {"plate": b["plate"], "bone_x": b["bone_x"]}, record)
        last = snapshots[-1]
        full_slip = bool(last.in_contact.any() and last.slip[last.in_contact].all()) and len(snapshots) > 1
        if not full_slip:
            warnings.warn(f"f_N = {normal_force} N/m: no full slip after {travel[-1] * 1e3:.3g} mm of travel "
                          f"({'Newton failed: ' + model.get('error', '') if not converged else 'travel limit'})",
                          ConvergenceWarning, stacklevel=2)
        mesh = self.mesh
        return SlidingRun(
            normal_force=normal_force, travel=np.array(travel),
            tangential_force=np.array([-s.tangential.sum() for s in snapshots]),
            contact_normal_force=np.array([s.normal.sum() for s in snapshots]),
            bone_tangential_force=np.array(bone_force),
            length=np.array([s.length() for s in snapshots]),
            length_gap=np.array([s.length("gap") for s in snapshots]),
            slipping=np.array([s.slip[s.in_contact].mean() if s.in_contact.any() else 0.0 for s in snapshots]),
            full_slip=full_slip, converged=converged, friction=self.friction, snapshots=tuple(snapshots),
            pressed_points=pressed_points[:len(mesh.points)],
            final_points=((model["points"] + model["displacement"].values) * _MM)[:len(mesh.points)],
            cells=mesh.cells, material=mesh.material, seconds=time.perf_counter() - start,
            cpu_seconds=time.process_time() - cpu)
