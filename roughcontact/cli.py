"""The roughcontact command: a thin wrapper over the library (the same code path as the Python API).

A user's mistake (an output path that is a file or whose parent does not exist, a bad value) ends with exit
code 2 and a one-line message, never a traceback; Ctrl-C ends with exit code 130 and one line; a warning is
one line.
"""
from __future__ import annotations

import argparse
import os
from concurrent.futures.process import BrokenProcessPool
from importlib import metadata
import platform
import sys
import time
import warnings

from . import study
from ._version import __version__
from .fe import command as fingertip_fe        # FElupe itself is imported only when the command runs
from .io.provenance import OutputPathError, output_directory, parse_arguments
from .paper import reproduce

#: Default output directory of "roughcontact figures" (ignored by git in this repository).
DEFAULT_FIGURES_OUTPUT = "roughcontact-figures"
#: Default results directory of "roughcontact run" (ignored by git in this repository).
DEFAULT_RUN_OUTPUT = "roughcontact-results"
#: Exit code of a user's mistake (as argparse's own).
USAGE_ERROR = 2
#: Exit code of a command interrupted by Ctrl-C (128 + SIGINT, as a shell reports it).
INTERRUPTED = 130


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
    output = output_directory(args.output)
    table = reproduce(output, provenance)
    print(table)
    print(f"\nfigures and tables written to {output.resolve()}")
    return 0


def _cmd_scene(args, provenance) -> int:
    path = getattr(args, "scene", None)
    try:
        if path is not None and study.has_variation(path):
            variants = study.load_variant_study(path)
            study.plan_variants(variants)       # every variant's checks of roughcontact run, before any solve
            return _show_variant_study(variants, args.show, path)
        scene = study.load_scene(path)
        study.checked_plan(scene)               # the patch's and the drive's checks of roughcontact run
    except (ValueError, ImportError) as error:
        print(f"roughcontact scene: error: {error}", file=sys.stderr)
        return USAGE_ERROR
    if args.show:
        print(scene.to_toml() if hasattr(args, "scene") else study.DEFAULT_SCENE_TOML, end="")
    else:
        frequencies = scene.screen.frequency or ()
        sweep = f" x {len(frequencies)} drive frequencies" if frequencies else ""
        print(f"{getattr(args, 'scene', 'the default scene')}: valid (preset {scene.study.preset}, "
              f"{len(scene.loads.normal_forces)} loads x {len(scene.loads.voltages)} voltages{sweep})")
    return 0


def _show_variant_study(variants, show: bool, path) -> int:
    """``roughcontact scene`` of a parameter study: its TOML, or a line saying what it varies."""
    if show:
        print(variants.to_toml(), end="")
    else:
        base = variants.base
        print(f"{path}: valid parameter study (preset {base.study.preset}, {len(base.loads.normal_forces)} loads x "
              f"{len(base.loads.voltages)} voltages; design {variants.design}, {len(variants.variants)} variants "
              f"of {', '.join(variants.variation.names)})")
    return 0


def _cmd_run(args, provenance) -> int:
    start = time.perf_counter()
    path, preset, target = (getattr(args, name, None) for name in ("scene", "preset", "target_error"))
    try:
        if path is not None and study.has_variation(path):
            variants = study.load_variant_study(path, preset=preset, target_error=target)
            output = output_directory(args.out)
            return _report_variants(study.run_variants(variants, output, progress=True, **_executor(args)), output,
                                    provenance, start)
        scene = study.scene_at_preset(path, preset, target)
        output = output_directory(args.out)
        result = study.run_study(scene, output, progress=True, **_executor(args))
    except (ValueError, ImportError) as error:   # a scene key or parameter the preset cannot resolve, another
        print(f"roughcontact run: error: {error}", file=sys.stderr)        # scene, dask not installed
        return USAGE_ERROR
    except RuntimeError as error:
        if not isinstance(error.__cause__, BrokenProcessPool):
            raise
        print(f"roughcontact run: error: {error}", file=sys.stderr)        # a worker was killed
        return 1
    written = study.write_results(result, output, provenance, time.perf_counter() - start)
    print(f"{result.computed} points computed ({result.solves} contact solves), "
          f"{result.array('seconds').size - result.computed} resumed; "
          f"{written['seconds']:.0f} s")
    print(f"report, figures and tables written to {output.resolve()}")
    return 0


def _executor(args) -> dict:
    """``workers``, ``dask`` and ``tasks`` of a run from its flags, the task directory checked (and created) as
    ``--tasks``."""
    tasks = getattr(args, "tasks", None)
    return {"workers": getattr(args, "workers", None), "dask": getattr(args, "dask", None),
            "tasks": None if tasks is None else output_directory(tasks, "--tasks")}


