"""The apparent scale: the fingertip cap pressed onto the layered skin, solved on a free (non-periodic) grid.

The cap h(r) = −r²/(2R) (``surfaces.fingertip``, apex at the window's centre pixel) of the scene's
``fingerpad.radius`` R is pressed with the normal force F_N onto the skin: the stratum-corneum layer of the
scene's ``skin`` (``layer_E_star``, ``layer_thickness``, ``poisson``) bonded on tissue of ``fingerpad.E_star``
(the fingertip-scale modulus; ``tissue_E_star`` overrides it), or the tissue half-space when
``layer_thickness`` is 0. The hard-wall solve (:func:`roughcontact.solve_contact`, free-surface layered kernel
of ``docs/guide/layered.md``) gives the apparent area A0 (the contact set) and the nominal pressure over it as means
over ``rings`` rings of equal area, the form of ``roughcontact.study.apparent_contact`` for the Hertz model.
With ``layer_thickness`` = 0 the answer is Hertz's to the grid's resolution (``docs/findings/equivalent_gap.md``,
"The apparent scale on the layered skin").
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from surfaces import Grid, fingertip
from surfaces.validation import check_integer, check_positive

from ..body import ElasticHalfSpace
from ..solvers import solve_contact

#: The window's half side over the Hertz contact radius of the tissue: the contact's diameter spans 80 % of it.
WINDOW_MARGIN = 1.25
#: Default solver tolerance (relative, :func:`roughcontact.solve_contact`).
TOLERANCE = 1e-8


@dataclass(frozen=True)
class FingertipContact:
    """The fingertip's apparent contact at one normal force.

    ``area`` A0 [m²] (contact pixels × pixel area) and ``pressures``, the mean nominal pressure [Pa] over each of
    the rings of equal area r² ∈ [k, k+1]·A0/(π·rings) around the apex, innermost first. Unpacks as
    ``area, pressures = result`` (the form of ``study.apparent_contact``). Also: ``normal_force`` [N],
    ``radius`` √(A0/π) [m], ``peak_pressure`` [Pa], ``penetration`` [m] (rigid approach from first touch),
    ``pixel`` [m] (grid spacing), ``grid_points`` (per side), ``converged`` and ``iterations`` of the solve.
    """
    normal_force: float
    area: float
    pressures: tuple
    radius: float
    peak_pressure: float
    penetration: float
    pixel: float
    grid_points: int
    converged: bool
    iterations: int

    def __iter__(self):
        return iter((self.area, self.pressures))


def skin_body(grid: Grid, skin, tissue_E_star: float, **options) -> ElasticHalfSpace:
    """The skin on ``grid``: the scene's layer bonded on tissue of ``tissue_E_star`` [Pa], or that tissue's
    half-space when ``skin.layer_thickness`` is 0; ``options`` (``threads``, ``dtype``, …) go to
    :class:`~roughcontact.body.ElasticHalfSpace`."""
    if skin.layer_thickness == 0:
        return ElasticHalfSpace(grid, E_star=tissue_E_star, **options)
    return ElasticHalfSpace(grid, E_star=skin.layer_E_star, thickness=skin.layer_thickness, poisson=skin.poisson,
                            substrate_E_star=tissue_E_star, substrate_poisson=skin.poisson, **options)


def ring_means(pressure: np.ndarray, radii: np.ndarray, contact_radius: float, rings: int) -> tuple:
    """Mean of ``pressure`` [Pa] over the pixels whose centre lies in each of ``rings`` rings of equal area,
    r² ∈ [k, k+1]·a²/rings with a = ``contact_radius`` [m]; ``radii`` [m] are the pixel centres' distances from
    the apex."""
    ring = np.floor(rings * (radii / contact_radius) ** 2).astype(int)
    counts = np.bincount(ring.ravel(), minlength=rings)[:rings]
    if counts.min() == 0:
        raise ValueError(f"rings = {rings} rings of equal area over a contact of radius {contact_radius:g} m leave "
                         f"a ring without a pixel centre (pixels per ring: {counts.tolist()}); use fewer rings or "
                         "more grid_points")
    return tuple(float(pressure[ring == k].mean()) for k in range(rings))


def fingertip_contact(fingerpad, skin, normal_force: float, rings: int, grid_points: int = 128, *,
                      tissue_E_star: float | None = None, tol: float = TOLERANCE) -> FingertipContact:
    """Press the fingertip cap (``fingerpad.radius``) with ``normal_force`` F_N [N] onto the layered ``skin``.

    ``fingerpad``, ``skin``: the scene's :class:`~roughcontact.study.scene.Fingerpad` and
    :class:`~roughcontact.study.scene.Skin` sections (or any objects with their fields). The square free-surface
    window of ``grid_points``² pixels has the half side ``WINDOW_MARGIN`` times the Hertz radius a = (3 F R/(4 E*))^⅓ of the
    tissue; if the contact reaches the window's border the window is doubled and the solve repeated.
    ``tissue_E_star`` [Pa]: the modulus under the layer (default ``fingerpad.E_star``). Returns a
    :class:`FingertipContact`; a solve that misses ``tol`` warns and reports ``converged`` = False.
    """
    force = check_positive("normal_force", normal_force)
    rings = check_integer("rings", rings, low=1)
    grid_points = check_integer("grid_points", grid_points, low=8)
    radius = check_positive("fingerpad.radius", fingerpad.radius)
    tissue = check_positive("tissue_E_star", fingerpad.E_star if tissue_E_star is None else tissue_E_star)
    half_side = WINDOW_MARGIN * (3 * force * radius / (4 * tissue)) ** (1 / 3)
    for _ in range(4):
        side = 2 * half_side
        grid = Grid((grid_points, grid_points), (side, side), periodic=False)
        cap = fingertip(grid, radii=(radius, radius))
        result = solve_contact(cap, skin_body(grid, skin, tissue), total_force=force, tol=tol)
        contact = result.contact
        if not (contact[0].any() or contact[-1].any() or contact[:, 0].any() or contact[:, -1].any()):
            break
        half_side *= 2
    else:
        raise ValueError(f"the contact of normal_force = {force!r} N reaches the border of a window 16 times the "
                         f"Hertz estimate (side {side!r} m); check skin (E_star, layer_E_star) and fingerpad.radius")
    area = float(np.count_nonzero(contact)) * grid.pixel_area
    contact_radius = math.sqrt(area / math.pi)
    x, y = grid.coordinates()
    centre = (grid_points // 2) * grid.spacing[0]
    radii = np.hypot(x[:, None] - centre, y[None, :] - centre)
    return FingertipContact(normal_force=force, area=area,
                            pressures=ring_means(result.pressure, radii, contact_radius, rings),
                            radius=contact_radius, peak_pressure=float(result.pressure.max()),
                            penetration=float(result.penetration), pixel=float(grid.spacing[0]),
                            grid_points=grid_points, converged=bool(result.converged),
                            iterations=int(result.iterations))
