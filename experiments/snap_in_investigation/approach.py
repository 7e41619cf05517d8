"""One-off: how far a cold snap-in solve moves with the step limit APPROACH (docs/interactions.md, "Several equilibria").
    PYTHONPATH=. python experiments/snap_in_investigation/approach.py 512 50 1 2 4 8
"""
import sys, numpy as np
import roughcontact.gap_solver as gs
from experiments.bench_interactions import patch
from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import DielectricStack
n = int(sys.argv[1]); V = float(sys.argv[2])
surface, half = patch(n, 1e6)
st = DielectricStack()
for a in [float(x) for x in sys.argv[3:]]:
    gs.APPROACH = a
    r = solve_contact(surface, half, mean_pressure=1e3, tol=1e-8, interaction=ElectrostaticInteraction(st, V), warn=False)
    print(a, r.iterations, r.params['fft_pairs'], round(r.contact_fraction,4), f'{r.equivalent_gap:.4e}', r.params['energy_history'][-1], r.converged)