def _report_variants(result, output, provenance, start) -> int:
    """Write a parameter study's results and say what was solved."""
    written = study.write_results(result, output, provenance, time.perf_counter() - start)
    print(f"{len(result.variants)} variants ({result.design}): {result.computed} of {result.tasks} distinct tasks "
          f"solved ({result.solves} contact solves), {result.tasks - result.computed} read back; "
          f"{written['seconds']:.0f} s")
    print(f"report, figures and tables written to {output.resolve()}")
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
    run = commands.add_parser("run", help="the multiscale fingerpad study of a scene: d_eq and A_R vs load and voltage",
                              description="Solve ridge + micro-roughness patches with the electrostatic attraction "
                                          "for every load and voltage of the scene, feed d_eq and A_R into the seed's "
                                          "friction law beside its fitted model, and write results.nc, CSV tables, "
                                          "PNG figures and report.md. Re-running into the same directory resumes.",
                              formatter_class=formatter)
    run.add_argument("scene", nargs="?", default=argparse.SUPPRESS,
                     help="scene TOML file (default: the embedded scene, see 'roughcontact scene --show')")
    run.add_argument("--preset", choices=("draft", "standard", "reference", "auto"), default=argparse.SUPPRESS,
                     help="accuracy preset (default: the scene's study.preset); auto: the cheapest measured setting "
                          "meeting --target-error (docs/guide/presets.md)")
    run.add_argument("--target-error", metavar="ERROR", default=argparse.SUPPRESS,
                     help="with --preset auto: the largest error accepted, e.g. 10%% or 0.1; refused below the "
                          "reference setting's own error (the floor, docs/guide/presets.md)")
    run.add_argument("--out", default=DEFAULT_RUN_OUTPUT,
                     help="results directory; created if missing, but its parent must exist")
    run.add_argument("--tasks", metavar="DIR", default=argparse.SUPPRESS,
                     help="a task directory that runs of several scenes share: a task whose inputs another run has "
                          "solved is read back (default: OUT/tasks)")
    executors = run.add_mutually_exclusive_group()
    executors.add_argument("--workers", type=int, default=argparse.SUPPRESS,
                           help="processes of the local pool, each with cores/N FFT threads; 1 runs in this "
                                "process (default: one per core)")
    executors.add_argument("--dask", metavar="ADDRESS", default=argparse.SUPPRESS,
                           help="run the tasks on the dask.distributed scheduler at ADDRESS (tcp://host:port); "
                                "needs roughcontact[parallel]")
    run.set_defaults(run=_cmd_run)
    scene = commands.add_parser("scene", help="validate a scene file or print the default scene as TOML",
                                description="Validate a scene TOML file (errors name the key and its line); "
                                            "--show prints it, or the commented default scene, as TOML.",
                                formatter_class=formatter)
    scene.add_argument("scene", nargs="?", default=argparse.SUPPRESS,
                       help="scene TOML file (default: the embedded scene)")
    scene.add_argument("--show", action="store_true", help="print the scene as TOML")
    scene.set_defaults(run=_cmd_scene)
    fingertip_fe.add_arguments(commands.add_parser(
        "fingertip-fe", help="the seed's FE fingertip: L(f_T), Eq. 34, Figs. 6-7 (needs roughcontact[fe])",
        description="Press a plane-strain hyperelastic finger section onto a plate and slide it to full slip at "
                    "several normal forces (FElupe); write CSV + PNG (docs/guide/fe_fingertip.md).",
        formatter_class=formatter))
    commands.choices["fingertip-fe"].set_defaults(run=fingertip_fe.run)
    return parser


def main(argv=None) -> int:
    parser = build_parser()
    args, provenance = parse_arguments(parser, argv, "roughcontact")
    program = f"roughcontact {args.command}"

    def show_warning(message, category, filename, lineno, file=None, line=None):
        print(f"{program}: warning: {message}", file=sys.stderr)          # one line, without the source line

    try:
        with warnings.catch_warnings():
            warnings.showwarning = show_warning
            return args.run(args, provenance)
    except KeyboardInterrupt:
        kept = f"; finished tasks are kept in {args.out} (the same command resumes)" if args.command == "run" else ""
        parser.exit(INTERRUPTED, f"{program}: interrupted{kept}\n")
    except OutputPathError as error:
        parser.exit(USAGE_ERROR, f"{program}: error: {error}\n")
    except OSError as error:                      # e.g. the disk filled up while writing
        parser.exit(USAGE_ERROR, f"{program}: error: cannot write {error.filename or 'the output'}: "
                                 f"{error.strerror or error}\n")


if __name__ == "__main__":
    sys.exit(main())
