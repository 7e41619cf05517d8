"""Linear PCG on the Hessian at converged solutions: iterations to 1e-8 and Lanczos kappa, with and without the law."""
import sys, numpy as np
from experiments.bench_interactions import patch
from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import DielectricStack
n = int(sys.argv[1])
surface, half = patch(n, 1e6)
st = DielectricStack()
lc = max(float(half.compliance(2*np.pi/1e-3)), half.uniform_compliance)
pix = half.pixel_compliance
buf_in, buf_out = half._fft.empty() if hasattr(half, '_fft') else None, None
def K(r):
    out = np.empty_like(r); half._displacement_into(r.copy(), out); return out + (lc - half.uniform_compliance) * r.mean()
def Kinv(v):
    out = np.empty_like(v); half.stiffness_into(v - v.mean(), out); return out
def pcg(F, D, tol=1e-8, maxit=500):
    rng = np.random.default_rng(0)
    b = rng.standard_normal(F.shape) * F
    x = np.zeros_like(b); r = b.copy(); z = K(r) * F; d = z.copy(); rz = (r*z).sum(); r0 = np.sqrt((z*z).sum())
    alphas, betas = [], []
    for it in range(1, maxit):
        Hd = (Kinv(d) - D*d) * F
        a = rz / (d*Hd).sum(); alphas.append(a)
        x += a*d; r -= a*Hd; z = K(r)*F
        rz_new = (r*z).sum(); beta = rz_new/rz; betas.append(beta); rz = rz_new
        if np.sqrt((z*z).sum()) < tol*r0: break
        d = z + beta*d
    m = len(alphas)
    T = np.zeros((m, m))
    for j in range(m):
        T[j, j] = 1/alphas[j] + (betas[j-1]/alphas[j-1] if j else 0)
        if j+1 < m: T[j, j+1] = T[j+1, j] = np.sqrt(betas[j])/alphas[j]
    if not np.all(np.isfinite(T)): return it, np.nan, np.nan, np.nan
    ev = np.linalg.eigvalsh(T)
    return it, ev.max()/ev.min(), ev.min(), ev.max()
for V in [float(v) for v in sys.argv[2:]]:
    law = ElectrostaticInteraction(st, V)
    r = solve_contact(surface, half, mean_pressure=1e3, tol=1e-8, interaction=law, warn=False) if V > 0 else \
        solve_contact(surface, half, mean_pressure=1e3, tol=1e-8)
    F = (r.gap > 0).astype(float)
    D = law.stiffness(r.gap) * F if V > 0 else 0*F
    kk = D*pix
    it0, kap0, *_ = pcg(F, 0*F)
    it1, kap1, lmin, lmax = pcg(F, D)
    print(f"{V:6g} V  A {r.contact_fraction:.4f}  nonlinear it {r.iterations:4d}  linear PCG  law {it1:4d} (kappa {kap1:9.3g}, lmin {lmin:.3g})  no law {it0:4d} (kappa {kap0:8.3g})  max kK_ii {kk.max():.3f}  frac kK_ii>0.5 {np.mean(kk>0.5):.4f}")
