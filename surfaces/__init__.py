"""surfaces — physical height fields on grids: generation and statistics (numpy/scipy only).

Knows nothing of contact mechanics; ``roughcontact`` consumes it. All lengths are in metres.
"""
from .grid import Grid
from .heightfield import HeightField
from .statistics import psd, rms_curvature, rms_height, rms_slope
from .selfaffine import SelfAffinePSD, fourier_synthesis, self_affine
from .shapes import fingertip

__version__ = "0.1.0"

__all__ = ["Grid", "HeightField", "psd", "rms_curvature", "rms_height", "rms_slope", "__version__",
           "SelfAffinePSD", "fourier_synthesis", "self_affine", "fingertip"]
