"""Peer benchmark of the FFT contact solver against the FFT floor, Tamaas and ContactMechanics (a script).

    python studies/bench_contact.py                          # 256² … 2048², peers if importable
    python studies/bench_contact.py --sizes 256 512 --threads 1 --output out
    python studies/bench_contact.py --fast                   # tiny grids, no peers, seconds

(from the repository root after ``pip install -e .[bench]``). All numbers come from one run on one machine;
see ``docs/dev/benchmarks.md`` for the method, the peer conventions and measured values. Writes, into
``--output``, ``bench_contact.csv`` (every row below) and ``bench_contact.md`` (the summary table of
docs/dev/benchmarks.md: per grid the FFT pair, our time to solution and its ratio to the FFT floor, the other
starts, and the peers' times as multiples of ours), both with their provenance.

Sections (column ``section`` of the table and the CSV):

* ``fft_floor``: one rfft2 + irfft2 pair [s], pyFFTW (plan made once, reused) and ``scipy.fft``; and
  ``pyfftw-rotating``, the pyFFTW pair cycling over six arrays, i.e. reading from memory rather than cache
  as any solver's convolutions do once its fields exceed the last-level cache.
* ``solve``: our time to solution, iterations, FFT pairs per iteration ((forward + backward transforms) / 2:
  a convolution is one pair, the Parseval step length half of one), time per iteration and its ratio to
  (pairs per iteration × pyFFTW pair); seeded self-affine surface at p̄ = 0.01 E* (``--pressure``); the
  defaults (preconditioned, nested cold start), PK's uniform start, and plain Polonsky–Keer; best of
  ``--solve-repeat`` solves. Iterations and time per iteration are those on the n² grid; the time to
  solution includes the nested start's coarse solves (listed in the note).
* ``profile``: where one preconditioned pyFFTW solve from PK's start (so that every transform is on the n²
  grid) spends its time (``cProfile``): the FFT transforms, the
  Fourier-multiplier passes and the pointwise passes over the grid and the contact set, each per iteration
  and as its share of the ``solve`` ratio (the three shares add up to about that ratio).
* ``memory``: peak memory of one solve (``tracemalloc``) in float64 grid arrays, half-space object included.
* ``peer``: the same problem solved by Tamaas (``PolonskyKeerRey``) and ContactMechanics
  (``minimize_proxy``), time ratio to ours, relative differences of contact fraction and mean gap.
* ``sweep``: a 20-step load sweep (p̄ = 0.0005 … 0.01 E*) at each of ``--sweep-tol``: every step cold (the
  default nested start, and PK's uniform start) and warm-started (``load_path``'s secant predictor); the
  ratios to the nested cold sweep.
"""
from __future__ import annotations

import argparse
import cProfile
import itertools
import os
import pickle
import time
import tracemalloc

import numpy as np
import scipy.fft

from roughcontact import ElasticHalfSpace, load_path, solve_contact
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.reference.benchmark import E_STAR, LENGTH, PRESSURE, SWEEP_STEPS, rough_surface, sweep_pressures

PAIRS_PER_SAMPLE = 12    # FFT floors: best of --repeat means over this many consecutive pairs (a multiple of 6)
COLUMNS = ("section", "solver", "n", "time_s", "iterations", "fft_pairs_per_iteration",
           "time_per_iteration_s", "ratio", "contact_fraction", "mean_gap_m", "rel_diff_contact_fraction",
           "rel_diff_mean_gap", "converged", "note")


def best_time(run, repeat: int, number: int = 1) -> float:
    """Time [s] of one call of ``run()``: the best of ``repeat`` means over ``number`` consecutive calls
    (after one untimed warm-up call), as ``timeit`` does."""
    run()
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in range(number):
            run()
        times.append((time.perf_counter() - start) / number)
    return min(times)


