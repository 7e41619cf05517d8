"""``roughcontact fingertip-fe``: the FE fingertip study written as CSV + PNG with provenance (needs FElupe)."""
from __future__ import annotations

import sys

from ..io.provenance import output_directory
from .geometry import MeshResolution
from .model import FEConvergenceError, FingertipModel
from .store import RunStore
from .study import DEFAULT_FRICTIONS, DEFAULT_NORMAL_FORCES, run_fingertip_study, write_fingertip_outputs

#: Default output directory of the command.
DEFAULT_OUTPUT = "roughcontact-fingertip-fe"
MESHES = ("coarse", "default", "fine")
#: The store of finished runs inside the output directory (re-running into it resumes).
RUNS_DIRECTORY = "runs"


def add_arguments(parser) -> None:
    """The command's options (the parser is made in ``roughcontact.cli``)."""
    parser.add_argument("--out", default=DEFAULT_OUTPUT,
                        help="output directory; created if missing, but its parent must exist; finished runs are "
                             "kept in its runs/, so re-running into it resumes")
    parser.add_argument("--mesh", choices=MESHES, default="default",
                        help="mesh: coarse (the tests' CI size), default, fine (x1.5 the default's element counts)")
    parser.add_argument("--forces", type=float, nargs="+", default=list(DEFAULT_NORMAL_FORCES), metavar="F_N",
                        help="normal forces per unit width [N/m], in (0, 1000]")
    parser.add_argument("--friction", type=float, nargs="+", default=list(DEFAULT_FRICTIONS), metavar="MU",
                        help="local Coulomb coefficients of the contact, (0, 3]: mu0 = 0.26 of the friction law, "
                             "and mu_eff = mu0 (1 + F_el/F_N) under electroadhesion (default: 0.26)")
    parser.add_argument("--travel-step", type=float, default=None, metavar="METRES",
                        help="bone travel per increment [m], up to 1e-3 (default: about 25 increments to full "
                             "slip per run)")
    parser.add_argument("--workers", type=int, default=None,
                        help="processes running the (f_N, mu) runs in parallel; 1 runs in this process "
                             "(default: one per core)")


def run(args, provenance) -> int:
    """Check the values, run the study and write its outputs; exit code 2 with a one-line message for a bad
    value, without FElupe, or for a run whose press fails."""
    resolution = {"coarse": MeshResolution.coarse(), "default": MeshResolution(),
                  "fine": MeshResolution().refined(1.5)}[args.mesh]
    model = FingertipModel(resolution=resolution)
    sweep = dict(normal_forces=args.forces, frictions=args.friction, travel_step=args.travel_step,
                 workers=args.workers)
    try:
        run_fingertip_study(model, **sweep, check_only=True)
    except (ValueError, TypeError) as error:
        return _error(error)
    try:
        import felupe  # noqa: F401  (only to fail early with a clear message)
    except ImportError:
        return _error('needs FElupe: pip install "roughcontact[fe]"')
    output = output_directory(args.out)
    try:
        study = run_fingertip_study(model, **sweep, store=RunStore(output / RUNS_DIRECTORY), progress=True)
    except FEConvergenceError as error:
        return _error(error)
    for path in write_fingertip_outputs(study, output, provenance, echo=True):
        print(path)
    return 0


def _error(message) -> int:
    print(f"roughcontact fingertip-fe: error: {message}", file=sys.stderr)
    return 2
