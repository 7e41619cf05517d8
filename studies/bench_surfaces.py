"""Benchmark of the surface generators: wall time and peak memory (a script, not a test).

    python studies/bench_surfaces.py            # self-affine 4096², fingerprint 2048²
    python studies/bench_surfaces.py --fast     # 512² (a quick check that the script runs)

(run from the repository root after ``pip install -e .``).

Time is the best of ``--repeat`` runs without tracing; peak memory is measured in a separate traced run with
``tracemalloc`` (numpy reports its buffers to it) and printed in units of one float64 grid array.
Design targets: self-affine 4096² < 5 s, fingerprint 2048² < 20 s on a 2-core machine (measured values:
docs/guide/surfaces.md).
"""
from __future__ import annotations

import argparse
import time
import tracemalloc

import surfaces


def measure(make, repeat: int) -> tuple:
    """``(best wall time [s], peak traced memory [bytes])`` of ``make()``."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        make()
        times.append(time.perf_counter() - start)
    tracemalloc.start()
    make()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return min(times), peak


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fast", action="store_true", help="small grids (512²)")
    parser.add_argument("--repeat", type=int, default=2, help="timed runs per case (best is reported)")
    args = parser.parse_args(argv)
    n_rough = 512 if args.fast else 4096
    n_print = 256 if args.fast else 2048
    cases = []
    rough_grid = surfaces.Grid((n_rough, n_rough), (4e-3, 4e-3), periodic=True)
    cases.append((f"self_affine {n_rough}² periodic", rough_grid,
                  lambda: surfaces.self_affine(rough_grid, hurst=0.8, rms_slope=0.2, rolloff=1e-3, rng=0)))
    window_grid = surfaces.Grid((n_rough // 2, n_rough // 2), (2e-3, 2e-3), periodic=False)
    cases.append((f"self_affine {n_rough // 2}² non-periodic", window_grid,
                  lambda: surfaces.self_affine(window_grid, hurst=0.8, rms_slope=0.2, rolloff=1e-3, rng=0)))
    print_grid = surfaces.Grid((n_print, n_print), (10e-3, 10e-3), periodic=False)
    cases.append((f"fingerprint {n_print}² left_loop", print_grid,
                  lambda: surfaces.fingerprint(print_grid, pattern="left_loop", rng=0)))
    print(f"{'case':36s} {'time [s]':>9s} {'peak [MB]':>10s} {'peak [grid arrays]':>19s}")
    for name, grid, make in cases:
        seconds, peak = measure(make, args.repeat)
        grid_array = grid.size * 8
        print(f"{name:36s} {seconds:9.2f} {peak / 1e6:10.0f} {peak / grid_array:19.1f}")


if __name__ == "__main__":
    main()
