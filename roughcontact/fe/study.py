"""The FE fingertip study: press-and-slide runs at several normal forces, the fit of seed Eq. 34 to each
L(f_T), ξ(f_N) as a power law, and the outputs of ``roughcontact fingertip-fe`` (CSV + PNG with provenance).

Needs FElupe (``pip install "roughcontact[fe]"``) to run the model; the tables it writes are read without it.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..io.provenance import Provenance, save_figure, write_csv
from .analysis import LinearFit, fit_eq34, power_law_fit
from .geometry import MATERIAL_NAMES
from .model import FingertipModel, SlidingRun

#: Normal forces per unit width of the default sweep [N/m] (0.025–0.4 N/mm).
DEFAULT_NORMAL_FORCES = (25.0, 50.0, 100.0, 200.0, 400.0)
#: The seed's exponent of ξ ∝ f_N^k (Sect. 4.3, below Eq. 34).
SEED_EXPONENT = -1.1
SUMMARY_CSV = "fingertip_fe_summary.csv"
#: From this normal force per unit width up [N/m] the reduction at full slip is resolved (>= 8 %, tens of
#: node spacings on the default mesh) and ξ(f_N) is a power law (docs/guide/fe_fingertip.md).
RESOLVED_FORCE = 100.0


@dataclass(frozen=True)
class FingertipStudy:
    """The ``runs`` (one :class:`~roughcontact.fe.model.SlidingRun` per normal force, ascending) of ``model``."""

    model: FingertipModel
    runs: tuple

    @property
    def normal_forces(self) -> np.ndarray:
        return np.array([run.normal_force for run in self.runs])

    def eq34_fits(self) -> tuple:
        """Eq. 34 fitted to each run's L(f_T) up to full slip (:func:`~roughcontact.fe.analysis.fit_eq34`)."""
        return tuple(fit_eq34(run.tangential_force, run.length) for run in self.runs)

    def exponent(self, lowest: float = 0.0) -> LinearFit:
        """ξ = C f_N^k over the runs with full slip and f_N >= ``lowest`` [N/m]: ``slope`` k and its standard
        error (:func:`exponent_fit`)."""
        xi = np.array([-fit.slope for fit in self.eq34_fits()])
        return exponent_fit(self.normal_forces, xi, [run.full_slip for run in self.runs], lowest)

    def summary_rows(self) -> list:
        """One row per normal force (SI units; per unit width)."""
        rows = []
        for run, fit in zip(self.runs, self.eq34_fits()):
            rows.append({
                "normal_force_N_per_m": run.normal_force,
                "initial_length_m": run.initial_length,
                "sliding_length_m": run.sliding_length,
                "relative_reduction": run.relative_reduction,
                "xi_m3_per_N2": -fit.slope, "xi_error_m3_per_N2": fit.slope_error,
                "fit_initial_length_m": fit.intercept, "fit_rms_m": fit.rms,
                "tangential_force_full_slip_N_per_m": run.tangential_force[-1],
                "coulomb_ratio_minus_1": run.tangential_force[-1] / (run.friction * run.normal_force) - 1,
                "bone_force_ratio_minus_1": run.bone_tangential_force[-1] / (run.friction * run.normal_force) - 1,
                "travel_full_slip_m": run.travel[-1], "full_slip": run.full_slip,
                "increments": len(run.travel) - 1, "seconds": round(run.seconds, 1)})
        return rows


def _usable(normal_forces, xi, full_slip, lowest: float) -> np.ndarray:
    """The runs with full slip, ξ > 0 and f_N >= ``lowest`` [N/m]."""
    return np.asarray(full_slip, bool) & (np.asarray(xi, float) > 0) & (np.asarray(normal_forces, float) >= lowest)


def exponent_fit(normal_forces, xi, full_slip, lowest: float = 0.0) -> LinearFit:
    """Power law ξ = C f_N^k through the runs with full slip, ξ > 0 and f_N >= ``lowest`` [N/m]."""
    used = _usable(normal_forces, xi, full_slip, lowest)
    return power_law_fit(np.asarray(normal_forces, float)[used], np.asarray(xi, float)[used])


