"""Reproduce the seed paper's Figs. 3, 4, 5, 9, 10, 11 (PNG + CSV each) and print its checkpoint table.

    python experiments/paper_figures.py [--fast] [--output DIR]   # after pip install -e . (or PYTHONPATH=.)

A thin wrapper over :func:`roughcontact.paper.reproduce`; ``--fast`` uses few points per curve.
"""
import argparse

from roughcontact.paper import reproduce


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="few points per curve (seconds)")
    parser.add_argument("--output", default="out/paper_figures", help="output directory")
    args = parser.parse_args(argv)
    table = reproduce(args.output, fast=args.fast)
    print(table)
    print(f"\nfigures and checkpoints.csv written to {args.output}/")
    return table


if __name__ == "__main__":
    main()
