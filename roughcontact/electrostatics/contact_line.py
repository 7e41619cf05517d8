"""Models of the contact line for the layered field: what limits the attraction where a contact meets an open gap.

Without one, the layered field (:mod:`~roughcontact.electrostatics.field`) gives a contact line no finite strength:
beside a gap that opens like a crack the contact is the edge of a conductor on the insulator, its flux grows as
r^(−1/2) towards the line, the attraction of its contact pixels as 1/r, and the contact solve's F_el and contact
edges depend on the pixel (``docs/findings/contact_line.md``). A model of the contact line is passed as
``contact_line`` to :func:`~roughcontact.electrostatics.field.solve_field`,
:class:`~roughcontact.electrostatics.field.FieldLaw` and :class:`~roughcontact.interactions.ElectrostaticInteraction`:

* :class:`AirBreakdown`: the air between the skin and the screen breaks down above a field E_bd; the discharge
  leaves charge on the insulator that keeps the air field at E_bd;
* :class:`RoughnessFilm`: the skin's roughness below the pixel keeps a film of air between surfaces that the
  model sees in contact;
* ``None``: the sharp contact line of the plain layered field.

Pure Python: importing this module loads neither numba nor an FFT library.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from surfaces.validation import check_choice, check_positive

from .stack import EPSILON_0

#: The breakdown field of air in gaps below 1 µm [V/m]: a nearly constant mean breakdown field of 350 V/µm between
#: 0.1 and 1 µm gaps, in air and nitrogen, between gold and ruthenium electrodes (Peschot et al. 2014,
#: ``docs/references.md`` §12); the Paschen curve holds only above about 4 µm.
AIR_BREAKDOWN_FIELD = 350e6
#: How a broken column attracts (:class:`AirBreakdown`).
BREAKDOWN_TRACTIONS = ("maxwell", "energy")


@dataclass(frozen=True)
class AirBreakdown:
    """Air breakdown in the micro-gaps, with the charge it deposits on the insulator.

    Model. Where the air column's field D/(ε0 ε_a f) (f = 1 + |∇g|²/3, the slope factor of the layered field)
    would exceed ``field`` E_bd [V/m], the air breaks down and deposits a surface charge ρ ≥ 0 on the insulator
    that keeps the column's air field at E_bd: with D the flux through the solid layers (into the insulator) and
    D_a = D − ρ the air's,

        unbroken (D ≤ ε0 ε_a f E_bd):   ρ = 0,                 air drop R D,     R = g/(ε0 ε_a f),
        broken   (D > ε0 ε_a f E_bd):   D_a = ε0 ε_a f E_bd,   air drop E_bd g,

    and the drops across the layers still add up to U: (M D)_j + V_a,j = U. The broken columns are an active set,
    found by primal–dual active-set sweeps; the flux D minimises the convex energy of an air whose field saturates
    at E_bd (:class:`~roughcontact.electrostatics.field.FieldLaw`). The charge follows the present field: it is
    the charge that a monotone approach at constant voltage deposits (a gap that closes only gains charge), and
    it is assumed gone where a gap has reopened (quasi-static, no memory: under an AC drive every half-period
    reverses the field that deposited it). Inside a wide contact of the seed's stack the insulator's field reaches
    E_bd at U = E_bd d_i/ε_i ≈ 90 V; beside a contact line the flux grows as r^(−1/2) and exceeds it at any
    voltage.

    At contact (g = 0) there is no air. With ``at_contact`` (the default) a contact pixel takes the limit g → 0⁺
    of a broken column: the charge that closed the gap stays at the interface, and the stress that separates the
    surfaces there is the broken gap's. Without it a contact pixel keeps its attraction D²/(2 ε0 ε_a), which
    jumps from the broken gap's ε0 E_bd²/2 at g = 0⁺ to a stress that grows without bound at a contact line: a
    zero-range adhesion, which traps the contact edges at pixel-dependent positions as the plain layered field
    does (``docs/findings/contact_line.md``).

    Attraction. ``traction="maxwell"`` (the default) is the air-side Maxwell stress on the skin, ε0 ε_a f E_a²/2
    with E_a the air field (ε0 E_bd²/2 ≈ 0.54 MPa at a broken flat column), with the slope factor's neighbour
    terms of the layered field: the virtual work ½ Σ (D − ρ)² ∂R/∂g at fixed deposited charge. It is not the
    derivative of an energy: a discharge dissipates E_bd g per unit charge it deposits. ``traction="energy"`` is
    the derivative of the saturating air's energy instead, larger by E_bd ρ per broken column (the work the
    discharge would dissipate per unit opening if all its charge were deposited at the present gap): kept to
    measure that difference, not as a model of the force.
    """

    field: float = AIR_BREAKDOWN_FIELD
    at_contact: bool = True
    traction: str = "maxwell"

    def __post_init__(self):
        object.__setattr__(self, "field", check_positive("AirBreakdown.field", self.field))
        if not isinstance(self.at_contact, (bool, np.bool_)):
            raise TypeError(f"AirBreakdown.at_contact must be True or False, got {self.at_contact!r}")
        object.__setattr__(self, "at_contact", bool(self.at_contact))
        check_choice("AirBreakdown.traction", self.traction, BREAKDOWN_TRACTIONS)

    @property
    def stress(self) -> float:
        """ε0 E_bd²/2 [Pa] (ε_a = 1, flat column): the attraction of a broken column."""
        return 0.5 * EPSILON_0 * self.field ** 2


@dataclass(frozen=True)
class RoughnessFilm:
    """A film of air of ``thickness`` t [m] kept by the skin's roughness below the pixel.

    Model. The scene's roughness stops at its short cut-off; below it the skin's surface keeps a mean separation
    of about its rms height h_r from the screen even where the model's surfaces touch. Every air column sees the
    gap g + t, t = h_r (the contact mechanics, g ≥ 0, is unchanged): R = (g + t)/(ε0 ε_a f). A contact pixel then
    has an air column like any other, the contact line is no longer the edge of a conductor, and the flux
    beside it stays below ε0 U/t. The attraction is the layered field's virtual work on the shifted gap (an
    energy exists). No measurement of fingerpad roughness below 10 µm fixes h_r; 50–200 nm is the range
    considered (``docs/findings/contact_line.md``).
    """

    thickness: float

    def __post_init__(self):
        object.__setattr__(self, "thickness", check_positive("RoughnessFilm.thickness", self.thickness))


def check_contact_line(contact_line):
    """``contact_line`` if it is None, an :class:`AirBreakdown` or a :class:`RoughnessFilm`, else ``TypeError``."""
    if contact_line is None or isinstance(contact_line, (AirBreakdown, RoughnessFilm)):
        return contact_line
    raise TypeError(f"contact_line must be None, an AirBreakdown or a RoughnessFilm, got "
                    f"{type(contact_line).__name__} ({contact_line!r})")


def parse_contact_line(text: str):
    """The contact-line model that ``text`` names (a study's or a command's option): ``"none"``, ``"breakdown"``
    (:class:`AirBreakdown` at :data:`AIR_BREAKDOWN_FIELD`), ``"breakdown:<E_bd in V/m>"``,
    ``"breakdown-bulk"`` (no breakdown at contact), ``"breakdown-energy"`` (the energy's traction) or
    ``"film:<thickness in m>"`` (:class:`RoughnessFilm`); ``ValueError`` naming the valid forms otherwise."""
    name, _, value = str(text).strip().partition(":")
    forms = "none, breakdown[:E_bd], breakdown-bulk[:E_bd], breakdown-energy[:E_bd], film:<thickness>"
    try:
        if name == "none" and not value:
            return None
        if name in ("breakdown", "breakdown-bulk", "breakdown-energy"):
            field = float(value) if value else AIR_BREAKDOWN_FIELD
            return AirBreakdown(field, at_contact=name != "breakdown-bulk",
                                traction="energy" if name == "breakdown-energy" else "maxwell")
        if name == "film" and value:
            return RoughnessFilm(float(value))
    except ValueError as error:
        raise ValueError(f"contact line {text!r}: {error}") from None
    raise ValueError(f"contact line {text!r} is not valid; the forms are {forms}")
