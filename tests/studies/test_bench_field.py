"""The layered field's benchmark runs in fast mode and its rows are self-consistent (no timing is asserted)."""
import pytest


@pytest.fixture(scope="module")
def rows(fast_run, read_csv):
    return read_csv(fast_run("bench_field") / "bench_field.csv")


FIELDS = ("parallel_plate", "layered", "parallel_plate_matched", "parallel_plate_local")   # --fast includes --matched


def test_both_fields_on_both_patches(rows):
    assert {(r["patch"], r["field"]) for r in rows} == {(patch, field) for patch in ("bench", "scene")
                                                        for field in FIELDS}
    assert all(r["converged"] == "True" for r in rows)
    for patch in ("bench", "scene"):
        plate, layered = (next(r for r in rows if r["patch"] == patch and r["field"] == field)
                          for field in ("parallel_plate", "layered"))
        assert float(plate["fft_pair_ratio"]) == 1.0 and float(layered["fft_pair_ratio"]) > 1.0
        # the layered field attracts more than the per-pixel law at the same load
        assert float(layered["electrostatic_force_N"]) > float(plate["electrostatic_force_N"])


def test_the_field_solves_are_counted_within_the_solves_fft_pairs(rows):
    for row in rows:
        field_pairs, evaluations = int(row["field_fft_pairs"]), int(row["field_evaluations"])
        if row["field"] != "layered":
            assert field_pairs == evaluations == 0
        else:           # every evaluation costs its start's pair; all of them are part of the solve's count
            assert evaluations > 0 and evaluations <= field_pairs < float(row["fft_pairs"])


@pytest.mark.parametrize("reference", ["parallel_plate_matched", "parallel_plate_local"])
def test_the_matched_solves_attract_as_much_as_the_layered_one(rows, load_experiment, reference):
    """Each matched per-pixel solve's own F_el (not the search's stored ratio alone) is within the search's
    tolerance of the layered solve's: the stack's own law at a higher voltage than the nominal one (the layered field
    attracts more), the law of the layered field's pixel elastance ε0 M_ii < c at a lower one (it attracts more
    than the layered field wherever the gap closes: in contact the layered flux is U/c, its flux U/(ε0 M_ii))."""
    tolerance = load_experiment("bench_field").MATCH_TOL
    for patch in ("bench", "scene"):
        layered, matched = (next(r for r in rows if r["patch"] == patch and r["field"] == field)
                            for field in ("layered", reference))
        ratio = float(matched["electrostatic_force_N"]) / float(layered["electrostatic_force_N"])
        assert abs(ratio - 1) <= tolerance
        assert ratio == pytest.approx(float(matched["matched_force_ratio"]), rel=1e-12)
        higher = float(matched["matched_voltage_V"]) > float(matched["voltage_V"])
        assert higher == (reference == "parallel_plate_matched")
        assert layered["matched_voltage_V"] == ""


def test_the_local_stack_has_the_layered_fields_pixel_elastance(load_experiment):
    """The per-pixel law of ``parallel_plate_local`` has the offset ε0 M_ii of the layered field on its grid, and
    only the offset changed (the air's permittivity, so the law's gap scale, is the stack's)."""
    from surfaces import Grid
    from roughcontact.electrostatics import EPSILON_0, DielectricStack, StackField
    stack, grid = DielectricStack(), Grid((64, 64), (1e-3, 1e-3), periodic=True)
    local = load_experiment("bench_field").local_stack(stack, grid)
    pixel = StackField(stack, grid).pixel_elastance * EPSILON_0
    assert local.dielectric_offset == pytest.approx(pixel, rel=1e-13)
    assert pixel < stack.dielectric_offset and local.eps_a == stack.eps_a
