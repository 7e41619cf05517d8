"""Hertz contact on the free surface: a sphere pressed on an elastic half-space, against Hertz's solution.

A sphere of radius R = 10 mm on a 1 mm window (free surface, not periodic: the kernel is the exact Boussinesq
response of pixels of uniform pressure) with E* = 1 MPa, at the force that gives a contact radius of 0.15 mm.
Prints the solved penetration, contact radius and peak pressure beside Hertz's (Johnson 1985, §4.2); on 128²
pixels they agree to about 1e-3, and the radius to about a pixel.
"""
import numpy as np

from roughcontact import ElasticHalfSpace, solve_contact
from roughcontact import reference
from surfaces import Grid, HeightField

side, radius, E_star = 1e-3, 10e-3, 1e6                     # window [m], sphere radius [m], contact modulus [Pa]
force = 4 * E_star * 0.15e-3 ** 3 / (3 * radius)            # Hertz: a = 0.15 mm at this force [N]

grid = Grid((128, 128), (side, side), periodic=False)
x, y = grid.meshgrid()
r = np.hypot(x - side / 2, y - side / 2)
sphere = HeightField(grid, -r ** 2 / (2 * radius))          # heights [m], apex at the window's centre
result = solve_contact(sphere, ElasticHalfSpace(grid, E_star=E_star), total_force=force, tol=1e-10)

contact_radius = np.sqrt(result.contact_fraction * side ** 2 / np.pi)
print(f"force {force * 1e3:.4f} mN, converged: {result.converged} in {result.iterations} iterations")
print(f"penetration    {result.penetration * 1e6:.5f} µm  (Hertz {reference.hertz_penetration(force, radius, E_star) * 1e6:.5f})")
print(f"contact radius {contact_radius * 1e3:.5f} mm  (Hertz {reference.hertz_contact_radius(force, radius, E_star) * 1e3:.5f})")
print(f"peak pressure  {result.pressure.max() / 1e3:.4f} kPa (Hertz {reference.hertz_pressure(0.0, force, radius, E_star) / 1e3:.4f})")
