"""studies/validation_measurements.py: its helpers against closed forms, its fast run's tables against the pages
that quote them, and its fixed-gap field solves against the study's own records."""
import math

import numpy as np
import pytest

from roughcontact.macro import SlidingFrictionModel
from roughcontact.study import load_scene, run_study


@pytest.fixture(scope="module")
def study(load_experiment):
    return load_experiment("validation_measurements")


@pytest.fixture(scope="module")
def fast(fast_run):
    return fast_run("validation_measurements")


def test_the_stand_in_is_the_seeds_fit(study):
    """F_el/F_N of the stand-in is μ/μ0 − 1 of the seed's Table 1: 1.6 / 1.2 / 1.0 / 0.97 at 200 V (the numbers
    quoted in docs/findings), 0 at 0 V; a wrong μ0 or law would move them."""
    forces = np.array(study.SIRIN_LOADS)
    assert study.stand_in(forces, 200.0) == pytest.approx([1.591, 1.190, 1.039, 0.964], abs=2e-3)
    assert np.all(study.stand_in(forces, 0.0) == 0.0)
    mu = SlidingFrictionModel.paper_table1().friction_coefficient(1.0, 100.0)
    assert study.mu(study.stand_in(1.0, 100.0)) == pytest.approx(mu, rel=1e-14)


def test_closed_forms(study):
    """The readings' voltages, the first-order leak, Guo's power law through its end points."""
    assert study.reading_voltage(200.0, "amplitude") == 141.421 and study.reading_voltage(100.0, "RMS") == 100.0
    for reported in (100.0, 200.0):                               # every voltage a table reads is solved
        for reading in study.READINGS:
            assert study.index(study.VOLTAGES, study.reading_voltage(reported, reading)) >= 0
            assert study.index(study.DRAFT_VOLTAGES, study.reading_voltage(reported, reading)) >= 0
    assert study.GUO_SINE == pytest.approx(150 / (2 * math.sqrt(2)), abs=5e-4) and study.GUO_SQUARE == 75.0
    assert study.first_order(250.0) == 0.5 and study.first_order(125.0) == pytest.approx(0.2)
    assert study.guo_law([0.5, 4.5]) == pytest.approx([2.5e-6, 1.5e-6], rel=1e-14)
    middle = study.guo_law(1.5)                                   # a power law: equal ratios for equal factors
    assert middle / study.guo_law(0.5) == pytest.approx(study.guo_law(4.5) / middle, rel=1e-12)
    with pytest.raises(ValueError, match="is not one of"):
        study.index(study.VOLTAGES, 141.42)


def test_the_implied_gap_inverts_eq21(study):
    """The stand-in's field-equivalent gap gives back its F_el through Eq. 21 over A0, in either reading."""
    central = run_study(load_scene(text=study.scene_text([1.0], [0.0], "standard", True)), workers=1)
    stack, area = central.scene.screen.stack(), central.array("apparent_area")[0, 0]
    for reading, scale in study.READINGS.items():
        gap = study.implied_gap(central, 1.0, 200.0, reading)
        force = stack.attraction(gap, 200.0 * scale) * area
        assert force == pytest.approx(study.stand_in(1.0, 200.0) * 1.0, rel=1e-12)


def test_extra_gap_interpolates_and_brackets(study):
    """On a made-up attraction e^(−t/1 µm): the exact t at a node, between nodes log-linear (so exact here), 0
    above the t = 0 value, inf below the last."""
    attraction = np.exp(-np.array(study.EXTRA_GAPS) / 1e-6)[None, None, None, :, None] * np.ones((1, 1, 2, 1, 3))
    gaps = {"attraction": attraction}
    assert study.extra_gap_needed(gaps, math.exp(-1.5), 0, 0, 1) == pytest.approx(1.5e-6, rel=1e-12)
    assert study.extra_gap_needed(gaps, math.exp(-2.2), 0, 0, 1) == pytest.approx(2.2e-6, rel=1e-12)
    assert study.extra_gap_needed(gaps, 2.0, 0, 0, 0) == 0.0
    assert study.extra_gap_needed(gaps, math.exp(-20), 0, 0, 0) == math.inf


