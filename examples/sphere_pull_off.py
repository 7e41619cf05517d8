"""Pull-off of an adhesive sphere: the load-controlled retraction of a sphere with a Dugdale law, against Maugis.

A paraboloid (R = 1 m, E* = 1 Pa, work of adhesion w = 1e-3 J/m²: the units are arbitrary) in a periodic
cell, with the Maugis–Dugdale cohesive law at Maugis' parameter λ = 0.3 (between the DMT and JKR limits).
Starting from the zero-load equilibrium the external load is lowered in steps until the sphere detaches,
then bisected (`roughcontact.solvers.pull_off`). Prints the pull-off force F/(π w R) beside Maugis' (1992)
curve: 2.8 % apart on these 64² pixels; the error falls to first order in the pixel size (1.5 % at
128², 0.5 % at 512², docs/img/adhesive_sphere.csv from `python studies/adhesive_sphere.py --output docs/img`).
"""
import numpy as np

from roughcontact import ContactProblem, ElasticHalfSpace, MaugisDugdale
from roughcontact.reference import maugis_cohesive_stress, maugis_dugdale_pull_off
from roughcontact.solvers import pull_off
from surfaces import Grid, HeightField

radius, E_star, work, maugis_lambda, cell, n = 1.0, 1.0, 1e-3, 0.3, 1.6, 64
grid = Grid((n, n), (cell, cell), periodic=True)
x = (np.arange(n) - n / 2) * cell / n
sphere = HeightField(grid, -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * radius))
stress = maugis_cohesive_stress(maugis_lambda, work, radius, E_star)          # Dugdale stress σ0 [Pa]
problem = ContactProblem(sphere, ElasticHalfSpace(grid, E_star=E_star), MaugisDugdale(work, work / stress))

start = problem.solve(mean_pressure=0.0)                                     # the zero-load equilibrium
found = pull_off(problem, start, step=0.1 * np.pi * work * radius / cell ** 2, rtol=1e-2)
print(f"λ = {maugis_lambda}: contact radius at zero load {np.sqrt(start.contact_fraction / np.pi) * cell:.4f} m")
solved, maugis = found.force / (np.pi * work * radius), maugis_dugdale_pull_off(maugis_lambda)
print(f"pull-off F/(π w R) = {solved:.4f} on {n}², Maugis {maugis:.4f} ({solved / maugis - 1:+.2%}), "
      f"after {found.solves} solves")
