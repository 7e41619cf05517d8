"""The layered field's models of the contact line (roughcontact.electrostatics.contact_line): air breakdown and a
roughness film, against closed forms, finite differences of their energies and the contact solve's pixel."""
import dataclasses

import numpy as np
import pytest

from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import (AIR_BREAKDOWN_FIELD, EPSILON_0, AirBreakdown, DielectricStack,
                                         RoughnessFilm, solve_field)
from roughcontact.electrostatics.contact_line import check_contact_line, parse_contact_line
from roughcontact.electrostatics.field import FieldLaw
from surfaces import Grid

STACK = DielectricStack()
BREAKDOWN = AirBreakdown()


def rough_gap(shape, rng, contact=0.2, scale=1e-6):
    """A smoothed random gap field with a contact fraction ``contact`` (its lowest values at g = 0)."""
    frequency = np.add.outer(np.fft.fftfreq(shape[0]) ** 2, np.fft.rfftfreq(shape[1]) ** 2)
    noise = np.fft.irfft2(np.fft.rfft2(rng.standard_normal(shape)) * np.exp(-200 * frequency), shape)
    noise *= scale / noise.std()
    return np.maximum(noise - np.quantile(noise, contact), 0.0)


def uniform_breakdown(gap, voltage, field=AIR_BREAKDOWN_FIELD, at_contact=True):
    """(D, σ_el, ρ) of a uniform gap: the series capacitor, or, where its air field U/h exceeds E_bd, the broken
    column D = ε0 (U − E_bd g)/c with the attraction ε0 E_bd²/2 (ε_a = 1, no slope)."""
    offset = STACK.dielectric_offset
    flux = EPSILON_0 * voltage / (offset + gap)
    if flux > EPSILON_0 * field and (at_contact or gap > 0):
        flux = EPSILON_0 * (voltage - field * gap) / offset
        return flux, 0.5 * EPSILON_0 * field ** 2, flux - EPSILON_0 * field
    return flux, flux ** 2 / (2 * EPSILON_0), 0.0


@pytest.mark.parametrize("shape", [(64,), (24, 32)])
@pytest.mark.parametrize("gap", [0.0, 0.1e-6, 0.3e-6, 1e-6])
@pytest.mark.parametrize("voltage", [50.0, 200.0])
def test_uniform_gap_breaks_down_as_a_series_capacitor(shape, gap, voltage):
    # A uniform gap is one column: unbroken it is Eq. 21; broken, the air drops E_bd g and the solid layers the
    # rest, the charge ρ = D − ε0 E_bd keeps the air field at E_bd and the skin is pulled by ε0 E_bd²/2 (0.54
    # MPa). At 200 V the gaps below U/E_bd − c = 0.23 µm break down, at 50 V none. To round-off (tol 1e-12).
    flux, pressure, charge = uniform_breakdown(gap, voltage)
    lengths = 1e-4 if len(shape) == 1 else (1e-4, 2e-4)
    solution = solve_field(STACK, np.full(shape, gap), lengths, voltage, tol=1e-12, contact_line=BREAKDOWN)
    assert np.allclose(solution.flux, flux, rtol=1e-10, atol=0)
    assert np.allclose(solution.attraction, pressure, rtol=1e-10, atol=0)
    assert np.allclose(solution.charge, charge, rtol=1e-10, atol=1e-12 * flux)
    assert (charge > 0) == (voltage == 200.0 and gap < 0.23e-6)


def test_contact_without_breakdown_keeps_the_full_flux():
    # at_contact=False: a contact pixel has no air, so no charge and the attraction D²/(2 ε0); an open gap still
    # breaks down
    contact = solve_field(STACK, np.zeros(16), 1e-4, 200.0, tol=1e-12, contact_line=AirBreakdown(at_contact=False))
    flux, pressure, _ = uniform_breakdown(0.0, 200.0, at_contact=False)
    assert np.allclose(contact.attraction, pressure, rtol=1e-10) and np.all(contact.charge == 0)
    assert pressure > 2.5 * BREAKDOWN.stress          # Eq. 23, 1.53 MPa, against 0.54 MPa
    opened = solve_field(STACK, np.full(16, 0.1e-6), 1e-4, 200.0, tol=1e-12,
                         contact_line=AirBreakdown(at_contact=False))
    assert np.allclose(opened.attraction, BREAKDOWN.stress, rtol=1e-10)


