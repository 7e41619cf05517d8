import sys, numpy as np
from experiments.bench_interactions import patch
from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import DielectricStack
n = int(sys.argv[1]); V = float(sys.argv[2])
surface, half = patch(n, 1e6)
r = solve_contact(surface, half, mean_pressure=1e3, tol=1e-8, interaction=ElectrostaticInteraction(DielectricStack(), V), warn=False)
res = r.residuals
print(' '.join(f'{i}:{x:.1e}' for i, x in enumerate(res)))
