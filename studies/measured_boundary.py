"""Which boundary a measured window needs: the same scan solved free, declared periodic and mirrored, against
the window solved inside the surface it was cut from.

    python studies/measured_boundary.py             # 4 x 4 windows of 128² (0.24 mm) from a 512² periodic surface
    python studies/measured_boundary.py --fast      # 4 x 4 windows of 32² (the test's case): seconds

A measurement is a window of a larger surface. Here the larger surface is known: a periodic self-affine
surface (``--tiles`` windows per side; default spectrum: the default scene's micro-roughness, H = 0.8, 3 µm
rms, wavelengths 60 µm to 10 µm) pressed onto a rigid flat at the mean pressure ``--pressure`` (the hard wall,
elastic half-space of E* = ``--E-star``). Each window is written to an ISO 25178-72 file
(``to_topography(...).to_x3p``), read back with ``surfaces.read_topography`` and solved alone at the same
mean pressure, with the three boundary choices a measured window allows:

* ``free``: a non-periodic grid (free surface around the window, no load outside it);
* ``periodic``: the window declared periodic as it is (a height step where its edges meet);
* ``mirrored``: ``HeightField.mirrored()``, the periodic window of twice the side with no edge step; its
  solution is mirror-symmetric, so the original quadrant is evaluated.

The reference (``inside``) is the same window's part of the solve of the whole surface. For each window the
equivalent gap d_eq (seed Eq. 25, the seed's dielectric stack, averaged over the window) and the contact
fraction A/A0 are compared with the reference. Writes ``measured_boundary.csv`` (one row per window and
variant, with its provenance) into ``--output`` and prints the mean and range of the relative errors.
"""
from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from surfaces import Grid, HeightField, self_affine
from surfaces.topography import read_topography, to_topography
from roughcontact import ElasticHalfSpace, solve_contact
from roughcontact.electrostatics import DielectricStack
from roughcontact.io import output_directory, parse_arguments, write_csv

VARIANTS = ("inside", "free", "periodic", "mirrored")
COLUMNS = ("window", "variant", "d_eq", "contact_fraction", "d_eq_error", "contact_fraction_error", "seconds")


def parent_surface(args) -> HeightField:
    """The periodic surface the windows are cut from: ``tiles`` x ``tiles`` windows of ``n``² pixels."""
    n = args.n * args.tiles
    grid = Grid((n, n), (args.tiles * args.side,) * 2, periodic=True)
    return self_affine(grid, hurst=args.hurst, rms_height=args.rms_height, long_cutoff=args.long_cutoff,
                       short_cutoff=args.short_cutoff, rng=args.seed)


def measured_windows(parent: HeightField, args, directory: Path) -> list:
    """Each window as a scan: written to an x3p file and read back (non-periodic, as instruments record it)."""
    windows = []
    for i in range(args.tiles):
        for j in range(args.tiles):
            part = parent.heights[i * args.n:(i + 1) * args.n, j * args.n:(j + 1) * args.n]
            window = HeightField(Grid((args.n, args.n), (args.side, args.side), periodic=False), part)
            path = directory / f"window_{i}_{j}.x3p"
            to_topography(window).to_x3p(str(path))
            windows.append(((i, j), read_topography(path)))
    return windows


def measure(stack, gap, contact) -> tuple:
    """(d_eq [m], A/A0) of a window's gap and contact map."""
    return stack.equivalent_gap(gap), float(contact.mean())


def solve(field: HeightField, args):
    """The hard-wall solve of ``field`` at the mean pressure, and its wall time [s]."""
    start = time.perf_counter()
    result = solve_contact(field, ElasticHalfSpace(field.grid, E_star=args.E_star), mean_pressure=args.pressure,
                           tol=args.tol)
    if not result.converged:
        raise RuntimeError(f"the solve of a {field.grid} did not converge: {result.residual:g}")
    return result, time.perf_counter() - start