def exponent_rows(normal_forces, xi, full_slip) -> list:
    """The exponent of ξ(f_N) over all runs and over f_N >= ``RESOLVED_FORCE`` (the table of the command; a
    range with fewer than 3 usable runs is left out)."""
    rows = []
    for lowest in (0.0, RESOLVED_FORCE):
        if _usable(normal_forces, xi, full_slip, lowest).sum() < 3:
            continue
        fit = exponent_fit(normal_forces, xi, full_slip, lowest)
        rows.append({"lowest_normal_force_N_per_m": lowest, "exponent": fit.slope, "exponent_error": fit.slope_error,
                     "log_prefactor": fit.intercept, "log_prefactor_error": fit.intercept_error,
                     "rms_log_residual": fit.rms, "seed_exponent": SEED_EXPONENT})
    return rows


def run_fingertip_study(model: FingertipModel = FingertipModel(), normal_forces=DEFAULT_NORMAL_FORCES,
                        travel_step: float = 0.1e-3, max_travel: float = 15e-3, progress: bool = False
                        ) -> FingertipStudy:
    """Press-and-slide runs of ``model`` at each normal force per unit width [N/m] (seed Fig. 7)."""
    forces = np.sort(np.asarray(normal_forces, float))
    runs = []
    for force in forces:
        runs.append(model.slide(float(force), travel_step=travel_step, max_travel=max_travel))
        if progress:
            run = runs[-1]
            print(f"f_N = {force:g} N/m: L0 = {run.initial_length * 1e3:.3f} mm, L_slide = "
                  f"{run.sliding_length * 1e3:.3f} mm, {len(run.travel) - 1} increments, {run.seconds:.0f} s",
                  flush=True)
    return FingertipStudy(model=model, runs=tuple(runs))


def _curve_rows(study: FingertipStudy) -> list:
    return [{"normal_force_N_per_m": run.normal_force, "increment": i, "travel_m": run.travel[i],
             "tangential_force_N_per_m": run.tangential_force[i],
             "contact_normal_force_N_per_m": run.contact_normal_force[i], "length_m": run.length[i],
             "length_gap_m": run.length_gap[i], "slipping_fraction": run.slipping[i]}
            for run in study.runs for i in range(len(run.travel))]


def _stick_slip_rows(study: FingertipStudy) -> list:
    rows = []
    for run in study.runs:
        for i, snap in enumerate(run.snapshots):
            for x, fn, ft, slip in zip(snap.x, snap.normal, snap.tangential, snap.slip):
                if fn > 0:
                    rows.append({"normal_force_N_per_m": run.normal_force, "increment": i,
                                 "tangential_force_N_per_m": run.tangential_force[i], "x_m": x,
                                 "nodal_normal_force_N_per_m": fn, "nodal_tangential_force_N_per_m": -ft,
                                 "state": "slip" if slip else "stick"})
    return rows


