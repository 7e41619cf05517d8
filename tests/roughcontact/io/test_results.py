"""Result objects save and load with their parameters and the library version."""
import json
import pickle
import re
import sys
import types
from dataclasses import dataclass, field

import numpy as np
import pytest

from roughcontact import __version__
from roughcontact.io import SavableResult
from roughcontact.io.results import FIELD_TYPES
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
    assert not clone.pressure.flags.writeable                     # immutable, as the original


def _metadata_json(path):
    with np.load(path) as data:
        return dict(data), json.loads(data["__metadata_json__"].tobytes())


def _rewritten(path, arrays, metadata=None):
    """``path`` rewritten with ``arrays`` (and ``metadata``), as a user tampering with the file would."""
    if metadata is not None:
        arrays = {**arrays, "__metadata_json__": np.frombuffer(json.dumps(metadata).encode(), dtype=np.uint8)}
    np.savez(path, **arrays)
    return path


@pytest.mark.parametrize("damage, reason", [
    (lambda path: path.write_bytes(b""), r"not a readable .npz archive \(empty, truncated or of another format"),
    (lambda path: path.write_bytes(path.read_bytes()[:200]), "not a readable .npz archive"),
    (lambda path: path.write_text("pressure,gap\n1,2\n"), "not an .npz archive$"),
    (lambda path: np.save(path.with_suffix(".npy"), np.ones(3)) or path.with_suffix(".npy").rename(path),
     "not a readable .npz archive"),
    (lambda path: np.savez(path, pressure=np.ones(3)), "has no metadata record"),
    (lambda path: _rewritten(path, {**_metadata_json(path)[0],
                                    "__metadata_json__": np.frombuffer(b"{not json", dtype=np.uint8)}),
     "its metadata record is not valid JSON"),
    (lambda path: _rewritten(path, {**_metadata_json(path)[0], "pressure": np.ones((3, 2))}),
     r"its arrays differ from the shapes and dtypes recorded when it was saved \(the file was altered\): "
     r"pressure: \(2, 3\) <f8 -> \(3, 2\) <f8$"),
    (lambda path: _rewritten(path, {**_metadata_json(path)[0], "pressure": np.ones((2, 3), np.float32)}),
     r"pressure: \(2, 3\) <f8 -> \(2, 3\) <f4$"),
    (lambda path: _rewritten(path, {k: v for k, v in _metadata_json(path)[0].items() if k != "pressure"}),
     r"pressure: \(2, 3\) <f8 -> missing$"),
    (lambda path: _rewritten(path, _metadata_json(path)[0], {**_metadata_json(path)[1], "fields": {
        **_metadata_json(path)[1]["fields"], "bogus": 1}}), "its _Toy record has the fields bogus that a _Toy does"),
    (lambda path: _rewritten(path, _metadata_json(path)[0], {**_metadata_json(path)[1], "fields": {
        k: v for k, v in _metadata_json(path)[1]["fields"].items() if k != "iterations"}}),
     "its _Toy record has no iterations$"),
    (lambda path: _rewritten(path, _metadata_json(path)[0], {**_metadata_json(path)[1], "arrays": "pressure"}),
     "its record of arrays is not a table"),
    (lambda path: _rewritten(path, _metadata_json(path)[0], {k: v for k, v in _metadata_json(path)[1].items()
                                                             if k != "arrays"}),
     "its metadata has no record of its arrays"),
    (lambda path: _rewritten(path, _metadata_json(path)[0], {**_metadata_json(path)[1], "fields": {
        **_metadata_json(path)[1]["fields"], "grid": {"__result__": "Nope", "fields": {}}}}),
     "its field grid holds a 'Nope', a result class not defined now"),
], ids=["empty", "truncated", "text", "npy", "no metadata", "bad JSON", "shape", "dtype", "missing array",
        "extra field", "missing field", "bad array record", "no array record", "unknown nested result"])
def test_a_damaged_or_altered_file_is_a_value_error_naming_it(tmp_path, damage, reason):
    path = _toy().save(tmp_path / "toy.npz")
    damage(path)
    with pytest.raises(ValueError, match=f"^{re.escape(str(path))}(:| is not a saved result:) .*{reason}") as error:
        _Toy.load(path)
    assert "allow_pickle" not in str(error.value)


def test_a_user_dataclass_is_rebuilt_while_its_module_is_imported_and_named_when_not(tmp_path, monkeypatch):
    # a user's own law (a dataclass in the user's module) saved in a result: rebuilt if its module is loaded,
    # otherwise a warning names it and the field comes back as a dict of its fields
    class Law:                                             # the library's base of its registered laws
        pass

    @dataclass(frozen=True)
    class BuiltIn(Law):
        depth: float

    monkeypatch.setitem(FIELD_TYPES, "BuiltIn", BuiltIn)
    module = types.ModuleType("user_laws")
    exec("from dataclasses import dataclass\n@dataclass(frozen=True)\nclass WallLaw(Law):\n    depth: float\n"
         "@dataclass(frozen=True)\nclass Unrelated:\n    depth: float\n", {**module.__dict__, "Law": Law},
         module.__dict__)
    monkeypatch.setitem(sys.modules, "user_laws", module)
    path = _with_law(_toy(), module.WallLaw(2e-9)).save(tmp_path / "toy.npz")
    assert _Toy.load(path).params["law"] == module.WallLaw(2e-9)
    unrelated = _with_law(_toy(), module.Unrelated(2e-9)).save(tmp_path / "unrelated.npz")
    with pytest.warns(UserWarning, match="cannot rebuild user_laws.Unrelated"):       # not a law: not built
        assert _Toy.load(unrelated).params["law"] == {"depth": 2e-9}
    monkeypatch.delitem(sys.modules, "user_laws")                       # another session, without the module
    with pytest.warns(UserWarning, match=f"{re.escape(str(path))}: cannot rebuild user_laws.WallLaw: not registered "
                                         "with roughcontact.io.savable_field, nor .* in a module imported now"):
        loaded = _Toy.load(path)
    assert loaded.params["law"] == {"depth": 2e-9}


def _with_law(toy, law):
    return _Toy(toy.pressure, toy.grid, toy.converged, toy.iterations, toy.shape, {**toy.params, "law": law})


def test_a_field_that_cannot_be_saved_is_named():
    class Law:                                             # a user's law that is not a dataclass
        length = 1e-6

    toy = _Toy(np.zeros((2, 3)), _toy().grid, True, 1, (2, 3), {"law": Law()})
    with pytest.raises(TypeError, match="_Toy.params: a .*Law cannot be saved: .* must be a frozen dataclass"):
        toy.save("unused.npz")