def test_below_the_breakdown_field_the_layered_field_is_unchanged():
    # an open rough gap at 30 V: no column reaches E_bd, and the active set stays empty: the plain layered field
    gap = rough_gap((32, 40), np.random.default_rng(2), contact=0.0) + 0.2e-6
    plain = solve_field(STACK, gap, (1e-4, 1e-4), 30.0, tol=1e-12)
    broken = solve_field(STACK, gap, (1e-4, 1e-4), 30.0, tol=1e-12, contact_line=BREAKDOWN)
    assert np.max(plain.flux) < EPSILON_0 * AIR_BREAKDOWN_FIELD
    assert np.all(broken.charge == 0)
    assert np.allclose(broken.attraction, plain.attraction, rtol=1e-12, atol=0)


def field_law_energy(law, gap, start=None):
    """(Σ V, arrays) of ``law`` at ``gap``: traction, stiffness, flux, columns."""
    arrays = [np.zeros(gap.shape) for _ in range(4)]
    return law.evaluate(gap, *arrays, start=start), arrays


@pytest.mark.parametrize("traction", ["maxwell", "energy"])
def test_attraction_is_the_virtual_work_at_fixed_deposited_charge(traction):
    # Maxwell: the traction is the derivative of the merit N [H(g) − E_bd ⟨ρ̄ g⟩] at the accepted gap (ρ̄ its own
    # charge): the virtual work with the deposited charge held, ½ Σ (D − ρ̄)² ∂R/∂g. Energy: the derivative of N H,
    # which exceeds it by E_bd ρ per broken column. Central differences (one-sided at contact, second order) at a
    # contact pixel, a broken open pixel, an unbroken near-contact pixel and an open one; step 1e-10 m, relative
    # agreement 1e-5 (measured ≤ 3e-7, the round-off of the smallest attraction; the energy's traction exceeds the
    # Maxwell stress by 0.01–2.8 times it on the broken pixels, median 1.9).
    grid = Grid((64, 48), (6e-5, 5e-5))
    gap = rough_gap(grid.shape, np.random.default_rng(7), contact=0.1, scale=0.6e-6)
    voltage, step = 200.0, 1e-10
    breakdown = AirBreakdown(traction=traction)
    law = FieldLaw(STACK, voltage, grid, tol=1e-13, contact_line=breakdown)
    _, (accepted_traction, _, flux, columns) = field_law_energy(law, gap)
    start = (columns.copy(), flux.copy())
    reference = solve_field(STACK, gap, grid.lengths, voltage, tol=1e-13, contact_line=breakdown)
    assert np.allclose(-accepted_traction, reference.attraction, rtol=1e-9, atol=1e-9 * reference.attraction.max())

    def merit(index, shift):
        shifted = gap.copy()
        shifted[index] += shift
        return field_law_energy(law, shifted, start=start)[0]

    law.evaluate(gap, *[np.zeros(grid.shape) for _ in range(4)], start=(columns, flux))     # ρ̄ of ``gap`` held
    broken = reference.charge > 0
    picks = {"contact": np.flatnonzero((gap == 0).ravel())[0],
             "broken open": np.flatnonzero((broken & (gap > 0)).ravel())[0],
             "unbroken near contact": np.flatnonzero((~broken & (gap > 0) & (gap < 0.3e-6)).ravel())[0],
             "open": int(np.argmax(gap))}
    for name, flat in picks.items():
        index = np.unravel_index(flat, gap.shape)
        if gap[index] == 0:
            derivative = (-3 * merit(index, 0.0) + 4 * merit(index, step) - merit(index, 2 * step)) / (2 * step)
        else:
            derivative = (merit(index, step) - merit(index, -step)) / (2 * step)
        assert derivative == pytest.approx(-accepted_traction[index], rel=1e-5), name
    if traction == "maxwell":                   # the Maxwell stress of a broken flat column, slope terms aside
        assert np.median(reference.attraction[broken]) == pytest.approx(breakdown.stress, rel=0.05)


