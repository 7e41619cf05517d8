"""voltage_path: an electrostatic law's voltage swept, each solve from the last gap: the branch a ramped drive
follows (the snap-in's hysteresis), equilibria checked on the raw fields, resume, progress and bad input."""
import numpy as np
import pytest

from contact_checks import check_equilibrium
from roughcontact import ElasticHalfSpace, ElectrostaticInteraction, HardWall, solve_contact, voltage_path
from roughcontact.electrostatics import DielectricStack
from surfaces import Grid, self_affine

STACK = DielectricStack()
LAW = ElectrostaticInteraction(STACK, 0.0, field="parallel_plate")
UP = [10.0, 20.0, 30.0, 40.0, 50.0, 60.0]
RAMP = UP + UP[-2::-1]                     # up to 60 V and down again to 10 V


@pytest.fixture(scope="module")
def patch():
    """The electrostatic bar's rough patch on 64² (1 mm, 3 µm rms, E* = 1 MPa) at 1 kPa."""
    grid = Grid((64, 64), (1e-3, 1e-3), periodic=True)
    return self_affine(grid, hurst=0.8, rms_height=3e-6, short_cutoff=8e-3 / 64, rng=1), ElasticHalfSpace(grid, 1e6)


@pytest.fixture(scope="module")
def ramp(patch):
    surface, half = patch
    return list(voltage_path(surface, half, RAMP, interaction=LAW, mean_pressure=1e3, tol=1e-8))


def test_a_ramp_down_keeps_the_contact_that_snapped_in(patch, ramp):
    surface, half = patch
    assert [result.interaction.voltage for result in ramp] == RAMP and all(result.converged for result in ramp)
    cold = [solve_contact(surface, half, mean_pressure=1e3, tol=1e-8, interaction=result.interaction)
            for result in ramp[:len(UP)]]
    # the first step is the cold solve; each result is an equilibrium of its own voltage's law, checked on the raw
    # fields (measured imbalance <= 3e-6 p̄, as the cold solves of test_interactions.py), its traction the law's
    np.testing.assert_array_equal(ramp[0].gap, cold[0].gap)
    for result in ramp:
        assert check_equilibrium(result, surface, half, tol_traction=1e-6 * 1e3) <= 1e-3 * 1e3
        np.testing.assert_allclose(result.interaction_traction,
                                   -STACK.attraction(result.gap, result.interaction.voltage), rtol=1e-12)
    up, down = {r.interaction.voltage: r for r in ramp[:len(UP)]}, {r.interaction.voltage: r for r in ramp[len(UP):]}
    # up the ramp the path meets the cold solves to within the snap-in's spread of equilibria (measured: contact
    # fractions at most 0.97 % of the patch apart, at 40 and 60 V, where a cold solve snaps in from the hard wall)
    for result, alone in zip(ramp[:len(UP)], cold):
        assert abs(result.contact_fraction - alone.contact_fraction) < 0.02
    # down the ramp the snapped-in contact stays where the attraction holds it: 0.797 / 0.769 / 0.539 at 50 / 40 /
    # 30 V against 0.702 / 0.533 / 0.375 up, and F_el above (measured); at 10 V the two branches meet again
    for voltage in (50.0, 40.0, 30.0):
        assert down[voltage].contact_fraction > up[voltage].contact_fraction + 0.09
        assert down[voltage].electrostatic_force > 1.1 * up[voltage].electrostatic_force
    assert down[10.0].contact_fraction == pytest.approx(up[10.0].contact_fraction, abs=2 / 64 ** 2)


def test_an_interrupted_ramp_resumes_exactly(patch, ramp, capsys):
    surface, half = patch
    resumed = list(voltage_path(surface, half, RAMP[3:5], start=ramp[2], progress=True, interaction=LAW,
                                mean_pressure=1e3, tol=1e-8))
    for again, uninterrupted in zip(resumed, ramp[3:5]):
        np.testing.assert_array_equal(again.gap, uninterrupted.gap)
        assert again.iterations == uninterrupted.iterations
    assert "voltage path" in capsys.readouterr().err
    # a step is solve_contact from the last result (the continuation of studies/bench_interactions.py)
    by_hand = solve_contact(surface, half, mean_pressure=1e3, tol=1e-8, interaction=ramp[3].interaction, x0=ramp[2])
    np.testing.assert_array_equal(by_hand.gap, ramp[3].gap)
    # cold steps are solve_contact's cold solves
    cold = next(voltage_path(surface, half, [40.0], warm_start=False, interaction=LAW, mean_pressure=1e3, tol=1e-8))
    alone = solve_contact(surface, half, mean_pressure=1e3, tol=1e-8, interaction=cold.interaction)
    np.testing.assert_array_equal(cold.gap, alone.gap)
    assert cold.interaction == ElectrostaticInteraction(STACK, 40.0, field="parallel_plate")


@pytest.mark.parametrize("arguments, error, match", [
    (dict(interaction=HardWall()), TypeError, "sweeps the voltage of an ElectrostaticInteraction; the problem's law is "
                                              "HardWall"),
    (dict(voltages="30"), TypeError, "voltages must be a sequence of voltages"),
    (dict(voltages=[10.0, float("nan")]), ValueError, "voltage"),
    (dict(x0=None), ValueError, "voltage_path sets x0 itself"),
    (dict(start=[None]), TypeError, "start must be a ContactResult"),
])
def test_bad_input_is_refused_before_the_first_step(patch, arguments, error, match):
    surface, half = patch
    keywords = dict(voltages=[10.0, 20.0], interaction=LAW, mean_pressure=1e3) | arguments
    with pytest.raises(error, match=match):
        voltage_path(surface, half, keywords.pop("voltages"), **keywords)
