"""Pull-off of an adhesive sphere under load control against Maugis–Dugdale, across the DMT–JKR transition.

    python studies/adhesive_sphere.py                        # λ = 0.1 … 3 on 128², 256², 512²
    python studies/adhesive_sphere.py --fast                 # λ = 0.3 on 64², 128²: seconds

A paraboloid h = −r²/(2R) (R = 1 m, E* = 1 Pa, w = 1e-3 J/m²: the units are arbitrary) in a periodic cell of side
``--cell`` (6.6 JKR zero-load contact radii by default), the Dugdale law (``MaugisDugdale``) with σ0 set by
Maugis' λ. Each solve starts from the zero-load equilibrium and retracts in steps of 0.1 π w R until the sphere
detaches (``roughcontact.solvers.pull_off``). The pull-off load P̄ = F/(π w R) is compared with Maugis' (1992)
analytic curve (``roughcontact.reference.maugis_dugdale_pull_off``); the error falls to first order in the
pixel size, so the last two grids also give a Richardson extrapolation. Writes ``adhesive_sphere.csv`` (with
its provenance) into ``--output``.
"""
from __future__ import annotations

import argparse

import numpy as np

from surfaces import Grid, HeightField
from roughcontact import ContactProblem, ElasticHalfSpace, MaugisDugdale
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.reference import maugis_cohesive_stress, maugis_dugdale_pull_off
from roughcontact.solvers import pull_off

RADIUS, E_STAR, WORK = 1.0, 1.0, 1e-3          # R [m], E* [Pa], w [J/m²]
COLUMNS = ("maugis_lambda", "n", "cell", "pixel", "pull_off", "pull_off_maugis", "relative_error",
           "contact_radius_at_pull_off", "solves")


def sphere_problem(n, cell, maugis_lambda):
    """The paraboloid on an n² periodic cell with the Dugdale law of Maugis parameter λ."""
    grid = Grid((n, n), (cell, cell), periodic=True)
    x = (np.arange(n) - n / 2) * cell / n
    surface = HeightField(grid, -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * RADIUS))
    cohesive_stress = maugis_cohesive_stress(maugis_lambda, WORK, RADIUS, E_STAR)
    return ContactProblem(surface, ElasticHalfSpace(grid, E_star=E_STAR),
                          MaugisDugdale(WORK, WORK / cohesive_stress))


def normalised_pull_off(n, cell, maugis_lambda):
    """(P̄ = F/(π w R) at pull-off, contact radius there [m], solves) of the BEM."""
    problem = sphere_problem(n, cell, maugis_lambda)
    start = problem.solve(mean_pressure=0.0)
    found = pull_off(problem, start, step=0.1 * np.pi * WORK * RADIUS / cell ** 2, tol=1e-2)
    radius = np.sqrt(found.last_attached.contact_fraction * cell ** 2 / np.pi)
    return found.force / (np.pi * WORK * RADIUS), radius, found.solves


def rows(lambdas, sizes, cell):
    table = []
    for maugis_lambda in lambdas:
        reference = maugis_dugdale_pull_off(maugis_lambda)
        values = []
        for n in sizes:
            value, radius, solves = normalised_pull_off(n, cell, maugis_lambda)
            values.append(value)
            table.append(dict(maugis_lambda=maugis_lambda, n=n, cell=cell, pixel=cell / n, pull_off=value,
                              pull_off_maugis=reference, relative_error=value / reference - 1,
                              contact_radius_at_pull_off=radius, solves=solves))
        extrapolated = 2 * values[-1] - values[-2]            # first order in the pixel size
        table.append(dict(maugis_lambda=maugis_lambda, n="richardson", cell=cell, pixel=0.0,
                          pull_off=extrapolated, pull_off_maugis=reference,
                          relative_error=extrapolated / reference - 1))
    return table


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--lambdas", type=float, nargs="+", default=[0.1, 0.3, 1.0, 3.0], help="Maugis λ values")
    parser.add_argument("--sizes", type=int, nargs="+", default=[128, 256, 512], help="grid sizes n, coarse first")
    parser.add_argument("--cell", type=float, default=1.6, help="cell side [m] (R = 1 m)")
    parser.add_argument("--fast", action="store_true", help="λ = 0.3 on 64² and 128² (the test's case)")
    parser.add_argument("--output", default="out", help="directory for adhesive_sphere.csv")
    args, provenance = parse_arguments(parser, argv, "studies/adhesive_sphere.py")
    if args.fast:
        args.lambdas, args.sizes = [0.3], [64, 128]
    table = rows(args.lambdas, args.sizes, args.cell)
    path = write_csv(output_directory(args.output) / "adhesive_sphere.csv", table, provenance, COLUMNS, echo=True)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
