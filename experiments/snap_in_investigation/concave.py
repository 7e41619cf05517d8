import sys, numpy as np
import roughcontact.gap_solver as gs
from experiments.bench_interactions import patch
from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import DielectricStack
n = int(sys.argv[1])
surface, half = patch(n, 1e6)
orig_cap = gs._curvature_and_cap
info = {}
def cap(*a):
    out = orig_cap(*a); info['c'] = out; return out
gs._curvature_and_cap = cap
orig_ls = gs._Solver.line_search
def ls(self, *a):
    out = orig_ls(self, *a)
    dw, kdd, c = info['c']
    if kdd >= dw: info['rows'].append((self_it[0], kdd/dw, out[1] >= c*(1-1e-12)))
    self_it[0] += 1
    return out
gs._Solver.line_search = ls
for V in [float(v) for v in sys.argv[2:]]:
    info['rows'] = []; self_it = [0]
    r = solve_contact(surface, half, mean_pressure=1e3, tol=1e-8, interaction=ElectrostaticInteraction(DielectricStack(), V), warn=False)
    print(V, r.iterations, 'concave steps', len(info['rows']), [(i, f'{q:.6f}', capped) for i, q, capped in info['rows']][:60])
