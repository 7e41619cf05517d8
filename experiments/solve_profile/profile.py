"""One-off: the per-step profile of an electrostatic solve (residual, step kind, line-search FFT pairs, contact
set changes, step length over the no-tunnelling cap).

    ROUGHCONTACT_FFT_THREADS=1 python experiments/solve_profile/profile.py 512 50

The bench patch (experiments/bench_interactions.py, E* 1 MPa, 1 kPa, tol 1e-8); wraps the solver's line search.
"""
import sys

import numpy as np

sys.path.insert(0, "experiments")
from bench_interactions import patch  # noqa: E402

import roughcontact.gap_solver as gap_solver  # noqa: E402
from roughcontact import ElectrostaticInteraction, solve_contact  # noqa: E402
from roughcontact.electrostatics import DielectricStack  # noqa: E402


def main(n, voltage):
    surface, half = patch(n, 1e6)
    steps, line_search = [], gap_solver._Solver.line_search

    def profiled(self, *args):
        snapping, transforms, wall = self.snapping, self.transforms, self.g <= 0
        outcome = line_search(self, *args)
        after = self.trial <= 0 if outcome[0] else wall
        cap = gap_solver._cap(self.g, self.d, self.law_now[1], self.window, float(self.law.length),
                              self.pixel_compliance, gap_solver.APPROACH)
        steps.append((snapping, (self.transforms - transforms) / 2, int(after.sum()), int((after & ~wall).sum()),
                      int((wall & ~after).sum()), outcome[1] / cap if np.isfinite(cap) else 0.0))
        return outcome

    gap_solver._Solver.line_search = profiled
    result = solve_contact(surface, half, mean_pressure=1e3, tol=1e-8,
                           interaction=ElectrostaticInteraction(DielectricStack(), voltage))
    print(f"{result.params['fft_pairs']} FFT pairs, {result.iterations} steps, contact {result.contact_fraction:.5f}")
    for number, (step, residual) in enumerate(zip(steps, result.residuals), 1):
        snapping, pairs, wall, closed, opened, length = step
        print(f"{number:3d} residual {residual:.1e} {'snap ' if snapping else 'model'} line-search pairs {pairs:.0f} "
              f"at the wall {wall} +{closed} -{opened} step/cap {length:.2g}")


if __name__ == "__main__":
    main(int(sys.argv[1]), float(sys.argv[2]))