def rows(args, directory: Path) -> list:
    stack = DielectricStack()
    parent = parent_surface(args)
    whole, seconds = solve(parent, args)
    table = []
    for (i, j), window in measured_windows(parent, args, directory):
        part = (slice(i * args.n, (i + 1) * args.n), slice(j * args.n, (j + 1) * args.n))
        reference = measure(stack, whole.gap[part], whole.contact[part])
        table.append(dict(window=f"{i},{j}", variant="inside", d_eq=reference[0], contact_fraction=reference[1],
                          d_eq_error=0.0, contact_fraction_error=0.0, seconds=seconds / args.tiles ** 2))
        declared = HeightField(Grid(window.grid.shape, window.grid.lengths, periodic=True), window.heights)
        for variant, field in (("free", window), ("periodic", declared), ("mirrored", window.mirrored())):
            result, seconds_variant = solve(field, args)
            quadrant = (slice(0, args.n), slice(0, args.n))
            d_eq, fraction = measure(stack, result.gap[quadrant], result.contact[quadrant])
            table.append(dict(window=f"{i},{j}", variant=variant, d_eq=d_eq, contact_fraction=fraction,
                              d_eq_error=d_eq / reference[0] - 1, contact_fraction_error=fraction / reference[1] - 1,
                              seconds=seconds_variant))
    return table


def summary(table) -> list:
    """Per variant: d_eq [µm] and A/A0 (mean and range over the windows) and their relative errors against the
    reference (mean, rms and range over the windows)."""
    lines = []
    for variant in VARIANTS:
        chosen = [row for row in table if row["variant"] == variant]
        parts = []
        for name, scale, unit in (("d_eq", 1e6, " µm"), ("contact_fraction", 1.0, "")):
            value = np.array([row[name] for row in chosen]) * scale
            error = np.array([row[f"{name}_error"] for row in chosen])
            parts.append(f"{name} {value.mean():.4g}{unit} [{value.min():.4g}, {value.max():.4g}], error "
                         f"{error.mean():+.1%} (rms {np.sqrt(np.mean(error ** 2)):.1%}, "
                         f"[{error.min():+.1%}, {error.max():+.1%}])")
        lines.append(f"{variant:9s} " + "; ".join(parts) + f"; {sum(row['seconds'] for row in chosen):.1f} s")
    return lines


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--n", type=int, default=128, help="pixels per window side")
    parser.add_argument("--tiles", type=int, default=4, help="windows per side of the periodic surface")
    parser.add_argument("--side", type=float, default=0.24e-3, help="window side [m]")
    parser.add_argument("--hurst", type=float, default=0.8, help="Hurst exponent")
    parser.add_argument("--rms-height", type=float, default=3e-6, help="rms height of the surface [m]")
    parser.add_argument("--long-cutoff", type=float, default=60e-6, help="longest wavelength [m]")
    parser.add_argument("--short-cutoff", type=float, default=10e-6, help="shortest wavelength [m]")
    parser.add_argument("--E-star", type=float, default=1e6, help="contact modulus E* [Pa]")
    parser.add_argument("--pressure", type=float, default=10e3,
                        help="mean pressure [Pa] (1 N on the seed's A0 gives 11 kPa)")
    parser.add_argument("--tol", type=float, default=1e-8, help="solver tolerance")
    parser.add_argument("--seed", type=int, default=0, help="rng seed of the surface")
    parser.add_argument("--fast", action="store_true",
                        help="windows of 32², shortest wavelength 20 µm (the test's case)")
    parser.add_argument("--output", default="out", help="directory for measured_boundary.csv")
    args, provenance = parse_arguments(parser, argv, "studies/measured_boundary.py")
    if args.fast:
        args.n, args.short_cutoff = 32, 20e-6
    with tempfile.TemporaryDirectory() as scans:
        table = rows(args, Path(scans))
    path = write_csv(output_directory(args.output) / "measured_boundary.csv", table, provenance, COLUMNS)
    print("\n".join(summary(table)))
    return path


if __name__ == "__main__":
    main()
