"""The FE fingertip sweep's cost: wall and processor time of ``roughcontact fingertip-fe``'s sweeps (needs
roughcontact[fe]).

    python studies/bench_fe.py --output out                 # default and coarse mesh, the default forces at μ0
    python studies/bench_fe.py --output out --cases coarse  # one case

Each case runs :func:`~roughcontact.fe.study.run_fingertip_study` as the command does (a fresh sweep, no store;
one process per core), and writes one row to ``bench_fe.csv``: the wall time, the processor time summed over the
runs (each run's own process, so it does not depend on how the runs share the cores; the pool's start-up is in
the wall time only), the increments and the machine's load average (1 min) before and after, since the machine
may be shared: the wall time is only as good as the cores were free. The targets: the default sweep within
2 min and the coarse one within 30 s of wall time on 2 cores.
"""
from __future__ import annotations

import argparse
import os
import time

from roughcontact.fe.geometry import MeshResolution
from roughcontact.fe.model import FingertipModel
from roughcontact.fe.study import DEFAULT_FRICTIONS, DEFAULT_NORMAL_FORCES, run_fingertip_study
from roughcontact.io.provenance import output_directory, parse_arguments, write_csv

CASES = {"default": MeshResolution(), "coarse": MeshResolution.coarse()}


def bench_row(case: str, workers: int | None) -> dict:
    load_before = os.getloadavg()[0]
    start, cpu = time.perf_counter(), time.process_time()
    study = run_fingertip_study(FingertipModel(resolution=CASES[case]), DEFAULT_NORMAL_FORCES, DEFAULT_FRICTIONS,
                                workers=workers)
    wall, own = time.perf_counter() - start, time.process_time() - cpu
    runs = study.runs
    return {"case": case, "runs": len(runs), "workers": workers or os.cpu_count(), "cores": os.cpu_count(),
            "wall_s": round(wall, 1), "cpu_runs_s": round(sum(r.cpu_seconds for r in runs), 1),
            "cpu_main_s": round(own, 1), "slowest_run_cpu_s": round(max(r.cpu_seconds for r in runs), 1),
            "increments": sum(len(r.travel) - 1 for r in runs),
            "full_slip": all(r.full_slip for r in runs),
            "load_1min_before": round(load_before, 2), "load_1min_after": round(os.getloadavg()[0], 2)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default="out")
    parser.add_argument("--cases", nargs="+", choices=sorted(CASES), default=sorted(CASES))
    parser.add_argument("--workers", type=int, default=None)
    args, provenance = parse_arguments(parser, argv, "python studies/bench_fe.py")
    output = output_directory(args.output)
    rows = []
    for case in args.cases:
        rows.append(bench_row(case, args.workers))
        print(rows[-1], flush=True)
    write_csv(output / "bench_fe.csv", rows, provenance, echo=True)


if __name__ == "__main__":
    main()
