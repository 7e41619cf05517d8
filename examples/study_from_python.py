"""A study from Python: d_eq(F_N, U) and A_R(F_N, U) of a small scene, and the friction law fed with them.

The multiscale fingerpad study (docs/guide/study.md) on a scene small enough to run in seconds: two normal
forces, 0 and 200 V, 32² patches of ridges and micro-roughness, two realisations, solved in this process.
Prints the equivalent air gap d_eq (seed Eq. 25) and the ridge contact area fraction A_R/A0 per force and
voltage (means over the realisations, with 95 % half-widths), and the friction coefficient of the seed's law
fed bottom-up beside the seed's fitted model.
"""
from roughcontact.macro import SlidingFrictionModel
from roughcontact.study import bottom_up_friction, load_scene, run_study

SMALL = """
[loads]
normal_forces = [0.5, 2.0]
voltages = [0.0, 200.0]
[roughness]
long_cutoff = 1.5e-4
[presets.draft]
grid = 32
realisations = 2
tolerance = 1e-6
pixels_per_cutoff = 3.0
"""

if __name__ == "__main__":                     # run_study's process pool imports this file; here workers=1
    scene = load_scene(text=SMALL, preset="draft")
    result = run_study(scene, workers=1)
    gaps, gap_widths = result.summary("equivalent_gap")
    areas = result.summary("ridge_area_fractions")[0][:, :, 0]
    for i, force in enumerate(result.normal_forces):
        for j, voltage in enumerate(result.voltages):
            print(f"F_N = {force:.1f} N, U = {voltage:5.1f} V: d_eq = {gaps[i, j] * 1e6:.3f} ± "
                  f"{gap_widths[i, j] * 1e6:.3f} µm, A_R/A0 = {areas[i, j]:.3f}")
    bottom_up = bottom_up_friction(result).friction_coefficient(1.0, [0.0, 200.0])
    fitted = SlidingFrictionModel.paper_table1().friction_coefficient(1.0, [0.0, 200.0])
    print(f"μ at 1 N, 0 and 200 V: bottom-up {bottom_up.round(3)}, the seed's fitted model {fitted.round(3)}")
