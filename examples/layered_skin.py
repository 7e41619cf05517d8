"""A layered skin: ridges pressed on a stiff stratum corneum bonded on soft tissue.

Sinusoidal ridges of the fingerprint's period (0.45 mm, amplitude 25 µm) pressed at 5 kPa on three bodies:
the soft tissue alone (E* = 0.1 MPa), the default scene's skin (a 30 µm stratum corneum of E* = 10 MPa bonded
on that tissue; docs/guide/layered.md gives its kernel) and the layer's material as a half-space. The two
half-spaces are checked against Westergaard's contact half-width (within a pixel, 1.8 µm); the layered skin
lies between them, far stiffer than the tissue at this wavelength because the layer spreads the load.
Prints the contact half-width and the mean gap.
"""
import numpy as np

from roughcontact import ElasticHalfSpace, solve_contact
from roughcontact.reference import westergaard_contact_half_width
from surfaces import Grid, HeightField

period, amplitude, pressure = 0.45e-3, 25e-6, 5e3             # [m], [m], [Pa]
tissue, layer, thickness = 1e5, 1e7, 30e-6                    # E* of tissue and layer [Pa], layer thickness [m]
grid = Grid((256, 4), (period, period / 64), periodic=True)   # one period, uniform along the ridges
x, _ = grid.meshgrid()
ridges = HeightField(grid, amplitude * np.cos(2 * np.pi * x / period))

bodies = {"tissue half-space": ElasticHalfSpace(grid, E_star=tissue),
          "layered skin": ElasticHalfSpace(grid, E_star=layer, thickness=thickness, poisson=0.5,
                                           substrate_E_star=tissue, substrate_poisson=0.5),
          "layer half-space": ElasticHalfSpace(grid, E_star=layer)}
exact = {"tissue half-space": tissue, "layer half-space": layer}
print("body               half-width [µm]  Westergaard [µm]  mean gap [µm]")
for name, body in bodies.items():
    result = solve_contact(ridges, body, mean_pressure=pressure, tol=1e-10)
    half_width = result.contact_fraction * period / 2
    reference = (f"{westergaard_contact_half_width(pressure, amplitude, period, exact[name]) * 1e6:8.3f}"
                 if name in exact else "        -")
    print(f"{name:18s} {half_width * 1e6:10.3f}       {reference}         {result.mean_gap * 1e6:8.3f}")
