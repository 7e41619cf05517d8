"""The FE sweep's store of finished runs: an interrupted sweep resumes, stale files are run again (no FElupe:
the runs are stand-ins)."""
import numpy as np
import pytest

from roughcontact.fe.model import ContactSnapshot, FingertipModel, SlidingRun
from roughcontact.fe.store import RunStore, StaleRunWarning
from roughcontact.fe.study import exponent_rows, run_fingertip_study


def stand_in(model, normal_force, travel_step=None, max_travel=30e-3):
    """A SlidingRun of the right shapes whose numbers depend on f_N and μ (no FE)."""
    x = np.linspace(-1e-3, 1e-3, 5)
    snapshots = tuple(ContactSnapshot(x=x, normal=np.full(5, normal_force / 5), tangential=np.full(5, -i * 0.1),
                                      gap=np.zeros(5), slip=np.arange(5) < i) for i in range(3))
    ramp = np.arange(3.0)
    return SlidingRun(normal_force=float(normal_force), travel=ramp * 1e-4, tangential_force=ramp * 0.5,
                      contact_normal_force=np.full(3, float(normal_force)), bone_tangential_force=ramp * 0.5,
                      length=8e-3 - ramp * 1e-4 * model.friction, length_gap=8e-3 - ramp * 1e-4,
                      slipping=ramp / 2, full_slip=True, converged=True, friction=model.friction,
                      snapshots=snapshots, pressed_points=np.ones((4, 2)), final_points=np.ones((4, 2)) * 2,
                      cells=np.arange(4).reshape(1, 4), material=np.zeros(1, int), seconds=1.5)


@pytest.fixture
def counted(monkeypatch):
    calls = []

    def slide(self, normal_force, travel_step=None, max_travel=30e-3):
        calls.append((normal_force, self.friction))
        if normal_force == 100.0 and getattr(slide, "interrupt", False):
            raise KeyboardInterrupt
        return stand_in(self, normal_force, travel_step, max_travel)

    monkeypatch.setattr(FingertipModel, "slide", slide)
    return slide, calls


def test_an_interrupted_sweep_resumes_from_its_store(counted, tmp_path):
    slide, calls = counted
    store, model = RunStore(tmp_path / "runs"), FingertipModel()
    slide.interrupt = True
    with pytest.raises(KeyboardInterrupt):
        run_fingertip_study(model, [50.0, 100.0], frictions=[0.26], workers=1, store=store)
    assert calls == [(50.0, 0.26), (100.0, 0.26)] and store.path(50.0, 0.26).exists()
    assert not store.path(100.0, 0.26).exists()
    slide.interrupt = False
    calls.clear()
    study = run_fingertip_study(model, [50.0, 100.0], frictions=[0.26], workers=1, store=store)
    assert calls == [(100.0, 0.26)]                               # the finished run was not run again
    reused = study.runs[0]
    fresh = stand_in(FingertipModel(friction=0.26), 50.0)
    for name in ("travel", "length", "tangential_force", "pressed_points", "cells"):
        assert np.array_equal(getattr(reused, name), getattr(fresh, name))
    assert all(np.array_equal(a.slip, b.slip) and np.array_equal(a.x, b.x)
               for a, b in zip(reused.snapshots, fresh.snapshots))
    assert (reused.full_slip, reused.friction, reused.seconds) == (True, 0.26, 1.5)


def test_stale_runs_are_named_and_run_again(counted, tmp_path):
    slide, calls = counted
    store, model = RunStore(tmp_path / "runs"), FingertipModel()
    run_fingertip_study(model, [50.0], frictions=[0.26, 0.5], workers=1, store=store)
    path = store.path(50.0, 0.5)
    with np.load(path) as stored:                                 # edited: one length changed, meta kept
        arrays = {name: stored[name] for name in stored.files}
    arrays["length"][1] *= 1.01
    np.savez(path, **arrays)
    calls.clear()
    with pytest.warns(StaleRunWarning, match="run_fN50_mu0.5.npz: its arrays do not match their digest"):
        run_fingertip_study(model, [50.0], frictions=[0.26, 0.5], workers=1, store=store)
    assert calls == [(50.0, 0.5)]
    path.write_bytes(b"")                                         # cut short
    calls.clear()
    with pytest.warns(StaleRunWarning, match="cannot be read"):
        run_fingertip_study(model, [50.0], frictions=[0.5], workers=1, store=store)
    assert calls == [(50.0, 0.5)]
    calls.clear()                                                 # another model: every run again
    with pytest.warns(StaleRunWarning, match="another model"):
        run_fingertip_study(FingertipModel(penalty=300.0), [50.0], frictions=[0.26], workers=1, store=store)
    assert calls == [(50.0, 0.26)]


def test_sweep_values_are_checked_before_anything_runs(counted):
    _, calls = counted
    for kwargs, match in (({"normal_forces": [1e7]}, r"normal_force = 10000000.0 is out of range; valid range \(0, 1000\]"),
                          ({"frictions": [-0.1]}, r"friction = -0.1 is out of range; valid range \(0, 3\]"),
                          ({"travel_step": 1e-12}, r"travel_step = 1e-12 is out of range; valid range \[3e-06, 0.001\]"),
                          ({"travel_step": 0.02}, r"travel_step = 0.02 is out of range"),
                          ({"workers": 0}, "workers")):
        with pytest.raises(ValueError, match=match):
            run_fingertip_study(FingertipModel(), **{"normal_forces": [50.0], **kwargs})
    assert calls == []


def test_exponent_table_explains_when_it_is_left_out():
    rows = [{"normal_force_N_per_m": f, "friction": 0.26, "xi_m3_per_N2": 1e-6 * f ** -1.0, "full_slip": True}
            for f in (50.0, 150.0)]
    exponents, notes = exponent_rows(rows)
    assert exponents == [] and len(notes) == 2 and "needs at least 3" in notes[0]
    rows.append({"normal_force_N_per_m": 400.0, "friction": 0.26, "xi_m3_per_N2": 1e-6 / 400.0, "full_slip": True})
    exponents, _ = exponent_rows(rows)
    assert exponents[0]["exponent"] == pytest.approx(-1.0, abs=1e-12)