def test_merit_is_continuous_where_the_solver_accepts_a_step():
    # The solver starts its next evaluation from the accepted one's arrays: evaluating the accepted gap again from
    # them (in place) returns the merit it had as a trial, although the held charge has changed to its own.
    grid = Grid((128, 1), (4e-5, 4e-5 / 128))
    x = (np.arange(128) + 0.5) / 128 - 0.5
    before = np.maximum(2e-6 * x ** 2 * 40 - 0.05e-6, 0.0)[:, None]
    after = np.maximum(before - 0.02e-6, 0.0)
    law = FieldLaw(STACK, 200.0, grid, tol=1e-13, contact_line=BREAKDOWN)
    _, first = field_law_energy(law, before)
    trial_merit, trial = field_law_energy(law, after, start=(first[3], first[2]))
    again = law.evaluate(after, *trial, start=(trial[3], trial[2]))
    assert again == pytest.approx(trial_merit, rel=1e-12)
    # the held charge changed: without the constant the merit would jump by E_bd ⟨Δρ g⟩ (here 1e-3 of it)
    jump = law._last[1] - law._last[2]
    assert abs(jump) > 1e-4 * abs(trial_merit)


def test_field_solution_of_a_broken_field_has_no_energy():
    solution = solve_field(STACK, np.zeros(8), 1e-4, 200.0, contact_line=BREAKDOWN)
    with pytest.raises(ValueError, match="no interaction energy"):
        solution.energy
    assert solve_field(STACK, np.zeros(8), 1e-4, 0.0, contact_line=BREAKDOWN).mean_attraction == 0.0


def test_roughness_film_is_the_layered_field_of_the_shifted_gap():
    grid = Grid((40, 32), (1e-4, 1e-4))
    gap = rough_gap(grid.shape, np.random.default_rng(3))
    film = RoughnessFilm(50e-9)
    shifted = solve_field(STACK, gap + 50e-9, grid.lengths, 150.0, tol=1e-12)
    solution = solve_field(STACK, gap, grid.lengths, 150.0, tol=1e-12, contact_line=film)
    assert np.array_equal(solution.attraction, shifted.attraction)
    law = FieldLaw(STACK, 150.0, grid, tol=1e-12, contact_line=film)
    energy, (traction, *_) = field_law_energy(law, gap)
    assert np.max(np.abs(traction + shifted.attraction)) < 1e-9 * shifted.attraction.max()
    assert energy / gap.size == pytest.approx(shifted.energy, rel=1e-9)


def cylinder(n, contact_line, x0=None):
    """One parabolic cylinder (radius 5 µm) per 20 µm period on the scene's skin (plane strain, E* of its layer) at 1
    kPa and 200 V: the clean model problem of studies/resolution_edges.py."""
    from roughcontact.study.patch import patch_body
    from roughcontact.study.scene import load_scene
    scene = load_scene()
    grid = Grid((n, 1), (20e-6, 20e-6 / n))
    x = (np.arange(n) + 0.5) * 20e-6 / n - 10e-6
    law = ElectrostaticInteraction(scene.screen.stack(), 200.0, contact_line=contact_line)
    return solve_contact((-x * x / 10e-6)[:, None], patch_body(scene, grid=grid), mean_pressure=1e3,
                         interaction=law, tol=1e-8, warn=False, x0=x0)


def refined(result, n):
    """``result`` with its gap interpolated linearly onto ``n`` pixels (a start for the finer solve)."""
    gap = np.asarray(result.gap)[:, 0]
    coarse = np.arange(gap.size + 1) * n / gap.size
    return dataclasses.replace(result, gap=np.interp(np.arange(n), coarse, np.append(gap, gap[0]))[:, None])


