"""The FE table that the friction law reads (``roughcontact/fe/fingertip_fe_summary.csv``): the default sweep at
μ0 and the friction levels of electroadhesion (a script; needs roughcontact[fe]).

    python studies/fe_friction_table.py --output out            # then copy out/fingertip_fe_summary.csv

Runs on the default mesh: the command's default sweep (f_N = 25–400 N/m at μ0 = 0.26, the 0 V friction level and
the exponent of ξ) and, for the contact friction μ_eff = μ0 (1 + F_el/F_N) under voltage, μ = 0.35 (the seed's FE),
0.5, 1, 1.5, 2 and 2.5 at f_N = 50, 100, 200 N/m, which bracket the finger's 0.5–2 N (f_N = F_N/w = 53–163 N/m,
``roughcontact.fe.feed``) and the default scene's μ_eff up to 2.15. One summary table of all runs (the format of
``roughcontact fingertip-fe``); finished runs are kept in ``out/runs`` (re-running resumes).
"""
from __future__ import annotations

import argparse

from roughcontact.fe.model import FingertipModel
from roughcontact.fe.store import RunStore
from roughcontact.fe.study import (DEFAULT_FRICTIONS, DEFAULT_NORMAL_FORCES, SUMMARY_CSV, FingertipStudy,
                                   run_fingertip_study)
from roughcontact.io.provenance import output_directory, parse_arguments, write_csv

#: The friction levels of electroadhesion and the forces per unit width at which they are run [N/m].
FRICTIONS = (0.35, 0.5, 1.0, 1.5, 2.0, 2.5)
FRICTION_FORCES = (50.0, 100.0, 200.0)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default="out")
    parser.add_argument("--workers", type=int, default=None)
    args, provenance = parse_arguments(parser, argv, "python studies/fe_friction_table.py")
    output = output_directory(args.output)
    store, model = RunStore(output / "runs"), FingertipModel()
    sweeps = [run_fingertip_study(model, DEFAULT_NORMAL_FORCES, DEFAULT_FRICTIONS, workers=args.workers,
                                  store=store, progress=True),
              run_fingertip_study(model, FRICTION_FORCES, FRICTIONS, workers=args.workers, store=store,
                                  progress=True)]
    study = FingertipStudy(model, tuple(run for sweep in sweeps for run in sweep.runs))
    write_csv(output / SUMMARY_CSV, study.summary_rows(), provenance, echo=True)


if __name__ == "__main__":
    main()
