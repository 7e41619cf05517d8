"""The FE fingertip study: press-and-slide runs at several normal forces, the fit of seed Eq. 34 to each
L(f_T), ξ(f_N) as a power law, and the outputs of ``roughcontact fingertip-fe`` (CSV + PNG with provenance).

Needs FElupe (``pip install "roughcontact[fe]"``) to run the model; the tables it writes are read without it.
"""
from __future__ import annotations

import os
import sys
import warnings
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from surfaces.validation import check_integer, check_real

from ..io.pool import ProcessPool
from ..io.provenance import Provenance, save_figure, write_csv
from ..io.results import ConvergenceWarning
from ..macro.friction import SlidingFrictionModel
from .analysis import LinearFit, fit_eq34, power_law_fit
from .geometry import MATERIAL_NAMES
from .model import (MAX_INCREMENTS, MAX_TRAVEL_STEP, FEConvergenceError, FingertipModel, SlidingRun,
                    check_normal_force, default_travel_step)
from .store import run_fingerprint

#: Normal forces per unit width of the default sweep [N/m].
DEFAULT_NORMAL_FORCES = (25.0, 50.0, 100.0, 200.0, 400.0)
#: Friction coefficients of the default sweep: the friction law's μ0 (0 V).
DEFAULT_FRICTIONS = (SlidingFrictionModel.mu0,)
#: The seed's exponent of ξ ∝ f_N^k (Sect. 4.3, below Eq. 34).
SEED_EXPONENT = -1.1
SUMMARY_CSV = "fingertip_fe_summary.csv"
EXPONENT_CSV = "fingertip_fe_exponent.csv"
#: From this normal force per unit width up [N/m] the reduction at full slip is resolved (>= 8 %, tens of
#: node spacings on the default mesh) and ξ(f_N) is a power law (docs/guide/fe_fingertip.md).
RESOLVED_FORCE = 100.0


@dataclass(frozen=True)
class FingertipStudy:
    """The ``runs`` (one :class:`~roughcontact.fe.model.SlidingRun` per normal force and friction coefficient,
    ordered by μ, then f_N) of ``model`` (whose ``friction`` each run replaces)."""

    model: FingertipModel
    runs: tuple

    @property
    def normal_forces(self) -> np.ndarray:
        return np.array([run.normal_force for run in self.runs])

    @property
    def frictions(self) -> np.ndarray:
        """The distinct friction coefficients μ of the runs, ascending."""
        return np.unique([run.friction for run in self.runs])

    def at(self, friction: float) -> FingertipStudy:
        """The runs at friction coefficient μ = ``friction``."""
        return FingertipStudy(self.model, tuple(run for run in self.runs if run.friction == friction))

    def eq34_fits(self) -> tuple:
        """Eq. 34 fitted to each run's L(f_T) up to full slip (:func:`~roughcontact.fe.analysis.fit_eq34`)."""
        return tuple(fit_eq34(run.tangential_force, run.length) for run in self.runs)

    def exponent(self, lowest: float = 0.0) -> LinearFit:
        """ξ = C f_N^k over the runs (of one μ) with full slip and f_N >= ``lowest`` [N/m]: ``slope`` k and its
        standard error (:func:`exponent_fit`)."""
        if len(self.frictions) > 1:
            raise ValueError(f"the runs have several friction coefficients {self.frictions.tolist()}; take one "
                             "with study.at(mu)")
        xi = np.array([-fit.slope for fit in self.eq34_fits()])
        return exponent_fit(self.normal_forces, xi, [run.full_slip for run in self.runs], lowest)

    def summary_rows(self) -> list:
        """One row per run (SI units; per unit width)."""
        rows = []
        for run, fit in zip(self.runs, self.eq34_fits()):
            rows.append({
                "normal_force_N_per_m": run.normal_force, "friction": run.friction,
                "initial_length_m": run.initial_length,
                "sliding_length_m": run.sliding_length,
                "relative_reduction": run.relative_reduction,
                "xi_m3_per_N2": -fit.slope, "xi_error_m3_per_N2": fit.slope_error,
                "fit_initial_length_m": fit.intercept, "fit_rms_m": fit.rms,
                "tangential_force_full_slip_N_per_m": run.tangential_force[-1],
                "coulomb_ratio_minus_1": run.tangential_force[-1] / (run.friction * run.normal_force) - 1,
                "bone_force_ratio_minus_1": run.bone_tangential_force[-1] / (run.friction * run.normal_force) - 1,
                "travel_full_slip_m": run.travel[-1], "full_slip": run.full_slip,
                "increments": len(run.travel) - 1, "seconds": round(run.seconds, 1),
                "cpu_seconds": round(run.cpu_seconds, 1)})
        return rows


