"""Reproduction of the seed paper's figures 3, 4, 5, 9, 10, 11 and of the numbers it quotes (checkpoint table).

``reproduce(output_dir)`` writes one PNG and one CSV per figure plus ``checkpoints.csv`` and returns the
:class:`CheckpointTable`; every file carries its provenance (:mod:`roughcontact.io.provenance`). Every "computed"
value in the table is computed here from the model; the "quoted" values are the numbers printed in Heß &
Forsbach (2020). Figures use matplotlib's object API with the Agg
canvas (no pyplot state, no rcParams edits); matplotlib is imported only when a figure is drawn.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .electrostatics import EPSILON_0, DielectricStack
from .macro import PowerLawContact, SavkoorBriggsPeeling, SlidingFrictionModel
from .io.provenance import Provenance, output_directory, save_figure, write_columns, write_csv

#: The seed's voltage for Figs. 3–5 [V] and the two equivalent gaps it compares [m].
VOLTAGE = 200.0
GAP_REALISTIC = 1e-6
#: Effective Hertz radius of the finger used for the Hertz/JKR comparison and peeling (Figs. 3, 5) [m].
RADIUS = 1e-2
#: Normal force at which the Hertz contact is fitted to the apparent-area law (E* = 47.4 kPa) [N].
FIT_FORCE = 1.0
#: The work of adhesion at which the seed evaluates its apparent-area numbers and Fig. 5 [J/m²].
W_QUOTED = 0.132
#: Largest normal force of Figs. 3–4 and of the seed's friction range (Table 1, Figs. 9–11) [N].
AREA_MAX_FORCE, FRICTION_MAX_FORCE = 2.0, 2.3
#: Smallest normal force of Fig. 11 [N] (μ → ∞ as F_N → 0 under voltage).
MU_MIN_FORCE = 0.05
#: Voltages of Figs. 9–11 [V].
FRICTION_VOLTAGES = (0.0, 50.0, 100.0, 150.0, 200.0)
MM2 = 1e-6   # 1 mm² in m²
#: Points per curve: along the area of Figs. 3–4, the tangential force of Fig. 5 and the normal force of Figs. 9–11.
AREA_POINTS, PEELING_POINTS, FORCE_POINTS = 400, 300, 231


# -- checkpoint table --------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Checkpoint:
    """One quoted number of the seed next to the model's value.

    ``kind``: "equal" (|computed/quoted − 1| <= ``tolerance``), "at least" (computed >= quoted) or "evidence"
    (a deliberately wrong variant, shown to identify which parameters the paper used; expected to miss).
    ``tolerance`` is relative and reflects the printed digits; ``reason`` explains any larger difference.
    """

    quantity: str
    quoted: float
    computed: float
    unit: str
    tolerance: float
    reason: str = ""
    kind: str = "equal"
    explained: bool = False

    @property
    def relative_difference(self) -> float:
        return self.computed / self.quoted - 1

    @property
    def agrees(self) -> bool:
        if self.kind == "at least":
            return self.computed >= self.quoted
        return abs(self.relative_difference) <= self.tolerance


@dataclass(frozen=True)
class CheckpointTable:
    """The checkpoint rows; ``str()`` / :meth:`to_markdown` render them, :meth:`to_csv` writes them."""

    rows: tuple

    def row(self, quantity: str) -> Checkpoint:
        for row in self.rows:
            if row.quantity == quantity:
                return row
        raise KeyError(quantity)

    def to_markdown(self) -> str:
        lines = ["| quantity | quoted | computed | unit | rel. difference | agrees | reason for a difference |",
                 "|---|---|---|---|---|---|---|"]
        for r in self.rows:
            quoted = f"≥ {r.quoted:.4g}" if r.kind == "at least" else f"{r.quoted:.4g}"
            agrees = ("evidence" if r.kind == "evidence" else "yes" if r.agrees
                      else "no, explained" if r.explained else "no")
            lines.append(f"| {r.quantity} | {quoted} | {r.computed:.5g} | {r.unit} | "
                         f"{100 * r.relative_difference:+.2f} % | {agrees} | {r.reason} |")
        return "\n".join(lines)

    __str__ = to_markdown

    def to_csv(self, path, provenance: Provenance) -> Path:
        return write_csv(path, ({"quantity": r.quantity, "quoted": r.quoted, "computed": repr(r.computed),
                                 "unit": r.unit, "relative_difference": r.relative_difference,
                                 "tolerance": r.tolerance, "kind": r.kind, "agrees": r.agrees,
                                 "reason": r.reason} for r in self.rows), provenance)


def hertz_modulus_matching(law: PowerLawContact, radius: float, normal_force: float) -> float:
    """E* [Pa] of the Hertz contact with radius R* whose area equals ``law``'s at ``normal_force`` (Eq. 12):
    π (3R*F/(4E*))^(2/3) = α F^m  ⇒  E* = 3R*F / (4 (α F^m/π)^(3/2))."""
    area = float(law.nonadhesive_area(normal_force))
    return 3 * radius * normal_force / (4 * (area / np.pi) ** 1.5)


def _area_change(law, normal_force, w):
    return float(law.area(normal_force, w) / law.area(normal_force, 0.0) - 1)


def _force_where_ratio_reaches(model, ratio, voltage, forces):
    mu_high = model.friction_coefficient(forces, voltage)
    mu_low = model.friction_coefficient(forces, 0.0)
    excess = mu_high / mu_low - ratio
    crossing = np.nonzero(np.diff(np.sign(excess)))[0]
    i = crossing[0]
    return float(forces[i] - excess[i] * (forces[i + 1] - forces[i]) / (excess[i + 1] - excess[i]))


def checkpoint_table() -> CheckpointTable:
    """Compute every number the seed quotes for its macroscopic model and compare (see docs/validation/paper_checkpoints.md)."""
    stack = DielectricStack()
    w_gap = float(stack.work_of_adhesion(GAP_REALISTIC, VOLTAGE))
    w_contact = float(stack.work_of_adhesion(0.0, VOLTAGE))
    apparent, ridge, ridge_t1 = (PowerLawContact.dzidek_apparent(), PowerLawContact.dzidek_ridge(),
                                 PowerLawContact.table1_ridge())
    model = SlidingFrictionModel.paper_table1()
    truncated = "printed truncated, not rounded (one unit of the last digit)"

    def reduction(force, voltage):
        return 100 * float(model.state(force, voltage).area_reduction)

    def mu(force, voltage):
        return float(model.friction_coefficient(force, voltage))

    rows = [
        Checkpoint("w at 200 V, 1 µm gap (Eq. 22)", 0.132, w_gap, "J/m²", 0.0005 / 0.132),
        Checkpoint("w at 200 V, no gap (Eq. 22)", 0.532, w_contact, "J/m²", 0.0005 / 0.532,
                   f"erratum (d): Table-1 layers give {w_contact:.4f}; 0.532 needs d_sc/ε_sc + d_i/ε_i = "
                   f"{1e6 * EPSILON_0 * VOLTAGE ** 2 / (2 * 0.532):.5f} µm instead of "
                   f"{1e6 * stack.dielectric_offset:.5f} µm. Fig. 4's 11.7 mN and 23.8 % reproduce only with "
                   f"{w_contact:.3f}, so 0.532 is a typo for 0.521", explained=True),
        Checkpoint("E* of the Hertz fit to Eq. 27 at 1 N, R* = 1 cm", 47.4,
                   hertz_modulus_matching(apparent, RADIUS, FIT_FORCE) / 1e3, "kPa", 0.05 / 47.4),
        Checkpoint("apparent-area pull-off force at w = 0.132 (Eq. 27)", 6.74,
                   -1e3 * float(apparent.pull_off(W_QUOTED).force), "mN", 0.01 / 6.74, truncated),
        Checkpoint("apparent-area zero-load area at w = 0.132", 24.14,
                   float(apparent.zero_load_area(W_QUOTED)) / MM2, "mm²", 0.01 / 24.14, truncated),
        Checkpoint("apparent-area change at 0.5 N, w = 0.132", 9.0, 100 * _area_change(apparent, 0.5, W_QUOTED),
                   "%", 0.5 / 9.0),
        Checkpoint("ridge pull-off, 1 µm gap (Eq. 28, w = 0.1322)", 2.3, -1e3 * float(ridge.pull_off(w_gap).force),
                   "mN", 0.05 / 2.3),
        Checkpoint("ridge pull-off, no gap (Eq. 28, w = 0.5212)", 11.7,
                   -1e3 * float(ridge.pull_off(w_contact).force), "mN", 0.05 / 11.7),
        Checkpoint("ridge-area change at 0.5 N, 1 µm gap (Eq. 28)", 11.2, 100 * _area_change(ridge, 0.5, w_gap),
                   "%", 0.1 / 11.2, truncated),
        Checkpoint("ridge-area change at 0.5 N, no gap (Eq. 28)", 23.8, 100 * _area_change(ridge, 0.5, w_contact),
                   "%", 0.1 / 23.8, truncated),
        Checkpoint("[evidence] ridge pull-off, no gap, with w = 0.532", 11.7,
                   -1e3 * float(ridge.pull_off(0.532).force), "mN", 0.05 / 11.7,
                   "the printed w = 0.532 does not reproduce 11.7 mN", kind="evidence"),
        Checkpoint("[evidence] ridge pull-off, 1 µm gap, Table-1 ridge law", 2.3,
                   -1e3 * float(ridge_t1.pull_off(w_gap).force), "mN", 0.05 / 2.3,
                   "Table-1 scaling does not reproduce Fig. 4: Fig. 4 uses Eq. 28", kind="evidence"),
        Checkpoint("Table 1: air gap at 0.5 N (Eq. 46)", 2.85, 1e6 * float(model.gap(0.5, 0.0)), "µm", 0.005 / 2.85),
        Checkpoint("Table 1: air gap at 2 N (Eq. 46)", 2.1, 1e6 * float(model.gap(2.0, 0.0)), "µm", 0.05 / 2.1),
        Checkpoint("Table 1: ridge-area reduction at 1 N, 0 V", 5.0, reduction(1.0, 0.0), "%", 0.5 / 5.0,
                   f"'approximately': at 0 V the reduction is c₂μ0²F^(2−2m)/α² = {reduction(1.0, 0.0):.2f} % exactly; "
                   f"5 % at 1 N with 12 % at 2 N would need a ratio 2.4 where the law gives "
                   f"2^(2−2m) = {2 ** (2 - 2 * model.contact.m):.2f}", explained=True),
        Checkpoint("Table 1: ridge-area reduction at 1 N, 100 V", 10.0, reduction(1.0, 100.0), "%", 0.5 / 10.0,
                   f"'approximately', read off Fig. 9A; {reduction(1.0, 100.0) - 10:.1f} percentage points more "
                   "(not explained)"),
        Checkpoint("Table 1: ridge-area reduction at 2 N, 0 V", 12.0, reduction(2.0, 0.0), "%", 0.5 / 12.0),
        Checkpoint("Table 1: ridge-area reduction at 2 N, 100 V", 19.0, reduction(2.0, 100.0), "%", 0.5 / 19.0,
                   f"'approximately', read off Fig. 9A; {reduction(2.0, 100.0) - 19:.1f} percentage points more "
                   "(not explained)"),
        Checkpoint("Table 1: μ(1 N)/μ(2.3 N) at 200 V ('constant above 1 N')", 1.0, mu(1.0, 200.0) / mu(2.3, 200.0),
                   "-", 0.15, f"qualitative statement, 'nearly constant' taken as within 15 %; μ(0.5 N)/μ(2.3 N) = "
                   f"{mu(0.5, 200.0) / mu(2.3, 200.0):.2f} for comparison; at 0 V μ is exactly constant"),
        Checkpoint("Table 1: μ(200 V)/μ(0 V) at 1 N ('more than doubled')", 2.0, mu(1.0, 200.0) / mu(1.0, 0.0), "-",
                   0.0, kind="at least"),
        Checkpoint("Table 1: μ(200 V)/μ(0 V) at 2.3 N", 2.0, mu(2.3, 200.0) / mu(2.3, 0.0), "-", 0.0,
                   "the paper's 'more than doubled' holds for F_N <= {:.2f} N only (not explained)".format(
                       _force_where_ratio_reaches(model, 2.0, 200.0, np.linspace(1.0, FRICTION_MAX_FORCE, 131))),
                   kind="at least"),
    ]
    return CheckpointTable(rows=tuple(rows))


# -- figures -----------------------------------------------------------------------------------------------
def _new_figure(ncols=1, width=5.0):
    from matplotlib.figure import Figure
    fig = Figure(figsize=(width * ncols, 4.0), layout="constrained")
    return fig, fig.subplots(1, ncols, squeeze=False)[0]


def _write(fig, output_dir, name, header, columns, provenance):
    """``<name>.png`` of ``fig`` and ``<name>.csv`` of ``columns`` in ``output_dir``, both with ``provenance``."""
    output_dir = Path(output_dir)
    return (save_figure(fig, output_dir / f"{name}.png", provenance),
            write_columns(output_dir / f"{name}.csv", header, columns, provenance))


def plot_adhesive_area(ax, law, works, labels, max_area, n_points=AREA_POINTS, force_scale=1.0):
    """Draw A(F_N) [mm²] of ``law`` (Eq. 9) for each w on ``ax``, both branches, parametrised by the area
    0 <= A <= ``max_area`` [m²]; forces are multiplied by ``force_scale`` (1e3 for mN). Returns the curves."""
    curves = []
    area = np.linspace(0.0, max_area, n_points)
    for w, label in zip(works, labels):
        force = law.normal_force(area, w)
        ax.plot(force * force_scale, area / MM2, label=label)
        curves.append((w, force, area))
    ax.set_xlabel("normal force F_N [mN]" if force_scale == 1e3 else "normal force F_N [N]")
    ax.set_ylabel("contact area [mm²]")
    ax.legend(fontsize=7)
    return curves


def _area_figure(output_dir, name, law, title, with_hertz, provenance):
    stack = DielectricStack()
    works = (0.0, float(stack.work_of_adhesion(GAP_REALISTIC, VOLTAGE)), float(stack.work_of_adhesion(0.0, VOLTAGE)))
    labels = ["non-adhesive", f"w = {works[1]:.3f} J/m² (200 V, 1 µm)", f"w = {works[2]:.3f} J/m² (200 V, 0 µm)"]
    fig, (ax_full, ax_zoom) = _new_figure(2)
    curves = plot_adhesive_area(ax_full, law, works, labels, float(law.area(AREA_MAX_FORCE, works[-1])))
    rows = [(0, w, f, a) for w, f, a in curves]
    zoom_area = 2 * float(law.zero_load_area(works[-1]))
    plot_adhesive_area(ax_zoom, law, works, labels, zoom_area, force_scale=1e3)
    if with_hertz:
        hertz = PowerLawContact.hertz(RADIUS, hertz_modulus_matching(law, RADIUS, FIT_FORCE))
        for w, label in zip(works, ("Hertz", "JKR (1 µm)", "JKR (0 µm)")):
            area = np.linspace(0.0, float(hertz.area(AREA_MAX_FORCE, w)), AREA_POINTS)
            force = hertz.normal_force(area, w)
            ax_full.plot(force, area / MM2, "--", label=label)
            rows.append((1, w, force, area))
        ax_full.legend(fontsize=7)
    ax_zoom.set_xlim(1.2e3 * float(law.pull_off(works[-1]).force), 10.0)
    ax_full.set_xlim(right=AREA_MAX_FORCE)
    ax_full.set_title(f"{title} (A)")
    ax_zoom.set_title("pull-off region (B)")
    columns = [np.concatenate([np.full(f.size, kind) for kind, w, f, a in rows]),
               np.concatenate([np.full(f.size, w) for kind, w, f, a in rows]),
               np.concatenate([f for kind, w, f, a in rows]), np.concatenate([a for kind, w, f, a in rows]) / MM2]
    return _write(fig, output_dir, name, ["hertz_jkr", "work_of_adhesion_J_per_m2", "normal_force_N", "area_mm2"],
                  columns, provenance)


def figure3(output_dir, provenance):
    """Fig. 3: apparent area vs load (Eq. 27 with Eq. 9), with Hertz/JKR for R* = 1 cm and E* fitted at 1 N."""
    return _area_figure(output_dir, "fig3_apparent_area", PowerLawContact.dzidek_apparent(), "apparent area",
                        True, provenance)


def figure4(output_dir, provenance):
    """Fig. 4: ridge area vs load (Eq. 28 with Eq. 9)."""
    return _area_figure(output_dir, "fig4_ridge_area", PowerLawContact.dzidek_ridge(), "ridge area",
                        False, provenance)


def figure5(output_dir, provenance, normal_forces=(0.25, 0.5, 1.0, 2.0)):
    """Fig. 5: apparent area vs tangential force up to F_T,c (Eqs. 31–32), R* = 1 cm, E* = 47.4 kPa fit,
    w = 0.132 J/m², G*/E* = 2/3."""
    E_star = hertz_modulus_matching(PowerLawContact.dzidek_apparent(), RADIUS, FIT_FORCE)
    peeling = SavkoorBriggsPeeling.incompressible_on_rigid(RADIUS, E_star)
    w = W_QUOTED
    fig, (ax,) = _new_figure(1)
    columns = [[], [], []]
    for force in normal_forces:
        tangential = np.linspace(0.0, float(peeling.critical_tangential_force(force, w)), PEELING_POINTS)
        area = peeling.area(tangential, force, w)
        ax.plot(tangential, area / MM2, label=f"F_N = {force:g} N")
        ax.plot(tangential[-1], area[-1] / MM2, "k.")
        for column, values in zip(columns, (np.full(tangential.size, force), tangential, area / MM2)):
            column.append(values)
    ax.set_xlabel("tangential force F_T [N]")
    ax.set_ylabel("apparent contact area [mm²]")
    ax.set_title(f"peeling (Savkoor–Briggs), w = {W_QUOTED} J/m²")
    ax.legend(fontsize=7)
    return _write(fig, output_dir, "fig5_peeling", ["normal_force_N", "tangential_force_N", "area_mm2"],
                  [np.concatenate(c) for c in columns], provenance)


def _friction_sweep(start=0.0):
    model = SlidingFrictionModel.paper_table1()
    forces = np.linspace(start, FRICTION_MAX_FORCE, FORCE_POINTS)
    states = [model.state(forces, voltage) for voltage in FRICTION_VOLTAGES]
    return forces, states


def _friction_figure(output_dir, name, forces, quantity, ylabel, column, provenance):
    fig, (ax,) = _new_figure(1)
    for voltage, values in zip(FRICTION_VOLTAGES, quantity):
        ax.plot(forces, values, label=f"{voltage:g} V")
    ax.set_xlabel("normal force F_N [N]")
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=7)
    header = ["normal_force_N"] + [f"{column}_{v:g}V" for v in FRICTION_VOLTAGES]
    return _write(fig, output_dir, name, header, [forces, *quantity], provenance)


def figure9(output_dir, provenance):
    """Fig. 9: (A) ridge-area reduction 1 − A_R/A_R0 at 0–200 V, (B) equivalent air gap (Eq. 46) vs load."""
    forces, states = _friction_sweep()
    fig, (ax_a, ax_b) = _new_figure(2)
    for voltage, state in zip(FRICTION_VOLTAGES, states):
        ax_a.plot(forces, 100 * state.area_reduction, label=f"{voltage:g} V")
    ax_a.set_xlabel("normal force F_N [N]")
    ax_a.set_ylabel("ridge-area reduction [%]")
    ax_a.legend(fontsize=7)
    ax_a.set_title("(A)")
    ax_b.plot(forces, 1e6 * states[0].gap)
    ax_b.set_xlabel("normal force F_N [N]")
    ax_b.set_ylabel("equivalent air gap [µm]")
    ax_b.set_title("(B)")
    header = ["normal_force_N"] + [f"area_reduction_percent_{v:g}V" for v in FRICTION_VOLTAGES] + ["gap_um"]
    return _write(fig, output_dir, "fig9_area_reduction_gap", header,
                  [forces, *[100 * s.area_reduction for s in states], 1e6 * states[0].gap], provenance)


def figure10(output_dir, provenance):
    """Fig. 10: sliding friction force F_T (Eq. 45) vs F_N at 0, 50, 100, 150, 200 V."""
    forces, states = _friction_sweep()
    return _friction_figure(output_dir, "fig10_tangential_force", forces, [s.tangential_force for s in states],
                            "tangential force F_T [N]", "tangential_force_N", provenance)


def figure11(output_dir, provenance):
    """Fig. 11: apparent friction coefficient μ = F_T/F_N (Eq. 42) vs F_N (from 0.05 N; μ → ∞ as F_N → 0)."""
    forces, states = _friction_sweep(start=MU_MIN_FORCE)
    return _friction_figure(output_dir, "fig11_friction_coefficient", forces, [s.friction_coefficient for s in states],
                            "apparent friction coefficient μ [-]", "friction_coefficient", provenance)


FIGURES = {"3": figure3, "4": figure4, "5": figure5, "9": figure9, "10": figure10, "11": figure11}


def reproduce(output_dir, provenance: Provenance | None = None) -> CheckpointTable:
    """Write every figure (PNG + CSV) and ``checkpoints.csv`` into ``output_dir`` (created if missing, only its
    last level: :func:`~roughcontact.io.output_directory`); return the checkpoint table. Each file
    carries ``provenance`` (default: this call and its output directory)."""
    output_dir = output_directory(output_dir)
    provenance = provenance or Provenance("roughcontact.paper.reproduce", {"output_dir": str(output_dir)})
    for figure in FIGURES.values():
        figure(output_dir, provenance)
    table = checkpoint_table()
    table.to_csv(output_dir / "checkpoints.csv", provenance)
    return table
