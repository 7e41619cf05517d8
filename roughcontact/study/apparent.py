"""The apparent scale of the study: the apparent area A0 and the nominal pressures over it at each normal force
(``docs/findings/equivalent_gap.md``) — the power law of seed Eq. 27, the Hertz ring means of a fingertip cap, or the
cap solved on the layered skin (:mod:`.fingertip`)."""
from __future__ import annotations

import numpy as np

from .fingertip import fingertip_contact
from .scene import Scene


def ring_count(scene: Scene) -> int:
    """The rings of equal area that the apparent contact is averaged over: the preset's for a fingertip, one
    for the power law."""
    return scene.preset.rings if scene.fingerpad.model == "fingertip" else 1


def apparent_contact(fingerpad, normal_force: float, rings: int) -> tuple:
    """``(A0 [m²], nominal pressures [Pa])`` at ``normal_force`` [N]: one pressure F_N/A0 for the power law,
    ``rings`` Hertz ring means (rings of equal area, a³ = 3 F R/(4 E*), p0 = 3F/(2π a²)) for a fingertip."""
    if fingerpad.model == "power_law":
        area = fingerpad.area_prefactor * normal_force ** fingerpad.area_exponent
        return area, (normal_force / area,)
    radius = (3 * normal_force * fingerpad.radius / (4 * fingerpad.E_star)) ** (1 / 3)
    area = np.pi * radius ** 2
    peak = 3 * normal_force / (2 * area)
    s = np.linspace(0.0, 1.0, rings + 1)                         # (r/a)² at the ring boundaries
    means = peak * (2 / 3) * ((1 - s[:-1]) ** 1.5 - (1 - s[1:]) ** 1.5) / np.diff(s)
    return area, tuple(float(p) for p in means)


def apparent_scale(scene: Scene) -> tuple:
    """``(A0 [m²], nominal pressures [Pa])`` at each of the scene's normal forces: :func:`apparent_contact`, or
    for a fingertip with ``fingerpad.layer`` the cap solved on the skin's layer over the tissue
    (:func:`roughcontact.study.fingertip.fingertip_contact` on ``fingerpad.layer_grid``² pixels; ``ValueError`` where a
    solve does not converge)."""
    rings, fingerpad = ring_count(scene), scene.fingerpad
    if fingerpad.model != "fingertip" or not fingerpad.layer:
        return tuple(apparent_contact(fingerpad, force, rings) for force in scene.loads.normal_forces)
    scales = []
    for force in scene.loads.normal_forces:
        contact = fingertip_contact(fingerpad, scene.skin, force, rings, grid_points=fingerpad.layer_grid)
        if not contact.converged:
            raise ValueError(f"the fingertip on the layered skin did not converge at loads.normal_forces = {force!r} "
                             f"N ({contact.iterations} iterations on fingerpad.layer_grid = {fingerpad.layer_grid} "
                             "px); refine layer_grid or set fingerpad.layer = false")
        scales.append((contact.area, contact.pressures))
    return tuple(scales)
