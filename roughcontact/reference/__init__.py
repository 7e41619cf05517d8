"""Independent references: analytic contact solutions (:mod:`.analytic`: Hertz, Westergaard, the bisinusoid,
Maugis–Dugdale, Johnson's adhesive sinusoid), the benchmark problem of the solver studies (:mod:`.benchmark`),
and the two references of the layered field: second-order perturbation theory of a sinusoidal gap
(:mod:`.perturbation`) and the finite-element field solve of the full stack (:mod:`.fem`, the optional extra
``fieldcheck``), imported as submodules. Layer 1: of roughcontact it imports only the dielectric stack
(:mod:`roughcontact.electrostatics.stack`) and io's ``ConvergenceWarning``, both in layer 1."""
from __future__ import annotations

from .analytic import (bisinusoid_area_low_load, bisinusoid_area_near_full_contact, bisinusoid_full_contact_pressure,
                       hertz_contact_radius, hertz_elastic_energy, hertz_force, hertz_penetration, hertz_pressure,
                       johnson_sinusoid_load, maugis_cohesive_stress, maugis_dugdale_load, maugis_dugdale_pull_off,
                       westergaard_contact_half_width, westergaard_elastic_energy_density,
                       westergaard_full_contact_pressure, westergaard_mean_gap, westergaard_pressure)

__all__ = ["bisinusoid_area_low_load", "bisinusoid_area_near_full_contact", "bisinusoid_full_contact_pressure",
           "hertz_contact_radius", "hertz_elastic_energy", "hertz_force", "hertz_penetration", "hertz_pressure",
           "johnson_sinusoid_load", "maugis_cohesive_stress", "maugis_dugdale_load", "maugis_dugdale_pull_off",
           "westergaard_contact_half_width", "westergaard_elastic_energy_density",
           "westergaard_full_contact_pressure", "westergaard_mean_gap", "westergaard_pressure"]
