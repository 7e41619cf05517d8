"""Result objects save and load with their parameters and the library version."""
import pickle
from dataclasses import dataclass, field

import numpy as np
import pytest

from roughcontact import __version__
from roughcontact.io import SavableResult
from surfaces import Grid
from surfaces.io import load_npz


@dataclass(frozen=True)
class _Toy(SavableResult):
    pressure: np.ndarray
    grid: Grid
    converged: bool
    iterations: int
    shape: tuple
    params: dict = field(default_factory=dict)


def _toy():
    return _Toy(np.arange(6.0).reshape(2, 3), Grid((2, 3), (1e-3, 2e-3), (True, False)), True, 17, (2, 3),
                {"E_star": 1e6, "nested": {"tol": 1e-8, "names": ["a", "b"]}})


def test_save_load_round_trip(tmp_path):
    original = _toy()
    path = original.save(tmp_path / "toy")
    assert path.suffix == ".npz"
    loaded = _Toy.load(path)
    np.testing.assert_array_equal(loaded.pressure, original.pressure)
    assert loaded.grid == original.grid
    assert (loaded.converged, loaded.iterations, loaded.shape, loaded.params) == \
           (original.converged, original.iterations, original.shape, original.params)
    assert isinstance(loaded.shape, tuple) and isinstance(loaded.params["nested"]["names"], list)
    assert not loaded.pressure.flags.writeable                   # immutable, as when it was made
    assert load_npz(path)[1]["version"] == __version__


def test_load_refuses_another_kind(tmp_path):
    @dataclass(frozen=True)
    class Other(SavableResult):
        x: float

    path = Other(1.0).save(tmp_path / "other.npz")
    with pytest.raises(ValueError, match="not a _Toy"):
        _Toy.load(path)


def test_pickle_round_trip():
    original = _toy()
    clone = pickle.loads(pickle.dumps(original))
    np.testing.assert_array_equal(clone.pressure, original.pressure)
    assert clone.pressure.dtype == original.pressure.dtype
    assert (clone.grid, clone.converged, clone.iterations, clone.shape, clone.params) == \
           (original.grid, original.converged, original.iterations, original.shape, original.params)