def _usable(normal_forces, xi, full_slip, lowest: float) -> np.ndarray:
    """The runs with full slip, ξ > 0 and f_N >= ``lowest`` [N/m]."""
    return np.asarray(full_slip, bool) & (np.asarray(xi, float) > 0) & (np.asarray(normal_forces, float) >= lowest)


def exponent_fit(normal_forces, xi, full_slip, lowest: float = 0.0) -> LinearFit:
    """Power law ξ = C f_N^k through the runs with full slip, ξ > 0 and f_N >= ``lowest`` [N/m]."""
    used = _usable(normal_forces, xi, full_slip, lowest)
    return power_law_fit(np.asarray(normal_forces, float)[used], np.asarray(xi, float)[used])


def exponent_rows(summary: list) -> tuple:
    """The exponent of ξ(f_N) per friction coefficient over all runs and over f_N >= ``RESOLVED_FORCE`` (the
    table of the command), and the notes on the ranges left out (fewer than 3 usable runs)."""
    rows, notes = [], []
    for friction in sorted({row["friction"] for row in summary}):
        runs = [row for row in summary if row["friction"] == friction]
        forces, xi, full_slip = ([row[name] for row in runs] for name in
                                 ("normal_force_N_per_m", "xi_m3_per_N2", "full_slip"))
        for lowest in (0.0, RESOLVED_FORCE):
            usable = int(_usable(forces, xi, full_slip, lowest).sum())
            if usable < 3:
                notes.append(f"mu = {friction:g}, f_N >= {lowest:g} N/m: {usable} run(s) with full slip and xi > 0; "
                             "the power law xi = C f_N^k needs at least 3")
                continue
            fit = exponent_fit(forces, xi, full_slip, lowest)
            rows.append({"friction": friction, "lowest_normal_force_N_per_m": lowest, "exponent": fit.slope,
                         "exponent_error": fit.slope_error, "log_prefactor": fit.intercept,
                         "log_prefactor_error": fit.intercept_error, "rms_log_residual": fit.rms,
                         "seed_exponent": SEED_EXPONENT})
    return rows, notes


def _slide(model: FingertipModel, normal_force: float, travel_step, max_travel: float) -> SlidingRun | str:
    """One run (a task of the pool: a module-level function), or the message of its failed press."""
    try:
        return model.slide(normal_force, travel_step=travel_step, max_travel=max_travel)
    except FEConvergenceError as error:
        return str(error)


def _solver_version() -> str:
    from importlib.metadata import PackageNotFoundError, version
    try:
        return f"felupe {version('felupe')}, tensortrax {version('tensortrax')}"
    except PackageNotFoundError:
        return "felupe missing"


