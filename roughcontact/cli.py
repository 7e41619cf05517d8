"""The roughcontact command: a thin wrapper over the library (the same code path as the Python API).

A user's mistake (an output path that is a file or whose parent does not exist, a bad value) ends with exit
code 2 and a one-line message, never a traceback.
"""
from __future__ import annotations

import argparse
import os
from importlib import metadata
import platform
import sys

from ._version import __version__

#: Default output directory of "roughcontact figures" (ignored by git in this repository).
DEFAULT_FIGURES_OUTPUT = "roughcontact-figures"
#: Exit code of a user's mistake (as argparse's own).
USAGE_ERROR = 2


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors: "roughcontact figures: error: ... (see --help)", exit code 2."""

    def error(self, message):
        self.exit(USAGE_ERROR, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def _package_version(name: str) -> str:
    """Installed version of a distribution, without importing it (numba would JIT-initialise)."""
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "not installed"


def info() -> dict:
    """Versions, FFT backend, thread settings and numba cache location of this installation."""
    numba_cache = os.environ.get("NUMBA_CACHE_DIR") or "next to each module's __pycache__ (numba default)"
    fft_backend = "pyfftw" if _package_version("pyfftw") != "not installed" else "scipy.fft (pyfftw missing)"
    return {
        "roughcontact": __version__,
        "python": platform.python_version(),
        **{name: _package_version(name) for name in ("numpy", "scipy", "numba", "pyfftw", "matplotlib")},
        "default FFT backend": fft_backend,
        "cores (os.cpu_count)": os.cpu_count(),
        "numba threads": os.environ.get("NUMBA_NUM_THREADS", "numba default (all cores)"),
        "numba cache dir": numba_cache,
        "numba JIT disabled": os.environ.get("NUMBA_DISABLE_JIT", "0") == "1",
    }


def _cmd_info(args, provenance) -> int:
    for key, value in info().items():
        print(f"{key:>22}: {value}")
    return 0


def _cmd_figures(args, provenance) -> int:
    from .paper import reproduce
    from .provenance import output_directory

    output = output_directory(args.output)
    table = reproduce(output, provenance)
    print(table)
    print(f"\nfigures and tables written to {output.resolve()}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    formatter = argparse.ArgumentDefaultsHelpFormatter
    parser = _Parser(prog="roughcontact", description=__doc__.splitlines()[0], formatter_class=formatter)
    parser.add_argument("--version", action="version", version=f"roughcontact {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    commands.add_parser("info", help="versions, FFT backend, threads, numba cache dir",
                        description="Print versions, the FFT backend, thread settings and the numba cache directory.",
                        formatter_class=formatter).set_defaults(run=_cmd_info)
    figures = commands.add_parser("figures", help="reproduce the seed paper's figures and print its checkpoint table",
                                  description="Write Figs. 3, 4, 5, 9, 10, 11 of Hess & Forsbach (2020) as PNG + CSV "
                                              "and checkpoints.csv, each file with its provenance, and print the "
                                              "checkpoint table.", formatter_class=formatter)
    figures.add_argument("--output", default=DEFAULT_FIGURES_OUTPUT,
                         help="output directory; created if missing, but its parent must exist")
    figures.set_defaults(run=_cmd_figures)
    return parser


def main(argv=None) -> int:
    from .provenance import OutputPathError, parse_arguments

    parser = build_parser()
    args, provenance = parse_arguments(parser, argv, "roughcontact")
    try:
        return args.run(args, provenance)
    except OutputPathError as error:
        parser.exit(USAGE_ERROR, f"roughcontact {args.command}: error: {error}\n")
    except OSError as error:                      # e.g. the disk filled up while writing
        parser.exit(USAGE_ERROR, f"roughcontact {args.command}: error: cannot write {error.filename}: "
                                 f"{error.strerror}\n")


if __name__ == "__main__":
    sys.exit(main())
