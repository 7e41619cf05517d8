"""The speed-accuracy experiment (studies/preset_pareto.py) runs in fast mode: the reference has error 0,
the errors are the relative differences of the realisation means, the cost adds up over realisations, a re-run
solves nothing again, and its per-setting table feeds roughcontact.study.presets."""
import json

import numpy as np
import pytest

from roughcontact.io import Provenance
from roughcontact.study.presets import choose, error_floor, read_table, write_table


@pytest.fixture(scope="module")
def output(load_experiment, fast_run):
    return load_experiment("preset_pareto"), fast_run("preset_pareto")


def test_rows_cover_every_setting_scene_and_realisation_count(output, read_csv):
    module, path = output
    rows = read_csv(path / "preset_pareto.csv")
    plan = module.settings_grid(type("Args", (), {"fast": True})())
    assert len(plan) == 3 and plan[0][0] == module.FAST["reference"]
    assert len(rows) == len(module.VARIANTS) * sum(count for _, count in plan) == 18
    for row in rows:
        if int(row["grid"]) == 48 and int(row["realisations"]) == 2:          # the reference itself
            assert float(row["error"]) == 0.0
        assert float(row["reference_ci"]) > 0
    # the error is the largest of the three; the cost of two realisations is that of one plus the second's
    for row in rows:
        parts = [float(row[k]) for k in ("d_eq_error", "ridge_area_error", "friction_error")]
        assert float(row["error"]) == max(parts)
    for variant in module.VARIANTS:
        mine = [r for r in rows if r["variant"] == variant and r["tolerance"] == "1e-07" and r["grid"] == "32"]
        one, two = sorted(mine, key=lambda r: int(r["realisations"]))
        assert 0 < float(one["cpu_seconds"]) < float(two["cpu_seconds"])


def test_d_eq_error_is_the_relative_difference_of_the_realisation_means(output, read_csv):
    module, path = output
    rows = read_csv(path / "preset_pareto.csv")
    setting = {**module.FAST["reference"], "grid": 32, "tolerance": 1e-7}

    def d_eq(setting, count):            # mean over the first ``count`` realisations, each cached on its own
        records = [json.loads((path / "runs" / "default" / module.setting_name(setting) / f"r{r}.json").read_text())
                   for r in range(count)]
        return np.mean([[[point["equivalent_gap"][0] for point in row] for row in record["points"]]
                        for record in records], axis=0)

    expected = np.max(np.abs(d_eq(setting, 2) / d_eq(module.FAST["reference"], 2) - 1))
    row = next(r for r in rows if r["variant"] == "default" and r["grid"] == "32" and r["tolerance"] == "1e-07"
               and r["realisations"] == "2")
    assert float(row["d_eq_error"]) == pytest.approx(expected, rel=1e-12)
    # 32² raises the roughness cut-off from 10 to 56 µm against 42 µm at 48²: a difference of several per cent
    assert 0.02 < expected < 0.5


def test_rerun_solves_nothing_again(output):
    module, path = output
    runs = sorted((path / "runs").rglob("r*.json"))
    stamps = [run.stat().st_mtime_ns for run in runs]
    module.main(["--fast", "--output", str(path)])
    assert sorted((path / "runs").rglob("r*.json")) == runs
    assert [run.stat().st_mtime_ns for run in runs] == stamps


def test_settings_table_feeds_the_choice(output, read_csv, tmp_path):
    module, path = output
    entries = module.setting_rows(module.rows_of(type("Args", (), {"fast": True})(), path / "runs"))
    table = read_table(write_table(entries, Provenance("test", {}), tmp_path / "table.csv"))
    assert len(table) == 6
    # without the discretisation columns the reference promises no better than the smallest error measured
    # against it, which a cheaper setting already meets; below it the choice is refused (issue 26)
    floor = error_floor(table)[0]
    assert floor == min(entry.error for entry in table if entry.error > 0)
    best = choose(floor, table)
    assert best.error == floor
    assert best.cpu_seconds == min(entry.cpu_seconds for entry in table if entry.error <= floor)
    with pytest.raises(ValueError, match="cannot be promised"):
        choose(0.5 * floor, table)
    loose = choose(1.0, table)                  # every finite error meets 100 %: the cheapest such setting
    assert loose.cpu_seconds == min(entry.cpu_seconds for entry in table if np.isfinite(entry.error))
