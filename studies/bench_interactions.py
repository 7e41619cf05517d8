"""Cost of electroadhesive contact against the hard wall, and of a voltage continuation against cold solves.

    python studies/bench_interactions.py                     # 256² and 512², the table of docs/guide/interactions.md
    python studies/bench_interactions.py --sizes 1024 --output out
    python studies/bench_interactions.py --fast              # 64², seconds
    python studies/bench_interactions.py --sizes 512 --voltages 30 50 100 --realisations 4   # summed over 4

The scene is the electrostatic bar's rough patch: 1 mm square, 3 µm rms self-affine heights (H = 0.8, short
cut-off 8 px; realisation r has ``rng=r``, r = 1 … ``--realisations``), contact modulus E* (``--E-star``,
default 1 MPa), external load p̄ (``--pressure``, default 1 kPa), the seed's dielectric stack (Table 1). For each
grid: the hard-wall solve (Polonsky–Keer) and the electrostatic solves (the per-pixel law,
``field="parallel_plate"``: the peers' law; the layered field's cost is ``studies/bench_field.py``) at each
voltage, cold, their time and FFT pairs as multiples of the hard wall's; then the voltage sweep 0 → max solved
cold at every step and as a continuation (each solve starts from the last gap); the ``sweep`` row holds the
continuation's time and FFT pairs and their shares of the cold solves'. With ``--realisations`` > 1 the costs are
also summed over the realisations, as ratios of the hard wall's sum (``bench_interactions_totals.csv``), and the
continuation's as a share of the cold solves' sum (section ``sweep``): near the snap-in one solve's cost moves by
a factor 2 with its path, and the sums average it. ``--peers``: the
same electrostatic problem in Tamaas (gap-primal Polonsky–Keer–Rey with the law as a Python functional, at our
mean gap) and ContactMechanics + Adhesion (L-BFGS-B at our flat position), timed against our solve at the same
control, with the relative difference of the conjugate quantity. Writes ``bench_interactions.csv`` with its
provenance into ``--output``.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from _bench import best_of, count_argument, summed_ratios
from surfaces import Grid, self_affine
from roughcontact import ElasticHalfSpace, ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import DielectricStack
from roughcontact.io import output_directory, parse_arguments, write_csv

COLUMNS = ("section", "n", "realisation", "voltage_V", "time_s", "time_ratio", "iterations", "fft_pairs",
           "fft_pair_ratio", "contact_fraction", "equivalent_gap_m", "converged", "relative_difference", "note")


def patch(n, E_star, realisation=1):
    grid = Grid((n, n), (1e-3, 1e-3), periodic=True)
    surface = self_affine(grid, hurst=0.8, rms_height=3e-6, short_cutoff=8e-3 / n,
                          rng=realisation)
    return surface, ElasticHalfSpace(grid, E_star=E_star, planner_effort="FFTW_MEASURE")



def rows_for(n, args, realisation=1):
    surface, half = patch(n, args.E_star, realisation)
    stack = DielectricStack()
    solve_contact(surface, half, mean_pressure=args.pressure, tol=args.tol)              # JIT and plans warm
    hard, hard_time = best_of(lambda: solve_contact(surface, half, mean_pressure=args.pressure, tol=args.tol),
                              args.repeat)
    rows = [dict(section="hard_wall", n=n, realisation=realisation, voltage_V=0.0, time_s=hard_time, time_ratio=1.0,
                 iterations=hard.iterations, fft_pairs=hard.solver.fft_pairs, fft_pair_ratio=1.0,
                 contact_fraction=hard.contact_fraction, equivalent_gap_m=stack.equivalent_gap(hard.gap),
                 converged=hard.converged)]
    sweeps = {kind: {"time_s": 0.0, "fft_pairs": 0.0} for kind in ("cold", "continuation")}
    previous = None
    for voltage in args.voltages:
        law = ElectrostaticInteraction(stack, voltage, field="parallel_plate")
        for kind in ("cold", "continuation"):
            x0 = previous if kind == "continuation" and previous is not None and voltage > 0 else None
            res, seconds = best_of(lambda: solve_contact(surface, half, mean_pressure=args.pressure, tol=args.tol,
                                                         interaction=law, x0=x0, warn=False), args.repeat)
            sweeps[kind]["time_s"] += seconds
            sweeps[kind]["fft_pairs"] += res.solver.fft_pairs
            rows.append(dict(section=f"electrostatic_{kind}", n=n, realisation=realisation, voltage_V=voltage,
                             time_s=seconds, time_ratio=seconds / hard_time, iterations=res.iterations,
                             fft_pairs=res.solver.fft_pairs, fft_pair_ratio=res.solver.fft_pairs /
                             hard.solver.fft_pairs, contact_fraction=res.contact_fraction,
                             equivalent_gap_m=res.equivalent_gap, converged=res.converged))
        previous = res
    cold, continued = sweeps["cold"], sweeps["continuation"]
    rows.append(dict(section="sweep", n=n, realisation=realisation, voltage_V=max(args.voltages),
                     time_s=continued["time_s"], time_ratio=continued["time_s"] / cold["time_s"],
                     fft_pairs=continued["fft_pairs"], fft_pair_ratio=continued["fft_pairs"] / cold["fft_pairs"]))
    return rows


def tamaas_electrostatic(surface, E_star, law, mean_gap, tol):
    """Tamaas 2.x at the mean gap [m] (its gap-primal Polonsky–Keer–Rey with the electrostatic energy as a Python
    ``tamaas.Functional``: Σ V(g) and its gradient, the normalisation of its own adhesion functionals).
    Returns (time [s], mean pressure [Pa], displacement field [m])."""
    import tamaas as tm

    class Electrostatic(tm.Functional):
        def computeF(self, gap, dual):
            return float(np.sum(law.energy(np.asarray(gap))))

        def computeGradF(self, gap, gradient):
            gradient_array = np.asarray(gradient)
            gradient_array -= law.traction(np.asarray(gap))

    n, length = surface.grid.shape[0], surface.grid.lengths[0]
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [length, length], [n, n])
    model.E, model.nu = E_star, 0.0
    heights = surface.heights.copy()
    solver = tm.PolonskyKeerRey(model, heights, tol, tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.gap)
    functional = Electrostatic()
    solver.addFunctionalTerm(functional)
    start = time.perf_counter()
    solver.solve(mean_gap)
    seconds = time.perf_counter() - start
    return seconds, float(np.mean(model.traction)), np.array(model.displacement).reshape(n, n)


def contactmechanics_electrostatic(surface, E_star, law, flat_position, gtol):
    """ContactMechanics + Adhesion at the flat position s [m] (``BoundedSmoothContactSystem.minimize_proxy`` at
    offset −s: their gap u − h − offset is ours; L-BFGS-B with the bound g ≥ 0; the q = 0 mode has their
    default stiffness, so the load follows from the solution). Returns (time [s], mean pressure [Pa],
    mean gap [m], contact fraction)."""
    from Adhesion.Interactions import Potential
    from Adhesion.System import BoundedSmoothContactSystem
    from ContactMechanics import PeriodicFFTElasticHalfSpace
    from SurfaceTopography import Topography

    class Electrostatic(Potential):
        name = "electrostatic"

        def __init__(self):
            Potential.__init__(self)

        def __repr__(self):
            return f"Electrostatic({law})"

        r_min = r_infl = property(lambda self: None)

        def evaluate(self, gap, potential=True, gradient=False, curvature=False, mask=None):
            return law.energy(gap), -law.traction(gap), -law.stiffness(gap)

    n, length = surface.grid.shape[0], surface.grid.lengths[0]
    substrate = PeriodicFFTElasticHalfSpace((n, n), E_star, physical_sizes=(length, length))
    system = BoundedSmoothContactSystem(substrate, Electrostatic(),
                                        Topography(surface.heights, physical_sizes=(length, length), periodic=True))
    start = time.perf_counter()
    result = system.minimize_proxy(offset=-flat_position, options=dict(gtol=gtol, ftol=0, maxiter=100000))
    seconds = time.perf_counter() - start
    gap = result.x.reshape(n, n) - surface.heights + flat_position
    return seconds, system.compute_normal_force() / length ** 2, float(gap.mean()), float(np.mean(gap <= 0))


def peer_rows(n, args):
    """The same electrostatic problem solved by Tamaas (at our mean gap) and ContactMechanics + Adhesion (at our
    flat position), against our solves at the same control."""
    surface, half = patch(n, args.E_star)
    rows = []
    for voltage in args.peer_voltages:
        law = ElectrostaticInteraction(DielectricStack(), voltage, field="parallel_plate")
        operating = solve_contact(surface, half, mean_pressure=args.pressure, tol=args.tol, interaction=law)
        ours, ours_time = best_of(lambda: solve_contact(surface, half, penetration=operating.penetration,
                                                        tol=args.tol, interaction=law))
        seconds, pressure, _ = tamaas_electrostatic(surface, args.E_star, law, ours.mean_gap, args.tol)
        rows.append(dict(section="peer_tamaas", n=n, voltage_V=voltage, time_s=seconds, time_ratio=seconds / ours_time,
                         relative_difference=abs(pressure / ours.mean_pressure - 1), iterations=ours.iterations,
                         contact_fraction=ours.contact_fraction, converged=ours.converged,
                         note="at our mean gap; relative difference of the mean pressure"))
        seconds, pressure, mean_gap, fraction = contactmechanics_electrostatic(
            surface, args.E_star, law, operating.flat_position, args.gtol)
        ours, ours_time = best_of(lambda: solve_contact(surface, half, mean_pressure=pressure, tol=args.tol,
                                                        interaction=law))
        rows.append(dict(section="peer_contactmechanics", n=n, voltage_V=voltage, time_s=seconds,
                         time_ratio=seconds / ours_time, relative_difference=abs(mean_gap / ours.mean_gap - 1),
                         iterations=ours.iterations, contact_fraction=fraction, converged=ours.converged,
                         note="ours at their load; relative difference of the mean gap"))
    return rows



def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 512], help="grid sizes n (n² pixels)")
    parser.add_argument("--voltages", type=float, nargs="+", default=[1e-6, 3.0, 10.0, 30.0, 50.0, 100.0, 200.0],
                        help="voltages U [V], solved in this order")
    parser.add_argument("--realisations", type=count_argument, default=1,
                        help="patch realisations rng = 1 … R; with R > 1 the costs are also summed over them")
    parser.add_argument("--E-star", type=float, default=1e6, help="contact modulus E* [Pa]")
    parser.add_argument("--pressure", type=float, default=1e3, help="external load p̄ [Pa]")
    parser.add_argument("--tol", type=float, default=1e-8, help="relative tolerance of both solvers")
    parser.add_argument("--repeat", type=count_argument, default=1,
                        help="solves per timing; the best time is kept (the machine's other load only adds)")
    parser.add_argument("--peers", action="store_true", help="also Tamaas and ContactMechanics + Adhesion")
    parser.add_argument("--peer-voltages", type=float, nargs="+", default=[3.0, 10.0],
                        help="voltages of the peer comparison [V] (low: a unique equilibrium)")
    parser.add_argument("--gtol", type=float, default=1e-10,
                        help="ContactMechanics' L-BFGS-B projected-gradient tolerance [N per pixel]")
    parser.add_argument("--fast", action="store_true", help="64² and two voltages: a test that the script runs")
    parser.add_argument("--output", default="out", help="directory for bench_interactions.csv")
    args, provenance = parse_arguments(parser, argv, "studies/bench_interactions.py")
    if args.fast:
        args.sizes, args.voltages = [64], [10.0, 30.0]
    if args.peers:
        import tamaas as tm
        tm.initialize(1)                                    # one thread, as ours
        tm.set_log_level(tm.LogLevel.error)
    rows = [row for n in args.sizes for realisation in range(1, args.realisations + 1)
            for row in rows_for(n, args, realisation)] + [row for n in args.sizes if args.peers
                                                          for row in peer_rows(n, args)]
    directory = output_directory(args.output)
    path = write_csv(directory / "bench_interactions.csv", rows, provenance, COLUMNS)
    for row in rows:
        print("  ".join(f"{key}={value:.4g}" if isinstance(value, float) else f"{key}={value}"
                        for key, value in row.items()))
    print(f"wrote {path}")
    if args.realisations > 1:
        solves = [row for row in rows
                  if row["section"] in ("hard_wall", "electrostatic_cold", "electrostatic_continuation")]
        totals = summed_ratios(solves, ("n", "section", "voltage_V"), lambda key: (key[0], "hard_wall", 0.0))
        sweeps = [dict(row, section=f"sweep_{row['section'][len('electrostatic_'):]}") for row in rows
                  if row["section"] in ("electrostatic_cold", "electrostatic_continuation")]
        totals += [dict(row, section="sweep", voltage_V=max(args.voltages), count=args.realisations)
                   for row in summed_ratios(sweeps, ("n", "section"), lambda key: (key[0], "sweep_cold"))
                   if row["section"] == "sweep_continuation"]
        write_csv(directory / "bench_interactions_totals.csv", totals, provenance)
        for row in totals:
            reference = "the cold solves" if row["section"] == "sweep" else "the hard wall"
            print(f"{row['n']:4d}² {row['section']:28s} {row['voltage_V']:6.3g} V over {row['count']} realisations: "
                  f"{row['fft_pairs']:7.0f} FFT pairs (x{row['fft_pairs_ratio']:.2f} {reference}), "
                  f"time x{row['time_s_ratio']:.2f}")


if __name__ == "__main__":
    main()
