"""The elastic body: surface displacement from surface pressure. Layer 2 (imports ``roughcontact.fft``).

:mod:`.kernels`: Fourier compliances Φ(q) of the half-space's layers (on a rigid base, on a half-space);
:mod:`.influence`: real-space influence coefficients of a pixel (Love's half-space, the layered free-surface
correction); :mod:`.elastic`: :class:`ElasticHalfSpace`, the FFT operator u = K p built from them, and
:class:`PaddedOperator`, a free surface's operator on its zero-padded grid.
"""
from __future__ import annotations

from .elastic import ElasticHalfSpace, PaddedOperator
from .influence import free_surface_correction, love_pixel_displacement, pixel_potential
from .kernels import BOTTOMS, THICK_X, layer_on_half_space_compliance, layer_on_rigid_base_compliance

__all__ = ["BOTTOMS", "ElasticHalfSpace", "PaddedOperator", "THICK_X", "free_surface_correction",
           "layer_on_half_space_compliance", "layer_on_rigid_base_compliance", "love_pixel_displacement",
           "pixel_potential"]
