"""An electroadhesive patch: the attraction of the finger–screen capacitor acting inside the contact solve.

A 0.5 mm periodic self-affine patch (rms height 3 µm) of skin (E* = 1 MPa) pressed on the screen at 1 kPa,
with the electrostatic attraction of the seed's dielectric stack (1 µm insulator, 250 µm stratum corneum)
at 0, 50 and 100 V. The attraction is the layered field of the stack over the solved gap (the default,
docs/guide/electrostatics.md); the seed's per-pixel parallel-plate law (Eq. 21) is shown beside it at 100 V.
Prints the contact fraction, the electrostatic force on the patch and the equivalent air gap of seed Eq. 25.
"""
from roughcontact import DielectricStack, ElasticHalfSpace, ElectrostaticInteraction, solve_contact
from surfaces import Grid, self_affine

patch = self_affine(Grid((64, 64), (0.5e-3, 0.5e-3), periodic=True), hurst=0.8, rms_height=3e-6, rng=0)
body = ElasticHalfSpace(patch.grid, E_star=1e6)
stack = DielectricStack()                                  # seed Table 1

print("field           U [V]  A/A0    F_el [mN]  d_eq [µm]")
for field, voltage in (("layered", 0.0), ("layered", 50.0), ("layered", 100.0), ("parallel_plate", 100.0)):
    law = ElectrostaticInteraction(stack, voltage, field=field)
    result = solve_contact(patch, body, mean_pressure=1e3, interaction=law)
    assert result.converged, result.message
    print(f"{field:15s} {voltage:5.0f}  {result.contact_fraction:.4f}  {result.electrostatic_force * 1e3:8.5f}"
          f"   {result.equivalent_gap * 1e6:.4f}")
