"""The friction model: the seed paper's sliding friction of a fingerpad under electroadhesion.

Heß & Forsbach's (2020) macroscopic model with its Table-1 parameters (docs/guide/friction_model.md): the
equivalent air gap d_eq(F_N) of Eq. 46, the electrostatic pressure of the layered capacitor (Eq. 21), the ridge
area of the adhesive power-law contact, reduced by the tangential load at the onset of sliding (Eq. 9), and
the friction force (Eqs. 40–45). Prints, for normal forces 0.5–2 N at 0, 100 and 200 V, the friction
coefficient μ = F_T/F_N and the electrostatic share of the friction force; at 0 V μ is the dry μ0 = 0.26, and
the seed quotes μ more than doubled at 200 V for forces below about 1.7 N (docs/findings/errata.md, (h)).
"""
import numpy as np

from roughcontact.macro import SlidingFrictionModel

model = SlidingFrictionModel.paper_table1()
forces, voltages = np.array([0.5, 1.0, 1.5, 2.0]), np.array([0.0, 100.0, 200.0])
state = model.state(forces[:, None], voltages[None, :])        # every quantity on the (force, voltage) grid

print("F_N [N]  d_eq [µm]  μ(0 V)  μ(100 V)  μ(200 V)  F_el/F_N at 200 V")
for i, force in enumerate(forces):
    mu = state.friction_coefficient[i]
    print(f"{force:6.1f}   {state.gap[i, 0] * 1e6:7.2f}    {mu[0]:.3f}   {mu[1]:.3f}     {mu[2]:.3f}"
          f"     {state.electrostatic_force[i, 2] / force:.3f}")
