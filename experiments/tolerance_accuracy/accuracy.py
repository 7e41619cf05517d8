"""One-off: how far a tol-1e-8 answer is from the converged one, for the hard wall and the electrostatic solves.

    ROUGHCONTACT_FFT_THREADS=1 python experiments/tolerance_accuracy/accuracy.py 512 10 50 100

Each solve at tol 1e-6 and 1e-8 on the bench patch (experiments/bench_interactions.py, E* 1 MPa, 1 kPa) is
continued from its own answer to tol 1e-13 (hard wall) or 1e-12 (electrostatic); printed: the rms change of the
displacement over the rms height, the relative change of the mean gap, of the contact fraction and the rms change
of the traction over the load, and the FFT pairs of the tolerance's solve.
"""
import sys

import numpy as np

sys.path.insert(0, "experiments")
from bench_interactions import patch  # noqa: E402

from roughcontact import ElectrostaticInteraction, solve_contact  # noqa: E402
from roughcontact.electrostatics import DielectricStack  # noqa: E402

LOAD = 1e3


def report(label, answer, converged, rms_height):
    du = np.sqrt(np.mean((answer.displacement - converged.displacement) ** 2)) / rms_height
    dp = np.sqrt(np.mean((answer.pressure - converged.pressure) ** 2)) / LOAD
    print(f"{label:>16}: rms du / rms h {du:.2e}  d<g>/<g> {abs(answer.mean_gap / converged.mean_gap - 1):.2e}  "
          f"d contact {abs(answer.contact_fraction - converged.contact_fraction):.2e}  rms dp / p {dp:.2e}  "
          f"FFT pairs {answer.params['fft_pairs']}")


def main(n, voltages):
    surface, half = patch(n, 1e6)
    rms_height = float(surface.heights.std())
    for tol in (1e-6, 1e-8):
        answer = solve_contact(surface, half, mean_pressure=LOAD, tol=tol)
        report(f"hard wall {tol:g}", answer, solve_contact(surface, half, mean_pressure=LOAD, tol=1e-13, x0=answer),
               rms_height)
    for voltage in voltages:
        law = ElectrostaticInteraction(DielectricStack(), voltage)
        for tol in (1e-6, 1e-8):
            answer = solve_contact(surface, half, mean_pressure=LOAD, tol=tol, interaction=law)
            converged = solve_contact(surface, half, mean_pressure=LOAD, tol=1e-12, interaction=law, x0=answer)
            report(f"{voltage:g} V {tol:g}", answer, converged, rms_height)


if __name__ == "__main__":
    main(int(sys.argv[1]), [float(v) for v in sys.argv[2:]])