def timed_solve(surface, half, pressure, tol, repeat, **options):
    """Best of ``repeat`` solves (after an untimed one that compiles the kernels and warms the plans): the
    result with the smallest wall time and the best time per iteration [s] from callback time stamps
    (iterations on the grid itself only: setup, the nested start's coarse solves and the final gap field
    excluded). ``options`` go to ``solve_contact``."""
    best, best_per_iteration = None, np.inf
    solve_contact(surface, half, mean_pressure=pressure, tol=1e-2, maxiter=5, warn=False)
    for _ in range(repeat):
        stamps = []
        result = solve_contact(surface, half, mean_pressure=pressure, tol=tol, **options,
                               callback=lambda state: stamps.append(time.perf_counter()))
        if len(stamps) > 1:
            best_per_iteration = min(best_per_iteration, (stamps[-1] - stamps[0]) / (len(stamps) - 1))
        if best is None or result.wall_time < best.wall_time:
            best = result
    if not np.isfinite(best_per_iteration):
        best_per_iteration = best.wall_time / max(best.iterations, 1)
    return best, best_per_iteration


SOLVE_VARIANTS = (("pyfftw", "pyfftw", {}),                                   # the defaults: preconditioned, nested
                  ("pyfftw,pk start", "pyfftw", {"cold_start": "pk"}),      # PK's uniform start
                  ("pyfftw,plain", "pyfftw", {"preconditioned": False}),
                  ("scipy", "scipy", {}))
SWEEP_VARIANTS = (("cold start", {"warm_start": False}),                     # every step nested from scratch
                  ("cold start (pk)", {"warm_start": False, "cold_start": "pk"}),
                  ("warm start", {}))                                       # load_path's secant predictor
PROFILE_GROUPS = {"transforms": ("fft.py", ("forward", "backward")),
                  "multiplier passes": ("elastic.py", ("apply_multiplier", "apply_inverse_multiplier",
                                                        "_apply_multiplier_quadratic")),
                  "pointwise passes": ("polonsky_keer.py", None)}      # None: every numba kernel (name "_...")


def time_decomposition(surface, half, pressure, tol) -> tuple:
    """Seconds per iteration that one solve spends in each of ``PROFILE_GROUPS`` (cProfile's own time of the
    functions), and the result."""
    profile = cProfile.Profile()
    profile.enable()
    result = solve_contact(surface, half, mean_pressure=pressure, tol=tol, cold_start="pk")   # all on the n² grid
    profile.disable()
    profile.create_stats()
    seconds = dict.fromkeys(PROFILE_GROUPS, 0.0)
    for (filename, _, function), (_, _, own_time, _, _) in profile.stats.items():
        for group, (module, functions) in PROFILE_GROUPS.items():
            in_group = function in functions if functions else function.startswith("_") and function != "_result"
            if filename.endswith(module) and in_group:
                seconds[group] += own_time
    return {group: value / max(result.iterations, 1) for group, value in seconds.items()}, result


def peak_memory(surface, pressure, tol) -> float:
    """Peak memory of building the half-space and solving once on ``surface``, in float64 grid arrays
    (``tracemalloc`` sees numpy's and pyFFTW's buffers)."""
    grid, heights = surface.grid, surface.heights.copy()
    # the same solve untraced first: every kernel it calls is compiled (or loaded from numba's cache) outside
    # the trace, since JIT memory is not the solver's (a shorter warm-up leaves kernels to compile inside it)
    solve_contact(heights, ElasticHalfSpace(grid, E_star=E_STAR), mean_pressure=pressure, tol=tol)
    tracemalloc.start()
    try:
        half = ElasticHalfSpace(grid, E_star=E_STAR)
        solve_contact(heights, half, mean_pressure=pressure, tol=tol)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    return peak / (surface.heights.size * 8)