def _pyplot():
    """matplotlib's pyplot on the non-interactive backend."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _save(plt, figure, path: Path, provenance: Provenance) -> Path:
    figure.tight_layout()
    path = save_figure(figure, path, provenance)
    plt.close(figure)
    return path


def _figure_fig7(study: FingertipStudy, provenance: Provenance, path: Path) -> Path:
    plt = _pyplot()

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for run, fit in zip(study.runs, study.eq34_fits()):
        f_t = run.tangential_force
        line, = left.plot(f_t * 1e-3, run.length * 1e3, ".", ms=3, label=f"$f_N$ = {run.normal_force * 1e-3:g} N/mm")
        grid = np.linspace(0, f_t.max(), 50)
        left.plot(grid * 1e-3, (fit.intercept + fit.slope * grid ** 2) * 1e3, "--", color="0.5", lw=1)
    left.set(xlabel="tangential force per unit width $f_T$ [N/mm]", ylabel="contact length $L$ [mm]",
             title="(A) L(f_T), dashed: Eq. 34 fits")
    left.legend(fontsize=8)
    forces = study.normal_forces * 1e-3
    right.plot(forces, [r.initial_length * 1e3 for r in study.runs], "o-", label="before tangential loading ($L_0$)")
    right.plot(forces, [r.sliding_length * 1e3 for r in study.runs], "s-", label="at the onset of full slip")
    right.set(xlabel="normal force per unit width $f_N$ [N/mm]", ylabel="contact length [mm]",
              title="(B) contact length against $f_N$")
    right.legend(fontsize=8)
    return _save(plt, figure, path, provenance)


def _figure_fig6(run: SlidingRun, provenance: Provenance, path: Path) -> Path:
    plt = _pyplot()
    from matplotlib.collections import PolyCollection

    colours = {0: "#f2c6a0", 1: "#c8745a", 2: "#8a8fa8"}
    figure, axes = plt.subplots(1, 2, figsize=(10, 4.8), sharey=True)
    plate = min(run.pressed_points[:, 1].min(), run.final_points[:, 1].min())
    states = ((run.pressed_points, run.snapshots[0], "(B) pressed, before tangential travel"),
              (run.final_points, run.snapshots[-1],
               "(C) onset of full slip" if run.full_slip else "(C) last increment"))
    for axis, (points, snapshot, title) in zip(axes, states):
        polygons = PolyCollection(points[run.cells] * 1e3, facecolors=[colours[m] for m in run.material],
                                  edgecolors="k", linewidths=0.15)
        axis.add_collection(polygons)
        contact = snapshot.normal > 0
        axis.plot(snapshot.x[contact & ~snapshot.slip] * 1e3, np.full((contact & ~snapshot.slip).sum(), plate * 1e3),
                  "b|", ms=8, label="stick")
        axis.plot(snapshot.x[contact & snapshot.slip] * 1e3, np.full((contact & snapshot.slip).sum(), plate * 1e3),
                  "r|", ms=8, label="slip")
        axis.axhline(plate * 1e3, color="k", lw=1.5)
        axis.set_aspect("equal")
        axis.autoscale_view()
        axis.set(title=title, xlabel="x [mm]")
        axis.legend(fontsize=8, loc="upper right")
    axes[0].set_ylabel("y [mm]")
    figure.suptitle(f"FE finger section at $f_N$ = {run.normal_force * 1e-3:g} N/mm, μ = {run.friction} "
                    f"(colours: {', '.join(MATERIAL_NAMES)})", fontsize=10)
    return _save(plt, figure, path, provenance)


def _figure_stick_slip(study: FingertipStudy, provenance: Provenance, path: Path) -> Path:
    plt = _pyplot()

    figure, axes = plt.subplots(1, len(study.runs), figsize=(3 * len(study.runs), 3.6), sharey=True)
    for axis, run in zip(np.atleast_1d(axes), study.runs):
        for i, snap in enumerate(run.snapshots):
            ratio = run.tangential_force[i] / (run.friction * run.normal_force)
            contact = snap.normal > 0
            centre = snap.x[contact].mean()
            for state, colour in ((~snap.slip, "tab:blue"), (snap.slip, "tab:red")):
                mask = contact & state
                axis.plot((snap.x[mask] - centre) * 1e3, np.full(mask.sum(), ratio), ".", color=colour, ms=1.5)
        axis.set(title=f"$f_N$ = {run.normal_force * 1e-3:g} N/mm", xlabel="x − contact centre [mm]")
    np.atleast_1d(axes)[0].set_ylabel(r"$f_T / (\mu f_N)$  (blue stick, red slip)")
    return _save(plt, figure, path, provenance)


def write_fingertip_outputs(study: FingertipStudy, output, provenance: Provenance, echo: bool = False) -> list:
    """Write the study's CSV tables and PNG figures into ``output`` (each with ``provenance``); the paths."""
    output = Path(output)
    summary = study.summary_rows()
    exponents = exponent_rows([row["normal_force_N_per_m"] for row in summary],
                              [row["xi_m3_per_N2"] for row in summary], [row["full_slip"] for row in summary])
    paths = [write_csv(output / SUMMARY_CSV, summary, provenance, echo=echo),
             write_csv(output / "fingertip_fe_curves.csv", _curve_rows(study), provenance),
             write_csv(output / "fingertip_fe_stick_slip.csv", _stick_slip_rows(study), provenance),
             *([write_csv(output / "fingertip_fe_exponent.csv", exponents, provenance, echo=echo)]
               if exponents else [])]
    shown = study.runs[int(np.argmin(np.abs(study.normal_forces - 200.0)))]
    write_csv(output / "fingertip_fe_mesh.csv",
              [{"node": i, "x_pressed_m": p[0], "y_pressed_m": p[1], "x_full_slip_m": q[0], "y_full_slip_m": q[1]}
               for i, (p, q) in enumerate(zip(shown.pressed_points, shown.final_points))], provenance)
    paths.append(output / "fingertip_fe_mesh.csv")
    paths += [_figure_fig7(study, provenance, output / "fingertip_fe_fig7.png"),
              _figure_fig6(shown, provenance, output / "fingertip_fe_fig6.png"),
              _figure_stick_slip(study, provenance, output / "fingertip_fe_stick_slip.png")]
    return paths