def test_breakdown_gives_the_contact_solve_one_equilibrium_at_every_pixel():
    # The cylinder at 156, 78 and 39 nm: with breakdown at contact the cold solves' F_el agree within 1e-3 (measured
    # 5.6e-4) and the solve from the next coarser pixel's equilibrium reaches the cold one (6e-8, the tolerance);
    # without it (a contact pixel keeps D²/(2ε0)) the two starts end 3.9 % apart at 39 nm (2.4 % at 78 nm).
    with_contact = [cylinder(n, BREAKDOWN) for n in (128, 256, 512)]
    forces = [-float(np.mean(result.interaction_traction)) for result in with_contact]
    assert all(result.converged for result in with_contact)
    assert max(forces) / min(forces) - 1 < 1e-3
    warm = cylinder(512, BREAKDOWN, x0=refined(with_contact[1], 512))
    assert -float(np.mean(warm.interaction_traction)) == pytest.approx(forces[2], rel=1e-6)
    bulk = AirBreakdown(at_contact=False)
    cold, coarse = cylinder(512, bulk), cylinder(256, bulk)
    from_coarse = cylinder(512, bulk, x0=refined(coarse, 512))
    spread = float(np.mean(from_coarse.interaction_traction) / np.mean(cold.interaction_traction)) - 1
    assert abs(spread) > 0.02


@pytest.mark.parametrize("make, message", [
    (lambda: AirBreakdown(field=-1.0), "AirBreakdown.field"),
    (lambda: AirBreakdown(field=np.inf), "AirBreakdown.field"),
    (lambda: AirBreakdown(at_contact="yes"), "at_contact"),
    (lambda: AirBreakdown(traction="force"), "AirBreakdown.traction"),
    (lambda: RoughnessFilm(0.0), "RoughnessFilm.thickness"),
    (lambda: check_contact_line(350e6), "contact_line"),
    (lambda: parse_contact_line("film"), "film:<thickness>"),
    (lambda: parse_contact_line("breakdown:-3"), "AirBreakdown.field"),
    (lambda: ElectrostaticInteraction(STACK, 100.0, field="parallel_plate", contact_line=BREAKDOWN), "contact_line"),
    (lambda: ElectrostaticInteraction(STACK, 100.0, frequency=100.0, contact_line=BREAKDOWN), "contact_line"),
    (lambda: ElectrostaticInteraction(STACK, 100.0, contact_line="breakdown"), "contact_line"),
    (lambda: solve_field(STACK, np.zeros(4), 1e-4, 100.0, model="parallel_plate", contact_line=BREAKDOWN),
     "model"),
])
def test_bad_input_names_the_parameter(make, message):
    with pytest.raises((ValueError, TypeError), match=message):
        make()


def test_parse_contact_line_reads_every_form():
    assert parse_contact_line("none") is None
    assert parse_contact_line("breakdown") == AirBreakdown()
    assert parse_contact_line("breakdown:3e8") == AirBreakdown(3e8)
    assert parse_contact_line("breakdown-bulk") == AirBreakdown(at_contact=False)
    assert parse_contact_line("breakdown-energy") == AirBreakdown(traction="energy")
    assert parse_contact_line("film:1e-7") == RoughnessFilm(1e-7)


@pytest.fixture
def field_solve():
    pytest.importorskip("skfem", reason="the finite-element field needs the optional extra roughcontact[fieldcheck]")
    from roughcontact.reference.fem import field_solve_profile
    return field_solve_profile


@pytest.mark.parametrize("gap", [0.0, 0.1e-6, 0.5e-6])
@pytest.mark.parametrize("voltage", [50.0, 200.0])
def test_finite_elements_with_deposited_charge_on_a_uniform_gap(field_solve, gap, voltage):
    # The finite-element reference with the same condition on the air's flux into the insulator: the charge moved
    # from the stratum corneum's face to the insulator's, the opened contact's limit included (P1 holds the
    # piecewise linear 1-D field exactly: round-off, measured ≤ 1e-12)
    flux, pressure, charge = uniform_breakdown(gap, voltage)
    solution = field_solve(STACK, np.full(16, gap), 1e-5, voltage, breakdown=BREAKDOWN)
    assert solution.converged and solution.mean_attraction == pytest.approx(pressure, rel=1e-9)
    assert np.allclose(solution.charge, charge, rtol=1e-9, atol=1e-12 * flux)
    assert solution.mean_maxwell_attraction == pytest.approx(pressure, rel=1e-9)


