import sys, numpy as np, os
import roughcontact.gap_solver as gs
from roughcontact.gap_solver import _centred_into, _curvature_and_cap, _trial_gap, _advance_traction, _restore_mean, _dot, APPROACH, ARMIJO, MAX_HALVINGS, _REFRESH
NEWTON = int(os.environ.get('NEWTON', '6'))
def line_search(self, slope, sum_d, pel, value, magnitude, tau, since_exact):
    energy, body, n, g, d = self.energy, self.body, self.n, self.g, self.d
    d_mean = sum_d / n
    centred = self.work.reshape(-1)
    _centred_into(d, d_mean, centred)
    w = body.stiffness_into(self.work, self.w_field).reshape(-1)
    self.transforms += 2
    dw, kdd, cap = _curvature_and_cap(g, d, w, self.law_now[2], self.window, float(self.law.length), self.pixel_compliance, gs.APPROACH)
    curvature = (dw - kdd) / n
    self.concave = curvature <= 0
    if not self.concave:
        tau = -slope / n / curvature
    else:
        tau = 2 * tau if tau > 0 else -slope / max(dw, 1e-300)
    tau = min(tau, cap)
    # exact line search on the unclipped interval (load control only): Newton on phi'(t) with bracketing
    if energy.load is not None and NEWTON and tau > 0:
        neg = (d < 0) & self.window & (g > 0)
        t_clip = np.min(g[neg] / -d[neg]) if neg.any() else np.inf
        t_max = min(cap, t_clip)
        load = energy.load
        def deriv(t):
            gt = np.maximum(g + t * d, 0.0)
            p = self.law.traction(gt) * self.window
            k = self.law.stiffness(gt) * self.window
            return np.dot(d, pel + t * w + load - p), dw - np.dot(k, d * d)
        lo, hi = 0.0, t_max
        if os.environ.get('DBG'): print('slope', slope, 'f(0)', deriv(0.0), 'curv*n', curvature*n, 'tau', tau, 'f(tau)', deriv(tau), 't_max', t_max)
        if tau >= t_max: hi = -1
        t = min(tau, t_max)
        for _ in range(NEWTON if hi > 0 else 0):
            f1, f2 = deriv(t)
            if f1 < 0: lo = t
            else: hi = t
            if abs(f1) <= 1e-3 * abs(slope): break
            if f2 > 0:
                tn = t - f1 / f2
            else:
                tn = np.inf
            if not (lo < tn < hi):
                tn = 0.5 * (lo + hi) if np.isfinite(hi) else 2 * t
            t = tn
        if hi > 0 and 0 < t <= t_max: tau = t
    trial, r = self.trial, self.r
    for _ in range(MAX_HALVINGS):
        clipped, predicted = _trial_gap(g, d, tau, r, self.window, trial)
        if clipped and energy.constrained:
            _restore_mean(trial, energy.mean_target)
            predicted = _dot(r, trial) - _dot(r, g)
        exact = clipped or since_exact >= _REFRESH
        if exact:
            step = self.elastic(trial, self.trial_field)
        else:
            step = self.trial_field.reshape(-1)
            _advance_traction(pel, w, tau, step)
        trial_value, trial_magnitude = self.evaluate(trial, step, self.law_trial)
        if trial_value <= value + ARMIJO * predicted / n + self.round_off * magnitude:
            return True, tau, step, 0 if exact else since_exact + 1, (trial_value, trial_magnitude)
        tau *= 0.5
    return False, tau, pel, since_exact, (value, magnitude)
gs._Solver.line_search = line_search
from experiments.bench_interactions import patch
from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import DielectricStack
n = int(sys.argv[1])
surface, half = patch(n, 1e6)
hard = solve_contact(surface, half, mean_pressure=1e3, tol=1e-8)
for V in [float(v) for v in sys.argv[2:]]:
    r = solve_contact(surface, half, mean_pressure=1e3, tol=1e-8, interaction=ElectrostaticInteraction(DielectricStack(), V), warn=False)
    print(V, r.iterations, r.params['fft_pairs'], round(r.params['fft_pairs']/hard.params['fft_pairs'], 2), round(r.contact_fraction, 4), f'{r.equivalent_gap:.4e}', r.converged)
