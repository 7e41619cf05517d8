import sys, dataclasses, numpy as np
import roughcontact.gap_solver as gs
from experiments.bench_interactions import patch
from roughcontact import ElasticHalfSpace, ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import DielectricStack
n = int(sys.argv[1]); volts = [float(v) for v in sys.argv[3:]]; coarsest = int(sys.argv[2])
surface, half = patch(n, 1e6)
st = DielectricStack()
hard = solve_contact(surface, half, mean_pressure=1e3, tol=1e-8)
def nested(surf, body, law, tol):
    """solve on surf, starting from the coarsened solve (recursively) down to `coarsest`"""
    m = surf.shape[0]
    if m // 2 < coarsest:
        return solve_contact(surf, body, mean_pressure=1e3, tol=tol, interaction=law, warn=False), 0.0
    cs = surf.coarsened(2)
    cb = ElasticHalfSpace(cs.grid, E_star=1e6)
    cr, pairs = nested(cs, cb, law, tol)
    u = np.kron(cr.gap + cs.heights, np.ones((2, 2)))       # g + h = s - u (rigid flat offset) prolonged
    g0 = np.maximum(u - surf.heights, 0.0)
    hw = solve_contact(surf, body, mean_pressure=1e3, tol=1e-2)
    x0 = dataclasses.replace(hw, gap=g0)
    r = solve_contact(surf, body, mean_pressure=1e3, tol=tol, interaction=law, x0=x0, warn=False)
    return r, pairs + cr.params['fft_pairs'] / 4
for V in volts:
    law = ElectrostaticInteraction(st, V)
    c = solve_contact(surface, half, mean_pressure=1e3, tol=1e-8, interaction=law, warn=False)
    r, coarse_pairs = nested(surface, half, law, 1e-8)
    hp = hard.params['fft_pairs']
    for name, x, extra in (('cold', c, 0), ('nested', r, coarse_pairs)):
        print(V, name, 'ratio', round((x.params['fft_pairs']+extra)/hp, 2), 'A', round(x.contact_fraction, 4), f'deq {x.equivalent_gap:.4e}',
              f'E {x.params["energy_history"][-1]:.6e}', x.converged)
