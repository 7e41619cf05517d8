"""One-off: the cold solve with and without the snap-in steps (docs/interactions.md, "Snap-in steps").

    ROUGHCONTACT_FFT_THREADS=1 PYTHONPATH=. python experiments/snap_in_investigation/snap_steps.py 512 50 100

Without them every step takes its length from the quadratic model (the solver's state forgets the last step's
concavity before each line search). Prints iterations, FFT pairs, contact fraction and d_eq for both.
"""
import sys

import roughcontact.gap_solver as gs
from experiments.bench_interactions import patch
from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import DielectricStack

search = gs._Solver.line_search


def model_only(self, *args):
    self.snapping = False
    return search(self, *args)


n = int(sys.argv[1])
surface, half = patch(n, 1e6)
for voltage in [float(v) for v in sys.argv[2:]]:
    for name, method in (("snap-in steps", search), ("model only", model_only)):
        gs._Solver.line_search = method
        res = solve_contact(surface, half, mean_pressure=1e3, tol=1e-8,
                            interaction=ElectrostaticInteraction(DielectricStack(), voltage))
        print(f"{n} {voltage:g} V {name:14s} {res.iterations:4d} steps {res.params['fft_pairs']:6.1f} pairs "
              f"contact {res.contact_fraction:.5f} d_eq {res.equivalent_gap:.5e} m converged {res.converged}")
