"""Cost of one layered field evaluation's pointwise passes against the FFT pair, on the default scene's patch.

    python studies/bench_field_passes.py                  # 256² and 512²: the pass times of docs/guide/electrostatics.md
    python studies/bench_field_passes.py --fast           # 64²: a test that it runs

A field evaluation inside the contact solve (:class:`roughcontact.electrostatics.field.FieldLaw`) is a start pass
(slope factor, air columns, Jacobi diagonal and the column-by-column start), the field's CG (one FFT pair per pass
and its pointwise updates) and an output pass (attraction, stiffness and the energy's sum). On the default scene's
patch (the hard-wall gap at the first ring's pressure at 0.5 N, one FFT thread) each is timed as the best of
``--repeat`` runs of ``--calls`` calls and printed in ms and as a multiple of the elastic body's FFT pair: the
floor of every solver step. Writes ``bench_field_passes.csv`` with its provenance into ``--output``.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from _bench import count_argument
from roughcontact import solve_contact
from roughcontact.electrostatics import EPSILON_0
from roughcontact.electrostatics.field import (FieldLaw, cg_curvature, cg_direction, cg_update, _law_outputs_into,
                                               _law_start_into)
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.study.patch import default_scene_patch

COLUMNS = ("n", "pass", "ms", "fft_pairs")


def timed(call, calls, repeat) -> float:
    """The shortest mean time [ms] of ``calls`` calls of ``call`` over ``repeat`` runs (after one untimed call)."""
    call()
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in range(calls):
            call()
        best = min(best, (time.perf_counter() - start) / calls)
    return best * 1e3


def rows_for(n, calls, repeat):
    """The pass times of the default scene's n² patch at the hard-wall gap, in ms and in FFT pairs."""
    patch = default_scene_patch(n, 0.5)
    gap = np.ascontiguousarray(solve_contact(patch.surface, patch.body, mean_pressure=patch.pressure, tol=1e-6).gap,
                               dtype=float)
    law = FieldLaw(patch.stack, 100.0, patch.body.grid, threads=1)
    field = law.field
    outputs = [np.zeros(gap.shape) for _ in range(4)]                # traction, stiffness, flux, columns
    law.evaluate(gap, *outputs)                                      # a converged flux to start from
    start = tuple(array.copy() for array in outputs[3:1:-1])         # (columns, flux) of that evaluation
    inverse_permittivity = 1.0 / (EPSILON_0 * patch.stack.eps_a)
    inverse_factor, column, inverse_diagonal, flux = law._work
    direction, product, residual, z = (np.random.default_rng(0).random(gap.shape) for _ in range(4))
    elastic, displacement = patch.body.empty(), patch.body.empty()
    elastic[...] = gap

    def cg_pass():                                                   # the pointwise work of one CG pass
        cg_curvature(direction.reshape(-1), product.reshape(-1), column.reshape(-1))
        cg_update(1e-30, direction.reshape(-1), product.reshape(-1), flux.reshape(-1), residual.reshape(-1),
                   z.reshape(-1), inverse_diagonal.reshape(-1))
        cg_direction(direction.reshape(-1), z.reshape(-1), 0.5)

    passes = {
        "elastic FFT pair": lambda: patch.body.displacement_into(elastic, displacement),
        "field FFT pair (M D)": lambda: field.apply_elastance(flux, product),
        "start pass": lambda: _law_start_into(gap, field._stencil, inverse_permittivity, field.pixel_elastance, True,
                                              *start, *law._work),
        "CG pass, pointwise": cg_pass,
        "output pass": lambda: _law_outputs_into(gap, flux, inverse_factor, column, inverse_diagonal, residual,
                                                 field._stencil, inverse_permittivity, 1e4, *outputs),
    }
    times = {name: timed(call, calls, repeat) for name, call in passes.items()}
    pair = times["elastic FFT pair"]
    return [dict(n=n, **{"pass": name}, ms=ms, fft_pairs=ms / pair) for name, ms in times.items()]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 512], help="grid sizes n (n² pixels)")
    parser.add_argument("--calls", type=count_argument, default=50, help="calls per timed run")
    parser.add_argument("--repeat", type=count_argument, default=5, help="timed runs; the shortest is kept")
    parser.add_argument("--fast", action="store_true", help="64², few calls: a test that the script runs")
    parser.add_argument("--output", default="out", help="directory for bench_field_passes.csv")
    args, provenance = parse_arguments(parser, argv, "studies/bench_field_passes.py")
    if args.fast:
        args.sizes, args.calls, args.repeat = [64], 3, 1
    rows = [row for n in args.sizes for row in rows_for(n, args.calls, args.repeat)]
    for row in rows:
        print(f"{row['n']:4d}²  {row['pass']:22s} {row['ms']:7.3f} ms  {row['fft_pairs']:5.2f} FFT pairs")
    path = write_csv(output_directory(args.output) / "bench_field_passes.csv", rows, provenance, COLUMNS)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