def test_the_pages_quote_every_table(study, fast):
    """Each page's generated blocks are tables of the run, every table sits in a page, and filling a page
    changes only its blocks (an unknown block name fails)."""
    tables = {}
    for part in (fast / "tables.md").read_text().split("## ")[1:]:
        name, _, text = part.partition("\n\n")
        tables[name] = text.strip()
    named = [name for page in study.PAGES.values() for name in study.page_blocks(page.read_text())]
    assert sorted(named) == sorted(tables)
    for page in study.PAGES.values():
        text = page.read_text()
        filled = study.fill_page(text, tables)
        assert study.BLOCK.sub("", filled) == study.BLOCK.sub("", text)
        assert study.page_blocks(filled) == study.page_blocks(text)
    with pytest.raises(KeyError):
        study.fill_page("<!-- begin nothing -->\n| a |\n<!-- end nothing -->", tables)


def test_the_central_numbers_nest_their_intervals(fast, read_csv):
    """numbers.csv: the sampling interval holds the mean and the total interval holds the sampling one (the
    discretisation widens it both ways: the preset's error of F_el is a magnitude); no force at 0 V; the stand-in
    only within the seed's 0–2.3 N."""
    rows = read_csv(fast / "numbers.csv")
    assert len(rows) == 5 * 9
    for row in rows:
        value = {key: float(text) for key, text in row.items()}
        if value["voltage_V"] == 0:
            assert value["fel_over_fn"] == 0.0
            continue
        assert value["fel_over_fn_low"] <= value["fel_over_fn"] <= value["fel_over_fn_high"]
        assert value["fel_over_fn_total_low"] < value["fel_over_fn_low"]
        assert value["fel_over_fn_total_high"] > value["fel_over_fn_high"]
        gap = [value[f"field_equivalent_gap{suffix}_um"] for suffix in ("_low", "", "_high")]
        assert gap[0] < gap[1] < gap[2]
        assert math.isnan(value["stand_in_mu"]) == (value["normal_force_N"] > 2.3)


def test_the_samples_ratios(study, fast, read_csv):
    """sample.csv: each ratio is (1 + F_el/F_N)/(1 + stand-in) of its own columns, in both readings."""
    rows = read_csv(fast / "sample.csv")
    assert len(rows) == study.FAST_SAMPLES * (len(study.SAMPLED) + 2)
    for row in rows:
        for force in study.SAMPLE_LOADS:
            for reported in (100.0, 200.0):
                for reading in study.READINGS:
                    solved = float(row[f"x_{force:g}N_{study.reading_voltage(reported, reading):g}V"])
                    expected = (1 + solved) / (1 + study.stand_in(force, reported))
                    ratio = float(row[f"ratio_{force:g}N_{reported:g}V_{reading}"])
                    assert ratio == pytest.approx(expected, rel=1e-12)


def test_the_fixed_gap_solves_reproduce_the_studys_equilibria(study, fast):
    """gaps.npz at t = 0 on the gap solved at 200 V is the study's own F_el of that realisation (the same chain of
    solves, recomputed independently of the task store): within the field solve's tolerance; the attraction
    falls as the extra gap grows, and the 0 V gap attracts less than the gap solved at the voltage."""
    gaps = np.load(fast / "gaps.npz")
    central = run_study(load_scene(text=study.scene_text(study.LOADS, study.VOLTAGES, "standard", True)),
                        tasks=fast / "tasks", workers=1)
    assert central.computed == 0                                  # read back from the fast run's task directory
    for j, voltage in enumerate(gaps["voltages"]):
        column = study.index(central.voltages, voltage)
        for i, force in enumerate(gaps["forces"]):
            point = central.points[study.index(central.normal_forces, force)][column]
            records = np.array(point.electrostatic_attraction)
            assert gaps["attraction"][i, j, 1, 0] == pytest.approx(records, rel=1e-6)
    attraction = gaps["attraction"]
    assert np.all(np.diff(attraction, axis=3) < 0)
    assert np.all(attraction[:, :, 0] < attraction[:, :, 1])
    assert np.all((0 < gaps["contact_share"]) & (gaps["contact_share"] < 1))
