"""``roughcontact fingertip-fe``: the FE fingertip study written as CSV + PNG with provenance (needs FElupe)."""
from __future__ import annotations

import sys

from ..io.provenance import output_directory
from .geometry import MeshResolution
from .model import FingertipModel
from .study import DEFAULT_NORMAL_FORCES, run_fingertip_study, write_fingertip_outputs

#: Default output directory of the command.
DEFAULT_OUTPUT = "roughcontact-fingertip-fe"
MESHES = ("coarse", "default", "fine")


def add_arguments(parser) -> None:
    """The command's options (the parser is made in ``roughcontact.cli``)."""
    parser.add_argument("--out", default=DEFAULT_OUTPUT,
                        help="output directory; created if missing, but its parent must exist")
    parser.add_argument("--mesh", choices=MESHES, default="default",
                        help="mesh: coarse (the tests' CI size), default, fine (x1.5 the default's element counts)")
    parser.add_argument("--forces", type=float, nargs="+", default=list(DEFAULT_NORMAL_FORCES), metavar="F_N",
                        help="normal forces per unit width [N/m]")
    parser.add_argument("--travel-step", type=float, default=0.1e-3, help="bone travel per increment [m]")


def run(args, provenance) -> int:
    """Run the study and write its outputs; exit code 2 with a one-line message without FElupe."""
    try:
        import felupe  # noqa: F401  (only to fail early with a clear message)
    except ImportError:
        print('roughcontact fingertip-fe: error: needs FElupe: pip install "roughcontact[fe]"', file=sys.stderr)
        return 2
    resolution = {"coarse": MeshResolution.coarse(), "default": MeshResolution(),
                  "fine": MeshResolution().refined(1.5)}[args.mesh]
    output = output_directory(args.out)
    try:
        study = run_fingertip_study(FingertipModel(resolution=resolution), args.forces,
                                    travel_step=args.travel_step, progress=True)
    except ValueError as error:
        print(f"roughcontact fingertip-fe: error: {error}", file=sys.stderr)
        return 2
    for path in write_fingertip_outputs(study, output, provenance, echo=True):
        print(path)
    return 0