def run_fingertip_study(model: FingertipModel = FingertipModel(), normal_forces=DEFAULT_NORMAL_FORCES,
                        frictions=None, travel_step: float | None = None, max_travel: float = 30e-3,
                        workers: int | None = None, store=None, progress: bool = False, check_only: bool = False
                        ) -> FingertipStudy | None:
    """Press-and-slide runs of ``model`` at each normal force per unit width [N/m] (seed Fig. 7) and each
    friction coefficient in ``frictions`` (default: the model's), on a local process pool of ``workers``
    (default: one per core; 1 runs in this process). ``store`` a :class:`~roughcontact.fe.store.RunStore`:
    runs found there (validated) are reused, finished runs saved, so an interrupted sweep resumes. ``progress``
    shows a bar (tqdm). ``check_only``: check the values (``ValueError`` naming the first bad one) and return
    None."""
    forces = [check_normal_force(f) for f in np.sort(np.unique(np.asarray(normal_forces, float)))]
    frictions = (model.friction,) if frictions is None else np.unique(np.asarray(frictions, float))
    models = {float(mu): replace(model, friction=float(mu)) for mu in frictions}      # (validates each μ)
    workers = min(len(forces) * len(models), os.cpu_count() or 1) if workers is None else \
        check_integer("workers", workers, low=1)
    for force, mu in ((f, m) for m in models for f in forces):                       # (validates the travel)
        check_real("travel_step", default_travel_step(force, mu) if travel_step is None else travel_step,
                   low=max_travel / MAX_INCREMENTS, high=MAX_TRAVEL_STEP)
    if check_only:
        return None
    version = _solver_version()
    keys = [(mu, force) for mu in models for force in forces]
    prints = {key: run_fingerprint(models[key[0]], key[1], travel_step, max_travel, version) for key in keys}
    runs = {key: store.load(prints[key], key[1], key[0]) for key in keys} if store is not None else {}
    missing, failed = [key for key in keys if runs.get(key) is None], []
    bar = _progress(len(keys), len(keys) - len(missing)) if progress else None
    for key, run in _finished(models, missing, travel_step, max_travel, workers):
        if isinstance(run, str):                           # a failed press: the sweep goes on without it
            warnings.warn(f"mu = {key[0]:g}: {run}; the run is left out", ConvergenceWarning, stacklevel=2)
            failed.append(run)
            continue
        runs[key] = run
        if store is not None:
            store.save(prints[key], run)
        if bar is not None:
            bar.set_postfix_str(f"f_N = {run.normal_force:g} N/m, mu = {run.friction:g}: "
                                f"{'full slip' if run.full_slip else 'NO full slip'}, {run.seconds:.0f} s")
            bar.update()
    if bar is not None:
        bar.close()
    if not any(runs.get(key) for key in keys):
        raise FEConvergenceError("; ".join(failed))
    return FingertipStudy(model=model, runs=tuple(runs[key] for key in keys if runs.get(key) is not None))


def _finished(models: dict, keys: list, travel_step, max_travel: float, workers: int):
    """Yield ((μ, f_N), run) as the runs of ``keys`` finish: in this process for one worker, else on a
    :class:`~roughcontact.io.pool.ProcessPool`, the costliest runs first (largest μ f_N); interrupted, the pool's
    waiting runs are cancelled and its workers terminated."""
    if workers == 1 or len(keys) <= 1:
        for mu, force in keys:
            yield (mu, force), _slide(models[mu], force, travel_step, max_travel)
        return
    with ProcessPool(min(workers, len(keys))) as pool:
        futures = {pool.submit(_slide, models[mu], force, travel_step, max_travel): (mu, force)
                   for mu, force in sorted(keys, key=lambda key: key[0] * key[1], reverse=True)}
        for future in pool.as_completed(futures):
            yield futures[future], future.result()


def _progress(total: int, done: int):
    from tqdm import tqdm
    bar = tqdm(total=total, initial=done, unit="run", desc="fingertip-fe", file=sys.stderr)
    if done:
        bar.write(f"fingertip-fe: {done} of {total} runs reused from the store")
    return bar