def test_graded_columns_refine_towards_the_contact_lines():
    from roughcontact.reference.fem import graded_positions
    positions = graded_positions(20e-6, [8e-6, 12e-6], 5e-9, 0.1e-6, ratio=1.15)
    spacing = np.diff(np.append(positions, positions[0] + 20e-6))
    assert np.all(spacing > 0) and positions[0] >= 0 and positions[-1] < 20e-6
    for edge in (8e-6, 12e-6):                      # the nearest columns 2.5 nm either side of each line
        nearest = np.sort(np.abs(positions - edge))[:2]
        assert nearest == pytest.approx([2.5e-9, 2.5e-9], rel=1e-6)
    assert spacing.min() == pytest.approx(5e-9, rel=1e-6) and spacing.max() <= 0.1e-6 * 1.2
    assert np.all(spacing[1:] / spacing[:-1] < 1.15 * 1.25) and np.all(spacing[:-1] / spacing[1:] < 1.15 * 1.25)
    with pytest.raises(ValueError, match="coarsest"):
        graded_positions(20e-6, [8e-6], 1e-7, 1e-8)


@pytest.mark.parametrize("opening, tolerance", [("crack", 0.05), ("hertz", 0.005)])
def test_breakdown_attraction_against_finite_elements_that_resolve_the_contact_line(field_solve, opening, tolerance):
    # The strips of studies/resolution_edges.py: a 4 µm contact strip per 20 µm whose gap opens like a crack
    # (A √s) or like a Hertz contact (s^3/2), at 200 V with air breakdown. The finite elements on columns graded
    # to 20 nm at the lines, the insulator's rows graded as finely from its face, against the layered field at
    # 7.8 nm pixels (converged to 2e-4): measured −1.9 % (crack) and −0.05 % (Hertz); the brief's bar is 5 %.
    from roughcontact.reference.fem import graded_positions
    length, width = 20e-6, 4e-6
    positions = graded_positions(length, [(length - width) / 2, (length + width) / 2], 20e-9, 0.1e-6)

    def gap(x):
        s = np.maximum(np.abs(x - length / 2) - width / 2, 0.0)
        return (3.2e-4 * np.sqrt(s) if opening == "crack" else 0.1e-6 * (s / 2e-6) ** 1.5) + s * s / 100e-6

    fem = field_solve(STACK, gap(positions), length, 200.0, positions=positions, insulator_rows=40,
                      insulator_first=20e-9, breakdown=BREAKDOWN)
    columns = solve_field(STACK, gap((np.arange(2560) + 0.5) * length / 2560), length, 200.0, tol=1e-12,
                          contact_line=BREAKDOWN)
    assert fem.converged
    assert fem.mean_attraction == pytest.approx(columns.mean_attraction, rel=tolerance)


def test_below_breakdown_the_contact_solve_is_the_plain_layered_solve():
    # 30 V on the default scene's 64² patch: no column reaches E_bd, so every field solve of the breakdown law is the
    # plain field's (its sweep on the plain system): the same steps and FFT pairs, the same F_el to round-off
    from roughcontact.study.patch import default_scene_patch
    patch = default_scene_patch(64, 0.5)
    results = [solve_contact(patch.surface, patch.body, mean_pressure=patch.pressure, tol=1e-8, warn=False,
                             interaction=ElectrostaticInteraction(patch.stack, 30.0, contact_line=contact_line))
               for contact_line in (None, BREAKDOWN)]
    plain, broken = results
    assert broken.iterations == plain.iterations and broken.solver.fft_pairs == plain.solver.fft_pairs
    assert broken.electrostatic_force == pytest.approx(plain.electrostatic_force, rel=1e-9)
