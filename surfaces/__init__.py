"""surfaces — physical height fields on grids: generation and statistics (numpy/scipy only).

Knows nothing of contact mechanics; ``roughcontact`` consumes it. All lengths are in metres.
Grid, HeightField and the statistics are numpy-only and imported eagerly; the generators (which use
``scipy.fft``/``scipy.ndimage``) load on first use (PEP 562), so ``import surfaces`` stays cheap for
``roughcontact.electrostatics`` and ``roughcontact.macro``.
"""
from .lazy import lazy_attributes
from .grid import Grid
from .heightfield import HeightField, MissingDataWarning
from .statistics import psd, rms_curvature, rms_height, rms_slope

__version__ = "0.1.0"

# public name -> submodule that defines it (loaded lazily)
_LAZY = {
    "SelfAffinePSD": "selfaffine",
    "fourier_synthesis": "selfaffine",
    "self_affine": "selfaffine",
    "fingertip": "shapes",
    **dict.fromkeys(["fingerprint", "parallel_ridges", "ridge_pattern", "RidgePattern", "ridge_profile"],
                    "ridges"),
    **dict.fromkeys(["dominant_wavelength", "orientation_field", "OrientationField", "angular_difference",
                     "detect_pores", "DetectedPores"], "texture"),
    # measured topographies through the optional SurfaceTopography (imported inside these functions)
    **dict.fromkeys(["read_topography", "from_topography", "to_topography"], "topography"),
}

__getattr__, __dir__, __all__ = lazy_attributes(
    __name__, _LAZY, ["Grid", "HeightField", "MissingDataWarning", "psd", "rms_curvature", "rms_height", "rms_slope",
                      "__version__"])
