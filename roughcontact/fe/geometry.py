"""Parametric cross-section of a fingertip and its structured quadrilateral mesh (numpy only).

The section lies in the (x, y) plane, x along the sliding direction, y normal to the plate, which touches the
pad from below. The outer contour is the ellipse x²/a² + y²/b² = 1 (``half_width`` a, ``half_height`` b); the
distal phalanx (bone) is an ellipse of half-axes (``bone_half_width``, ``bone_half_height``) whose centre sits
``bone_offset`` above the section's centre (towards the nail, so the pulp under the bone is thick). A skin
layer of ``skin_thickness`` covers the subcutaneous tissue; over the dorsal arc within ``nail_half_angle`` of
the top the skin layer is the nail. The bone is rigid (17 GPa against tissue moduli of kPa–MPa) and is not
meshed: its contour nodes move with one reference point.

The mesh maps a polar grid: ray k joins the bone point B(θ_k) to the outer point O(θ_k) of the same ellipse
parameter θ_k; along it the subcutaneous tissue fills B → O − t e and the skin O − t e → O (e the ray's unit
vector, t the skin thickness). The angles crowd at the bottom, θ = −π/2 + π (c s + (1 − c) s³) for s uniform
in [−1, 1): the spacing at the contact is c times the uniform spacing (``contact_refinement`` c).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from surfaces.validation import check_real

#: Material labels of the mesh's cells.
SUBCUTANEOUS, SKIN, NAIL = 0, 1, 2
MATERIAL_NAMES = ("subcutaneous", "skin", "nail")


def _check_count(name: str, value, low: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
        raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")
    return int(value)


@dataclass(frozen=True)
class FingerSection:
    """Geometry of the finger's cross-section [m]; defaults in ``docs/guide/fe_fingertip.md`` (after Wu et al.)."""

    half_width: float = 8.0e-3
    half_height: float = 7.0e-3
    bone_half_width: float = 3.0e-3
    bone_half_height: float = 2.0e-3
    bone_offset: float = 2.0e-3
    skin_thickness: float = 1.0e-3
    nail_half_angle: float = np.deg2rad(50.0)

    def __post_init__(self):
        for name in ("half_width", "half_height", "bone_half_width", "bone_half_height", "skin_thickness"):
            check_real(name, getattr(self, name), low=0.0, low_open=True)
        check_real("bone_offset", self.bone_offset)
        check_real("nail_half_angle", self.nail_half_angle, low=0.0, high=np.pi / 2)
        pulp = self.half_height - (self.bone_half_height - self.bone_offset)      # tissue under the bone [m]
        top = self.half_height - (self.bone_half_height + self.bone_offset)       # tissue over the bone [m]
        side = self.half_width - self.bone_half_width
        if min(pulp, top, side) <= 1.5 * self.skin_thickness:
            raise ValueError(f"the bone (half-axes {self.bone_half_width}, {self.bone_half_height} m, offset "
                             f"{self.bone_offset} m) and skin ({self.skin_thickness} m) must fit inside the contour "
                             f"(half-axes {self.half_width}, {self.half_height} m) with tissue between them")

    @classmethod
    def circular(cls, radius: float, bone_radius: float, skin_thickness: float) -> FingerSection:
        """A round section with a concentric round bone and no nail (the Hertz check's geometry)."""
        return cls(half_width=radius, half_height=radius, bone_half_width=bone_radius,
                   bone_half_height=bone_radius, bone_offset=0.0, skin_thickness=skin_thickness,
                   nail_half_angle=0.0)

    @property
    def bottom_radius(self) -> float:
        """Radius of curvature of the contour at its lowest point, a²/b [m] (the Hertz radius)."""
        return self.half_width ** 2 / self.half_height


