"""The finger section's mesh and the tissue parameters (no FElupe)."""
import numpy as np
import pytest

from roughcontact.fe.geometry import NAIL, SKIN, SUBCUTANEOUS, FingerSection, MeshResolution, mesh_section
from roughcontact.fe.materials import FingerMaterials, OgdenMaterial


def signed_areas(mesh):
    """Shoelace area of each quadrilateral, positive for counter-clockwise nodes [m²]."""
    x, y = mesh.points[mesh.cells][..., 0], mesh.points[mesh.cells][..., 1]
    return 0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1)


def test_mesh_fills_the_section_between_bone_and_contour():
    section = FingerSection()
    mesh = mesh_section(section, MeshResolution())
    areas = signed_areas(mesh)
    assert (areas > 0).all()                                  # counter-clockwise, no inverted cell
    # the cells' bilinear area sums to ellipse minus bone; the polygons undercut the ellipses by O(h²)
    expected = np.pi * (section.half_width * section.half_height
                        - section.bone_half_width * section.bone_half_height)
    assert areas.sum() == pytest.approx(expected, rel=2e-3)
    outer = mesh.points[mesh.surface]
    assert np.allclose((outer[:, 0] / section.half_width) ** 2 + (outer[:, 1] / section.half_height) ** 2, 1)
    assert set(np.unique(mesh.material)) == {SUBCUTANEOUS, SKIN, NAIL}
    nail = mesh.cells[mesh.material == NAIL]
    assert (mesh.points[nail][..., 1] > section.bone_offset).all()          # the nail is on the dorsal side
    lower = mesh.points[mesh.lower_surface]
    assert (lower[:, 1] < 0).all() and lower[:, 1].min() == pytest.approx(-section.half_height)


def test_contact_refinement_sets_the_spacing_at_the_bottom():
    section = FingerSection.circular(10e-3, 3e-3, 0.5e-3)
    for c in (0.1, 0.5):
        mesh = mesh_section(section, MeshResolution(around=100, contact_refinement=c))
        x = np.sort(mesh.points[mesh.lower_surface, 0])
        bottom = np.argmin(np.abs(x))
        spacing = x[bottom + 1] - x[bottom]
        # R dθ at s = 0 plus the cubic term of the angle map, (1 − c)(2/around)² / c ≈ 0.4 % of it at c = 0.1
        assert spacing == pytest.approx(c * 2 * np.pi / 100 * 10e-3, rel=1e-2)


@pytest.mark.parametrize("kwargs, match", [({"skin_thickness": 5e-3}, "must fit"),
                                           ({"half_width": -1.0}, "half_width"),
                                           ({"nail_half_angle": 3.0}, "nail_half_angle")])
def test_bad_sections_are_refused(kwargs, match):
    with pytest.raises(ValueError, match=match):
        FingerSection(**kwargs)


def test_bad_resolutions_and_materials_are_refused():
    with pytest.raises(ValueError, match="around"):
        MeshResolution(around=4)
    with pytest.raises(ValueError, match="contact_refinement"):
        MeshResolution(contact_refinement=0.0)
    with pytest.raises(ValueError, match="same number"):
        OgdenMaterial(mu=(1.0, 2.0), alpha=(2.0,), bulk=10.0)
    with pytest.raises(TypeError, match="skin"):
        FingerMaterials(skin=1.0)


def test_plane_strain_modulus_of_the_neo_hookean_solid():
    # E* = E/(1 − ν²) = 2μ/(1 − ν) for the bulk modulus of ν
    solid = FingerMaterials.homogeneous(10e3, 0.3).skin
    assert solid.plane_strain_modulus == pytest.approx(2 * 10e3 / 0.7, rel=1e-12)
