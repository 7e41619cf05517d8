"""Cost of a one-at-a-time parameter study against the single studies it is made of.

    python studies/bench_variants.py --fast                  # 32² patches, 2 loads, 0 and 150 V: seconds
    python studies/bench_variants.py --preset draft          # the default scene's loads and voltages

The study varies k = 2 inputs of the scene (default scene, or ``--scene``; ``--fast`` the tiny test scene with
one realisation) at two levels each: the skin layer's modulus at 1e7 Pa (the default scene's own value, so that
variant is the baseline) and 1e9 Pa, ε_sc at the ends of its literature range (1e3, 1e4): 2k + 1 = 5 variants.
It runs in this process (one worker: the process CPU time is the study's) after one point that compiles the
kernels, untimed; then each variant runs alone as a single study without a task store. The bar: the study
costs at most 2k + 1 single studies, less where its variants share tasks (here the variant equal to the
baseline solves nothing). Contact solves and tasks do not depend on the machine; CPU seconds do. Writes
``bench_variants.csv`` with its provenance into ``--output``.
"""
from __future__ import annotations

import argparse
import dataclasses
import time

from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.study.run import run_study
from roughcontact.study.variant_run import run_variants
from roughcontact.study.variants import load_variant_study

COLUMNS = ("run", "variants", "tasks", "solves", "cpu_s", "solves_per_single_study", "budget_solves")
VARY = """
[vary]
"skin.layer_E_star" = [1e7, 1e9]
"screen.eps_sc" = "literature"
"""
FAST = """\
[loads]
normal_forces = [0.5, 2.0]
voltages = [0.0, 150.0]
[roughness]
long_cutoff = 1.5e-4
[presets.draft]
grid = 32
realisations = 1
tolerance = 1e-6
pixels_per_cutoff = 3.0
"""


def measure(args) -> list:
    """The rows of the table: the parameter study, the single studies of its variants and the budget."""
    text = FAST if args.fast else (open(args.scene, encoding="utf-8").read() if args.scene else "")
    study = load_variant_study(text=text + VARY, preset="draft" if args.fast else args.preset)
    warm = dataclasses.replace(study.base, loads=dataclasses.replace(
        study.base.loads, normal_forces=study.base.loads.normal_forces[:1], voltages=study.base.loads.voltages[-1:]))
    run_study(warm, workers=1)                              # compile the kernels, untimed
    start = time.process_time()
    varied = run_variants(study, workers=1)
    cpu = time.process_time() - start
    singles, single_cpu = [], 0.0
    for variant in study.variants:
        start = time.process_time()
        singles.append(run_study(variant.scene, workers=1))
        single_cpu += time.process_time() - start
    per_study = singles[0].solves
    k = len(study.inputs)
    return [{"run": "parameter study", "variants": len(study.variants), "tasks": varied.tasks,
             "solves": varied.solves, "cpu_s": cpu, "solves_per_single_study": per_study,
             "budget_solves": (2 * k + 1) * per_study},
            {"run": "single studies", "variants": len(singles), "tasks": sum(len(s.plan.tasks) for s in singles),
             "solves": sum(s.solves for s in singles), "cpu_s": single_cpu, "solves_per_single_study": per_study,
             "budget_solves": (2 * k + 1) * per_study}]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--scene", default=None, help="scene file without [vary] (default: the default scene)")
    parser.add_argument("--preset", default="draft", help="accuracy preset")
    parser.add_argument("--fast", action="store_true", help="the tiny scene: 32² patches, 2 loads, 0 and 150 V")
    parser.add_argument("--output", default="bench-variants", help="output directory")
    args, provenance = parse_arguments(parser, argv, "studies/bench_variants.py")
    rows = measure(args)
    write_csv(output_directory(args.output) / "bench_variants.csv", rows, provenance, COLUMNS, echo=True)
    return rows


if __name__ == "__main__":
    main()