@dataclass(frozen=True)
class MeshResolution:
    """Element counts: ``around`` the contour, through the ``subcutaneous`` tissue and the ``skin``;
    ``contact_refinement`` c in (0, 1]: the angular spacing at the contact relative to uniform; ``grading`` g ≥ 1
    of the subcutaneous layers, finer towards the skin (radial position s^(1/g))."""

    around: int = 160
    subcutaneous: int = 10
    skin: int = 3
    contact_refinement: float = 0.15
    grading: float = 1.5

    def __post_init__(self):
        _check_count("around", self.around, 16)
        _check_count("subcutaneous", self.subcutaneous, 1)
        _check_count("skin", self.skin, 1)
        check_real("contact_refinement", self.contact_refinement, low=0.0, high=1.0, low_open=True)
        check_real("grading", self.grading, low=1.0)

    @classmethod
    def coarse(cls) -> MeshResolution:
        """The CI-sized mesh of the tests."""
        return cls(around=64, subcutaneous=5, skin=2, contact_refinement=0.25)

    def refined(self, factor: float) -> MeshResolution:
        """Every element count times ``factor`` (the convergence study)."""
        return MeshResolution(around=int(round(self.around * factor)),
                              subcutaneous=max(1, int(round(self.subcutaneous * factor))),
                              skin=max(1, int(round(self.skin * factor))),
                              contact_refinement=self.contact_refinement, grading=self.grading)


@dataclass(frozen=True)
class SectionMesh:
    """Quadrilateral mesh of the section: ``points`` (n, 2) [m], ``cells`` (m, 4) counter-clockwise,
    ``material`` (m,) labels (``SUBCUTANEOUS``, ``SKIN``, ``NAIL``), ``bone`` the node indices on the bone
    contour, ``surface`` the outer contour's nodes in order of their angle ``surface_angle`` [rad]."""

    points: np.ndarray
    cells: np.ndarray
    material: np.ndarray
    bone: np.ndarray
    surface: np.ndarray
    surface_angle: np.ndarray

    @property
    def lower_surface(self) -> np.ndarray:
        """Outer nodes of the lower half (the candidates for contact with the plate)."""
        return self.surface[np.sin(self.surface_angle) < 0]


def mesh_section(section: FingerSection, resolution: MeshResolution = MeshResolution()) -> SectionMesh:
    """The structured mesh of ``section`` (module docstring)."""
    c = resolution.contact_refinement
    s = np.linspace(-1.0, 1.0, resolution.around, endpoint=False)
    theta = -np.pi / 2 + np.pi * (c * s + (1 - c) * s ** 3)
    outer = np.column_stack([section.half_width * np.cos(theta), section.half_height * np.sin(theta)])
    bone = np.column_stack([section.bone_half_width * np.cos(theta),
                            section.bone_offset + section.bone_half_height * np.sin(theta)])
    ray = outer - bone
    skin_inner = outer - section.skin_thickness * ray / np.linalg.norm(ray, axis=1)[:, None]
    depth = np.linspace(0.0, 1.0, resolution.subcutaneous + 1) ** (1 / resolution.grading)
    rows = [bone + t * (skin_inner - bone) for t in depth]
    rows += [skin_inner + t * (outer - skin_inner) for t in np.linspace(0.0, 1.0, resolution.skin + 1)[1:]]
    index = np.arange(len(rows) * resolution.around).reshape(len(rows), resolution.around)
    following = np.roll(index, -1, axis=1)
    cells = np.stack([index[:-1], index[1:], following[1:], following[:-1]], axis=-1).reshape(-1, 4)
    layer = np.repeat(np.arange(len(rows) - 1), resolution.around)
    cell_angle = np.tile(theta + np.diff(np.append(theta, theta[0] + 2 * np.pi)) / 2, len(rows) - 1)
    material = np.where(layer < resolution.subcutaneous, SUBCUTANEOUS, SKIN)
    dorsal = np.abs(np.angle(np.exp(1j * (cell_angle - np.pi / 2)))) < section.nail_half_angle
    material = np.where((material == SKIN) & dorsal, NAIL, material)
    return SectionMesh(points=np.concatenate(rows), cells=cells, material=material, bone=index[0],
                       surface=index[-1], surface_angle=theta)
