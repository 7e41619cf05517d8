"""The tiny scene of the study and coupling tests: 32² patches, two loads, 0 and 150 V, seconds to run."""

TINY = """\
[loads]
normal_forces = [0.5, 2.0]
voltages = [0.0, 150.0]
[roughness]
long_cutoff = 1.5e-4
[ridge_area]
coarse_graining = 6e-5
sensitivity = [2.0]
[presets.draft]
grid = 32
realisations = 2
tolerance = 1e-6
pixels_per_cutoff = 3.0
"""
