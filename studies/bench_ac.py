"""Cost of one frequency's AC field solve against the dielectric field solve on the same gap.

    python studies/bench_ac.py                      # 256²: the table of docs/guide/ac_drive.md
    python studies/bench_ac.py --sizes 256 512 --repeat 5 --output out
    python studies/bench_ac.py --fast               # 64², seconds

The gap is the default scene's patch (realisation 0) solved against the hard wall at the apparent pressure of
1 N. On it, with the operators built once (FFT plans, multipliers: the situation inside a contact solve), each
solve starts cold and runs to ``--tol``:

* ``dielectric``: :class:`StackField` (CG, one real FFT pair per iteration), the reference;
* ``cocg``: :class:`ACStackField` at each of ``--frequencies`` and DC (COCG, two real FFT pairs per iteration);
* ``gmres-block`` / ``bicgstab-block``: the same complex system as the real 2×2 block system
  [[Re A, −Im A], [Im A, Re A]] (nonsymmetric), by scipy's GMRES (restart 30) and BiCGSTAB with the same Jacobi
  preconditioner, through the same operator (two real FFT pairs per product);
* ``fft-pair-real`` / ``fft-pair-complex``: one real FFT pair of the backend against one complex (c2c) pyFFTW pair
  on the same n² points, the reason M(ω) is applied as two real pairs.

Printed per solve: iterations, real FFT pairs and CPU time (best of ``--repeat``; CPU, not wall time, so that the
ratios hold on a shared machine: run with one FFT thread) and their ratios to the dielectric solve's, and the
relative residual reached. Writes ``bench_ac.csv`` with its provenance into ``--output``.
"""
from __future__ import annotations

import argparse
import time

import numpy as np
from scipy.sparse.linalg import LinearOperator, bicgstab, gmres

from _bench import best_of, count_argument
from roughcontact import solve_contact
from roughcontact.electrostatics import ACStackField, StackField
from roughcontact.fft import default_planner, make_backend
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.study.patch import default_scene_patch

COLUMNS = ("n", "method", "frequency_Hz", "iterations", "fft_pairs", "time_s", "fft_pair_ratio", "time_ratio",
           "residual")


def hard_wall_gap(n: int) -> tuple:
    """(stack, grid, gap [m]) of the default scene's patch on n² pixels against the hard wall at 1 N."""
    patch = default_scene_patch(n, 1.0)
    result = solve_contact(patch.surface, patch.body, mean_pressure=patch.pressure)
    return patch.stack, patch.grid, result.gap


def block_solve(field: ACStackField, columns: np.ndarray, method: str, tol: float) -> tuple:
    """(iterations, relative residual) of the real 2×2 block form of (M(ω) + R) D̂ = 1 by scipy's ``method``."""
    n = columns.size
    complex_product = np.empty(columns.shape, complex)
    inverse_diagonal = (1.0 / (field.pixel_elastance + columns)).reshape(-1)

    def product(vector):
        flux = (vector[:n] + 1j * vector[n:]).reshape(columns.shape)
        field.apply_elastance(flux, complex_product)
        out = (complex_product + columns * flux).reshape(-1)
        return np.concatenate([out.real, out.imag])

    def preconditioner(vector):
        out = inverse_diagonal * (vector[:n] + 1j * vector[n:])
        return np.concatenate([out.real, out.imag])

    operator = LinearOperator((2 * n, 2 * n), matvec=product, dtype=float)
    jacobi = LinearOperator((2 * n, 2 * n), matvec=preconditioner, dtype=float)
    right = np.concatenate([np.ones(n), np.zeros(n)])
    counter = []
    solver = {"gmres-block": lambda: gmres(operator, right, M=jacobi, rtol=tol, restart=30, maxiter=200,
                                           callback=counter.append, callback_type="pr_norm"),
              "bicgstab-block": lambda: bicgstab(operator, right, M=jacobi, rtol=tol, maxiter=2000,
                                                 callback=counter.append)}[method]
    solution, _ = solver()
    residual = np.linalg.norm(right - product(solution)) / np.sqrt(n)
    return len(counter), float(residual)