def fft_floor(n: int, threads: int, planner: str, repeat: int, backend=None, rotating=False) -> dict:
    """Time [s] of one rfft2 + irfft2 pair on an n² float64 array: pyFFTW with its plans reused, scipy.fft
    (``backend``: only that one); ``rotating``: also the pyFFTW pair on arrays that are not in cache."""
    floors = {}
    real = np.random.default_rng(0).random((n, n))
    try:
        import pyfftw
    except ImportError:
        pyfftw = None
    if pyfftw is not None and backend in (None, "pyfftw"):
        a = pyfftw.empty_aligned((n, n), "float64")
        b = pyfftw.empty_aligned((n, n // 2 + 1), "complex128")
        forward = pyfftw.FFTW(a, b, axes=(0, 1), flags=(planner,), threads=threads)
        backward = pyfftw.FFTW(b, a, axes=(0, 1), direction="FFTW_BACKWARD",
                               flags=(planner, "FFTW_DESTROY_INPUT"), threads=threads)
        a[...] = real

        def pair():                                     # execute(): no normalisation pass, as in the solver
            forward.execute()
            backward.execute()
        floors["pyfftw"] = best_time(pair, repeat, number=PAIRS_PER_SAMPLE)
        if rotating:                                    # the same pair cycling over six n² arrays (48 MB at
            arrays = [pyfftw.empty_aligned((n, n), "float64") for _ in range(6)]   # 1024²): no cache reuse
            for array in arrays:
                array[...] = real
            turn = itertools.count()

            def rotating_pair():
                k = next(turn)
                forward.update_arrays(arrays[k % 6], b)
                forward.execute()
                backward.update_arrays(b, arrays[(k + 3) % 6])
                backward.execute()
            floors["pyfftw-rotating"] = best_time(rotating_pair, repeat, number=PAIRS_PER_SAMPLE)
    if backend in (None, "scipy"):
        floors["scipy"] = best_time(lambda: scipy.fft.irfft2(scipy.fft.rfft2(real, workers=threads), s=(n, n),
                                                             workers=threads), repeat, number=PAIRS_PER_SAMPLE)
    return floors


def row(**values) -> dict:
    return {column: values.get(column, "") for column in COLUMNS}


def relative_difference(value, reference) -> float:
    return abs(value - reference) / abs(reference)


def mean_gap_from(displacement_minus_height: np.ndarray, contact: np.ndarray) -> float:
    """Mean gap [m] of a peer solution: g = (u − h) − s, with s fixed by g = 0 on the contact set."""
    return float(displacement_minus_height.mean() - displacement_minus_height[contact].mean())


def solve_tamaas(heights: np.ndarray, pressure: float, tol: float):
    """Tamaas 2.x: ``basic_2d`` model with E = E*, ν = 0 (its E* = E/(1 − ν²)); heights peaks-positive as
    ours; ``solve(p̄)`` takes the mean pressure [Pa]; ``model.traction`` is the pressure (compressive > 0) and
    ``model.displacement`` the surface displacement, so g = u − h − s. Returns (time, cf, mean gap, iterations)."""
    import tamaas as tm
    n = heights.shape[0]
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [LENGTH, LENGTH], [n, n])
    model.E, model.nu = E_STAR, 0.0
    solver = tm.PolonskyKeerRey(model, heights.copy(), tol)
    start = time.perf_counter()
    solver.solve(pressure)
    seconds = time.perf_counter() - start
    pressure = np.array(model.traction).reshape(n, n)
    contact = pressure > 0
    gap = mean_gap_from(np.array(model.displacement).reshape(n, n) - heights, contact)
    return seconds, contact.mean(), gap, ""


def solve_contactmechanics(heights: np.ndarray, pressure: float, tol: float):
    """ContactMechanics: ``PeriodicFFTElasticHalfSpace(young=E*)`` (its ``young`` *is* the contact modulus),
    ``make_system(topography, substrate)``, ``minimize_proxy(external_force=p̄ L², pentol=tol·h_rms)``;
    ``jac`` are pixel forces (compressive > 0), ``x`` the displacement with the rigid offset, so
    g = x − h − offset. Returns (time, cf, mean gap, iterations)."""
    from ContactMechanics import PeriodicFFTElasticHalfSpace, make_system
    from SurfaceTopography import Topography
    n = heights.shape[0]
    substrate = PeriodicFFTElasticHalfSpace((n, n), E_STAR, physical_sizes=(LENGTH, LENGTH))
    system = make_system(Topography(heights, physical_sizes=(LENGTH, LENGTH), periodic=True), substrate)
    start = time.perf_counter()
    result = system.minimize_proxy(external_force=pressure * LENGTH**2, pentol=tol * heights.std(),
                                   maxiter=100000)
    seconds = time.perf_counter() - start
    contact = result.jac > 0
    gap = mean_gap_from(np.asarray(result.x) - heights, contact)
    return seconds, contact.mean(), gap, int(result.nit)


PEERS = {"tamaas": solve_tamaas, "ContactMechanics": solve_contactmechanics}


def peer_available(name: str) -> str:
    """'' if the peer imports, else the reason it does not."""
    try:
        if name == "tamaas":
            import tamaas as tm
            tm.set_log_level(tm.LogLevel.error)
        else:
            import ContactMechanics  # noqa: F401
            import SurfaceTopography  # noqa: F401
    except Exception as error:        # any import failure (missing compiled extension, ...) means "skip"
        return f"{type(error).__name__}: {error}"
    return ""


def run(sizes, pressure, threads, tol, planner, sweep_size, sweep_tols, repeat, solve_repeat, peers, write):
    """Run every section, calling ``write(row)`` for each result row."""
    for n in sizes:
        floors = fft_floor(n, threads, planner, repeat, rotating=True)
        for backend, seconds in floors.items():
            write(row(section="fft_floor", solver=backend, n=n, time_s=seconds, note="rfft2+irfft2 pair"))
        surface = rough_surface(n)
        ours, halves = None, {}
        for label, backend, options in SOLVE_VARIANTS:
            if backend == "pyfftw" and "pyfftw" not in floors:
                continue
            if backend not in halves:
                halves[backend] = ElasticHalfSpace(surface.grid, E_star=E_STAR, backend=backend, threads=threads,
                                                   planner_effort=planner)
            result, per_iteration = timed_solve(surface, halves[backend], pressure, tol, solve_repeat, **options)
            floors[backend] = floor = min(floors[backend], fft_floor(n, threads, planner, repeat, backend)[backend])
            pairs = result.solver.fft_pairs / max(result.iterations, 1)
            uncached = (f"; {per_iteration / (pairs * floors['pyfftw-rotating']):.3g} against the rotating pair"
                        if backend == "pyfftw" else "")
            coarse = result.solver.details["nested_iterations"]
            nested = f"; nested start: {'+'.join(map(str, coarse))} coarse iterations" if coarse else ""
            write(row(section="solve", solver=f"roughcontact[{label}]", n=n,
                      time_s=result.wall_time, iterations=result.iterations,
                      fft_pairs_per_iteration=pairs, time_per_iteration_s=per_iteration,
                      ratio=per_iteration / (pairs * floor), contact_fraction=result.contact_fraction,
                      mean_gap_m=result.mean_gap, converged=result.converged,
                      note="best of repeats; ratio = time per iteration / (FFT pairs per iteration x "
                           f"own-backend pair, best of before and after){uncached}{nested}"))
            ours = ours or result
        if "pyfftw" in halves:
            decomposition, result = time_decomposition(surface, halves["pyfftw"], pressure, tol)
            pairs = result.solver.fft_pairs / max(result.iterations, 1)
            for group, per_iteration in decomposition.items():
                write(row(section="profile", solver=group, n=n, time_s=result.wall_time, iterations=result.iterations,
                          fft_pairs_per_iteration=pairs, time_per_iteration_s=per_iteration,
                          ratio=per_iteration / (pairs * floors["pyfftw"]),
                          note="cProfile of one preconditioned pyfftw solve from PK's start (time_s: its wall "
                               "time); ratio = "
                               "this group's share of the solve ratio (per iteration / (pairs per iteration x pair))"))
        for periodic in (True, False) if n <= 1024 else (True,):      # free 2048²: a 4096² transform, minutes
            write(row(section="memory", solver="roughcontact[pyfftw]", n=n,
                      ratio=peak_memory(surface if periodic else rough_surface(n, periodic=False), pressure, tol),
                      note=f"{'periodic' if periodic else 'free surface (2n x 2n padded FFT)'}: peak traced memory "
                           "of building the half-space and one solve / one float64 n x n array"))
        for name in peers:
            reason = peer_available(name)
            if reason:
                write(row(section="peer", solver=name, n=n, note=f"not importable: {reason}"))
                continue
            seconds, fraction, gap, iterations = PEERS[name](surface.heights, pressure, tol)
            write(row(section="peer", solver=name, n=n, time_s=seconds, iterations=iterations,
                      ratio=seconds / ours.wall_time, contact_fraction=fraction, mean_gap_m=gap,
                      rel_diff_contact_fraction=relative_difference(fraction, ours.contact_fraction),
                      rel_diff_mean_gap=relative_difference(gap, ours.mean_gap),
                      note="ratio = peer time / our time (pyfftw); differences relative to ours"))
    surface = rough_surface(sweep_size)
    half = ElasticHalfSpace(surface.grid, E_star=E_STAR, threads=threads, planner_effort=planner)
    pressures = sweep_pressures(pressure)
    for sweep_tol in sweep_tols:
        sweeps = {}
        for label, options in SWEEP_VARIANTS:
            start = time.perf_counter()
            results = list(load_path(surface, half, pressures, tol=sweep_tol, **options))
            sweeps[label] = (time.perf_counter() - start, results)
        cold_time, cold = sweeps["cold start"]
        for label, (seconds, results) in sweeps.items():
            coarse = sum(sum(r.solver.details["nested_iterations"]) for r in results)
            write(row(section="sweep", solver=label, n=sweep_size,
                      time_s=seconds, iterations=sum(r.iterations for r in results),
                      ratio=cold_time / seconds, contact_fraction=results[-1].contact_fraction,
                      mean_gap_m=results[-1].mean_gap, converged=all(r.converged for r in results),
                      rel_diff_contact_fraction=max(relative_difference(r.contact_fraction, c.contact_fraction)
                                                    for r, c in zip(results, cold)),
                      rel_diff_mean_gap=max(relative_difference(r.mean_gap, c.mean_gap)
                                            for r, c in zip(results, cold)),
                      note=f"tol {sweep_tol:g}; {SWEEP_STEPS} steps to {pressure / E_STAR:g} E*; ratio = cold start "
                           f"time / this time; + {coarse} coarse-grid iterations of nested starts; differences: "
                           "max over steps, this vs cold start"))


def format_row(values: dict) -> str:
    def cell(value, width, fmt):
        return f"{value:{width}{fmt}}" if isinstance(value, (float, np.floating)) else f"{str(value):>{width}s}"
    return " ".join([f"{values['section']:9s}", f"{values['solver']:22s}", cell(values["n"], 5, "d"),
                     cell(values["time_s"], 10, ".4g"), cell(values["iterations"], 6, "d"),
                     cell(values["fft_pairs_per_iteration"], 6, ".3f"),
                     cell(values["time_per_iteration_s"], 10, ".4g"), cell(values["ratio"], 7, ".3g"),
                     cell(values["contact_fraction"], 10, ".6g"), cell(values["mean_gap_m"], 11, ".6g"),
                     cell(values["rel_diff_contact_fraction"], 9, ".2g"), cell(values["rel_diff_mean_gap"], 9, ".2g"),
                     f" {values['note']}"])


def _find(rows, section, solver, n=None):
    return next((r for r in rows if r["section"] == section and r["solver"] == solver and n in (None, r["n"])), None)


def summary_table(rows) -> str:
    """The Markdown tables of docs/dev/benchmarks.md from the rows of one run: per grid the cache-warm pyFFTW pair,
    our time to solution and its ratio to the FFT floor, the other starts and backends, the peers' times as
    multiples of ours; then the load sweeps."""
    def own(n, label):
        r = _find(rows, "solve", f"roughcontact[{label}]", n)
        return f"{r['time_s']:.4g} ({r['iterations']})" if r else ""

    def peer(n, name):
        r = _find(rows, "peer", name, n)
        return f"{r['time_s']:.3g} ({r['ratio']:.1f}×)" if r and r["time_s"] != "" else ""

    lines = ["| n | pair [ms] | roughcontact [s] (iter.) | ratio to the FFT floor | PK start [s] (iter.) "
             "| plain PK [s] (iter.) | scipy.fft [s] (iter.) | Tamaas [s] (× roughcontact) "
             "| ContactMechanics [s] (× roughcontact) |",
             "|---|---|---|---|---|---|---|---|---|"]
    for n in dict.fromkeys(r["n"] for r in rows if r["section"] == "solve"):
        pair, ours = _find(rows, "fft_floor", "pyfftw", n), _find(rows, "solve", "roughcontact[pyfftw]", n)
        lines.append(f"| {n} | {1e3 * pair['time_s']:.3g} | {own(n, 'pyfftw')} | {ours['ratio']:.2f} | "
                     f"{own(n, 'pyfftw,pk start')} | {own(n, 'pyfftw,plain')} | {own(n, 'scipy')} | "
                     f"{peer(n, 'tamaas')} | {peer(n, 'ContactMechanics')} |")
    lines += ["", "| sweep | n | time [s] | iterations | nested cold time / this |", "|---|---|---|---|---|"]
    lines += [f"| {r['solver']}, {r['note'].split(';')[0]} | {r['n']} | {r['time_s']:.3g} | {r['iterations']} | "
              f"{r['ratio']:.2f} |" for r in rows if r["section"] == "sweep"]
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024, 2048], help="grid sizes n (n²)")
    parser.add_argument("--fast", action="store_true", help="tiny grids (32², 64²), no peers: a smoke run")
    parser.add_argument("--output", default="out", help="output directory (its parent must exist)")
    parser.add_argument("--threads", type=int, default=1, help="FFT threads (ours, the floor; Tamaas via OpenMP)")
    parser.add_argument("--tol", type=float, default=1e-10,
                        help="our tol = Tamaas tol; ContactMechanics pentol = tol x rms height")
    parser.add_argument("--planner", default="FFTW_MEASURE", help="FFTW planner effort (floor and solver)")
    parser.add_argument("--sweep-size", type=int, default=512, help="grid size of the load sweep")
    parser.add_argument("--repeat", type=int, default=5, help="timed repeats of the FFT floor (best reported)")
    parser.add_argument("--pressure", type=float, default=PRESSURE / E_STAR,
                        help="mean pressure in units of E* (0.01: A/A0 ≈ 0.2 at rms slope 0.1; 0.001: ≈ 0.02)")
    parser.add_argument("--solve-repeat", type=int, default=3, help="timed solves per variant (best reported)")
    parser.add_argument("--sweep-tol", type=float, nargs="+", default=[1e-8, 1e-10],
                        help="tolerances of the load sweep")
    parser.add_argument("--no-peers", action="store_true", help="skip Tamaas and ContactMechanics")
    parser.add_argument("--peers", nargs="+", choices=list(PEERS), default=list(PEERS), help="peers to run")
    parser.add_argument("--wisdom", help="FFTW wisdom file: imported if it exists, saved at the end, so that "
                                         "repeated runs use the same FFT plans (see docs/dev/benchmarks.md)")
    args, provenance = parse_arguments(parser, argv, "python studies/bench_contact.py")
    output = output_directory(args.output)
    if args.fast:
        args.sizes, args.sweep_size, args.repeat, args.solve_repeat, args.no_peers = [32, 64], 32, 2, 1, True
        args.planner = "FFTW_ESTIMATE"
    peers = [] if args.no_peers else args.peers
    if args.wisdom and os.path.exists(args.wisdom):
        import pyfftw
        with open(args.wisdom, "rb") as stream:
            pyfftw.import_wisdom(pickle.load(stream))
    if "tamaas" in peers and peer_available("tamaas") == "":
        import tamaas as tm
        tm.initialize(args.threads)
    print(f"load average {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} {os.getloadavg()[2]:.2f}; "
          f"{os.cpu_count()} cores; threads {args.threads}; tol {args.tol:g}; planner {args.planner}")
    header = {column: column for column in COLUMNS}
    header.update(section="section", solver="solver", n="n", time_s="time [s]", iterations="iters",
                  fft_pairs_per_iteration="pair/it", time_per_iteration_s="s/iter", ratio="ratio",
                  contact_fraction="A/A0", mean_gap_m="<g> [m]", rel_diff_contact_fraction="dA/A",
                  rel_diff_mean_gap="d<g>/<g>", note="note")
    print(format_row(header))
    rows = []

    def write(values):                              # the CSV is rewritten after every row: a long run that is
        rows.append(values)                         # interrupted keeps what it measured
        write_csv(output / "bench_contact.csv", rows, provenance, COLUMNS)
        print(format_row(values), flush=True)
    run(args.sizes, args.pressure * E_STAR, args.threads, args.tol, args.planner, args.sweep_size,
        args.sweep_tol, args.repeat, args.solve_repeat, peers, write)
    table = summary_table(rows)
    (output / "bench_contact.md").write_text(f"<!-- {provenance.line} -->\n\n{table}")
    print(f"\n{table}")
    if args.wisdom:
        import pyfftw
        with open(args.wisdom, "wb") as stream:
            pickle.dump(pyfftw.export_wisdom(), stream)
    print(f"load average at the end {os.getloadavg()[0]:.2f}; written to {output}/bench_contact.csv and .md")


if __name__ == "__main__":
    main()
