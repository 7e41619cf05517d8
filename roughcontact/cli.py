"""The ``roughcontact`` command: a thin wrapper over library functions (same code path as the Python API)."""
from __future__ import annotations

import argparse
import os
from importlib import metadata
import platform
import sys

from ._version import __version__


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


def _cmd_info(args) -> int:
    for key, value in info().items():
        print(f"{key:>22}: {value}")
    return 0


def _cmd_figures(args) -> int:
    from .paper import reproduce

    table = reproduce(args.output, fast=args.fast)
    print(table)
    print(f"\nfigures and tables written to {os.path.abspath(args.output)}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="roughcontact", description=__doc__)
    parser.add_argument("--version", action="version", version=f"roughcontact {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)
    commands.add_parser("info", help="versions, FFT backend, threads, numba cache dir").set_defaults(run=_cmd_info)
    figures = commands.add_parser("figures", help="reproduce the seed paper's figures and print its checkpoint table")
    figures.add_argument("--output", default="roughcontact-figures", help="output directory (PNG + CSV)")
    figures.add_argument("--fast", action="store_true", help="few points per curve (seconds)")
    figures.set_defaults(run=_cmd_figures)
    return parser


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    return args.run(args)


if __name__ == "__main__":
    sys.exit(main())
