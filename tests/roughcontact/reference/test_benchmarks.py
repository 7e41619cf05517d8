"""The benchmark problem shared by the solver studies (roughcontact.reference.benchmark)."""
import numpy as np
import pytest

from roughcontact.reference.benchmark import CUTOFF_PIXELS, LENGTH, contact_patches, rough_surface, sweep_pressures


def test_rough_surface_is_seeded_and_keeps_its_heights_on_a_free_grid():
    periodic, free = rough_surface(32, rng=3), rough_surface(32, rng=3, periodic=False)
    assert all(periodic.grid.periodic) and not any(free.grid.periodic)
    np.testing.assert_array_equal(periodic.heights, free.heights)
    assert not np.array_equal(periodic.heights, rough_surface(32, rng=4).heights)
    assert periodic.grid.lengths == (LENGTH, LENGTH) and CUTOFF_PIXELS == 4


def test_sweep_pressures():
    np.testing.assert_allclose(sweep_pressures(1.0, 4), [0.25, 0.5, 0.75, 1.0])


@pytest.mark.parametrize("periodic, expected", [(True, 2), (False, 4)])
def test_contact_patches(periodic, expected):
    contact = np.zeros((8, 8), dtype=bool)
    contact[2:4, 2:5] = True                                      # a 2×3 block
    contact[0, 0] = contact[-1, 0] = contact[0, -1] = True         # three pixels joined across the periodic edges
    assert contact_patches(contact, periodic=periodic) == expected