def _curve_rows(study: FingertipStudy) -> list:
    return [{"normal_force_N_per_m": run.normal_force, "friction": run.friction, "increment": i,
             "travel_m": run.travel[i],
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
                    rows.append({"normal_force_N_per_m": run.normal_force, "friction": run.friction,
                                 "increment": i,
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
    """(A) L(f_T) with the Eq. 34 fits at the smallest μ; (B) L0 and L at full slip against f_N, per μ."""
    plt = _pyplot()

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    first = study.at(study.frictions[0])
    for run, fit in zip(first.runs, first.eq34_fits()):
        f_t = run.tangential_force
        left.plot(f_t, run.length * 1e3, ".", ms=3, label=f"$f_N$ = {run.normal_force:g} N/m")
        grid = np.linspace(0, f_t.max(), 50)
        left.plot(grid, (fit.intercept + fit.slope * grid ** 2) * 1e3, "--", color="0.5", lw=1)
    left.set(xlabel="tangential force per unit width $f_T$ [N/m]", ylabel="contact length $L$ [mm]",
             title=f"(A) L(f_T) at μ = {study.frictions[0]:g}, dashed: Eq. 34 fits")
    left.legend(fontsize=8)
    right.plot(first.normal_forces, [r.initial_length * 1e3 for r in first.runs], "ko-",
               label="before tangential loading ($L_0$)")
    for friction in study.frictions:
        runs = study.at(friction).runs
        right.plot([r.normal_force for r in runs], [r.sliding_length * 1e3 for r in runs], "s-", ms=4,
                   label=f"at the onset of full slip, μ = {friction:g}")
    right.set(xlabel="normal force per unit width $f_N$ [N/m]", ylabel="contact length [mm]", xscale="log",
              title="(B) contact length against $f_N$")
    right.legend(fontsize=7)
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
    figure.suptitle(f"FE finger section at $f_N$ = {run.normal_force:g} N/m, μ = {run.friction:g} "
                    f"(colours: {', '.join(MATERIAL_NAMES)})", fontsize=10)
    return _save(plt, figure, path, provenance)


def _figure_stick_slip(study: FingertipStudy, provenance: Provenance, path: Path) -> Path:
    """Stick and slip along the contact per increment, one panel per run at the smallest μ."""
    plt = _pyplot()
    study = study.at(study.frictions[0])

    figure, axes = plt.subplots(1, len(study.runs), figsize=(3 * len(study.runs), 3.6), sharey=True)
    for axis, run in zip(np.atleast_1d(axes), study.runs):
        for i, snap in enumerate(run.snapshots):
            ratio = run.tangential_force[i] / (run.friction * run.normal_force)
            contact = snap.normal > 0
            centre = snap.x[contact].mean()
            for state, colour in ((~snap.slip, "tab:blue"), (snap.slip, "tab:red")):
                mask = contact & state
                axis.plot((snap.x[mask] - centre) * 1e3, np.full(mask.sum(), ratio), ".", color=colour, ms=1.5)
        axis.set(title=f"$f_N$ = {run.normal_force:g} N/m, μ = {run.friction:g}",
                 xlabel="x − contact centre [mm]")
    np.atleast_1d(axes)[0].set_ylabel(r"$f_T / (\mu f_N)$  (blue stick, red slip)")
    return _save(plt, figure, path, provenance)


def write_fingertip_outputs(study: FingertipStudy, output, provenance: Provenance, echo: bool = False) -> list:
    """Write the study's CSV tables and PNG figures into ``output`` (each with ``provenance``); the paths."""
    output = Path(output)
    summary = study.summary_rows()
    exponents, notes = exponent_rows(summary)
    paths = [write_csv(output / SUMMARY_CSV, summary, provenance, echo=echo),
             write_csv(output / "fingertip_fe_curves.csv", _curve_rows(study), provenance),
             write_csv(output / "fingertip_fe_stick_slip.csv", _stick_slip_rows(study), provenance)]
    if exponents:
        paths.append(write_csv(output / EXPONENT_CSV, exponents, provenance, echo=echo))
    for note in notes:
        print(f"{EXPONENT_CSV}: {note}" + ("" if exponents else "; not written"), file=sys.stderr)
    first = study.at(study.frictions[0])
    shown = first.runs[int(np.argmin(np.abs(first.normal_forces - 200.0)))]
    write_csv(output / "fingertip_fe_mesh.csv",
              [{"node": i, "x_pressed_m": p[0], "y_pressed_m": p[1], "x_full_slip_m": q[0], "y_full_slip_m": q[1]}
               for i, (p, q) in enumerate(zip(shown.pressed_points, shown.final_points))], provenance)
    paths.append(output / "fingertip_fe_mesh.csv")
    paths += [_figure_fig7(study, provenance, output / "fingertip_fe_fig7.png"),
              _figure_fig6(shown, provenance, output / "fingertip_fe_fig6.png"),
              _figure_stick_slip(study, provenance, output / "fingertip_fe_stick_slip.png")]
    return paths