def fft_pair_times(n: int, repeat: int) -> tuple:
    """CPU time [s] of one real FFT pair (the backend's plans) and of one complex pair (pyFFTW c2c, one thread)
    on n² points, each the best of ``repeat`` runs of 100 pairs."""
    import pyfftw
    real = make_backend("pyfftw", (n, n), threads=1)
    buffer = real.empty()
    buffer[...] = np.random.default_rng(0).random((n, n))
    data = pyfftw.empty_aligned((n, n), complex)
    spectrum = pyfftw.empty_aligned((n, n), complex)
    flags = (default_planner(),)
    forward = pyfftw.FFTW(data, spectrum, axes=(0, 1), flags=flags, threads=1)
    backward = pyfftw.FFTW(spectrum, data, axes=(0, 1), direction="FFTW_BACKWARD", flags=flags, threads=1)
    data[...] = buffer

    def real_pairs():
        for _ in range(100):
            real.forward(buffer)
            real.backward(buffer)

    def complex_pairs():
        for _ in range(100):
            forward()
            backward()

    return tuple(best_of(pairs, repeat, clock=time.process_time)[1] / 100 for pairs in (real_pairs, complex_pairs))


def rows_for(n: int, args) -> list:
    stack, grid, gap = hard_wall_gap(n)
    dielectric = StackField(stack, grid)
    dielectric.solve_flux(gap, tol=args.tol)                                      # compiles, warms the plans
    (flux, iterations, residual), seconds = best_of(lambda: dielectric.solve_flux(gap, tol=args.tol),
                                                    args.repeat, clock=time.process_time)
    reference = (iterations + 1, seconds)
    rows = [dict(n=n, method="dielectric", frequency_Hz=float("inf"), iterations=iterations, fft_pairs=iterations + 1,
                 time_s=seconds, residual=residual)]
    for frequency in (*args.frequencies, 0.0):
        field = ACStackField(stack, grid, frequency)
        field.solve_flux(gap, tol=args.tol)
        field.fft_pairs = 0
        (flux, iterations, residual), seconds = best_of(lambda: field.solve_flux(gap, tol=args.tol), args.repeat,
                                                        clock=time.process_time)
        rows.append(dict(n=n, method="cocg", frequency_Hz=frequency, iterations=iterations,
                         fft_pairs=field.fft_pairs // args.repeat, time_s=seconds, residual=residual))
        if frequency in args.block_frequencies:
            columns = field.column_elastance(gap)
            for method in ("gmres-block", "bicgstab-block"):
                field.fft_pairs = 0
                (iterations, residual), seconds = best_of(lambda: block_solve(field, columns, method, args.tol),
                                                          args.repeat, clock=time.process_time)
                rows.append(dict(n=n, method=method, frequency_Hz=frequency, iterations=iterations,
                                 fft_pairs=field.fft_pairs // args.repeat, time_s=seconds, residual=residual))
    real_pair, complex_pair = fft_pair_times(n, args.repeat)
    rows += [dict(n=n, method="fft-pair-real", fft_pairs=1, time_s=real_pair),
             dict(n=n, method="fft-pair-complex", fft_pairs=1, time_s=complex_pair)]
    for row in rows:
        row.update(fft_pair_ratio=row["fft_pairs"] / reference[0], time_ratio=row["time_s"] / reference[1])
    print(f"{n:4d}² one complex FFT pair costs {complex_pair / real_pair:.2f} real pairs "
          f"({complex_pair * 1e3:.3f} against {real_pair * 1e3:.3f} ms CPU)")
    for row in rows[:-2]:
        print(f"{n:4d}² {row['method']:15s} {row['frequency_Hz']:9.4g} Hz  {row['iterations']:4d} it  "
              f"{row['fft_pairs']:5d} FFT pairs x{row['fft_pair_ratio']:.2f}  {row['time_s'] * 1e3:8.2f} ms CPU "
              f"x{row['time_ratio']:.2f}  residual {row['residual']:.1e}", flush=True)
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[256], help="grid sizes n (n² pixels)")
    parser.add_argument("--frequencies", type=float, nargs="+", default=[10.0, 100.0, 1000.0, 10000.0],
                        help="drive frequencies [Hz] (DC is always added)")
    parser.add_argument("--block-frequencies", type=float, nargs="*", default=[1000.0],
                        help="frequencies at which the real 2x2 block form is solved too")
    parser.add_argument("--tol", type=float, default=1e-10, help="relative residual of every field solve")
    parser.add_argument("--repeat", type=count_argument, default=3, help="timings per solve; the best is kept")
    parser.add_argument("--fast", action="store_true", help="64², one timing: a test that the script runs")
    parser.add_argument("--output", default="out", help="directory for bench_ac.csv")
    args, provenance = parse_arguments(parser, argv, "studies/bench_ac.py")
    if args.fast:
        args.sizes, args.repeat = [64], 1
    directory = output_directory(args.output)
    rows = [row for n in args.sizes for row in rows_for(n, args)]
    write_csv(directory / "bench_ac.csv", rows, provenance, COLUMNS)


if __name__ == "__main__":
    main()
