"""The measured-boundary study (studies/measured_boundary.py) runs in fast mode: a window that is itself the
whole periodic surface, declared periodic, reproduces the reference solve; cut windows give one row per window
and variant with errors that are those of the written values."""
import numpy as np
import pytest

pytest.importorskip("SurfaceTopography", reason="the study reads its windows back through SurfaceTopography")


@pytest.fixture(scope="module")
def study(load_experiment):
    return load_experiment("measured_boundary")


def test_the_whole_periodic_surface_declared_periodic_is_the_reference(study, tmp_path, read_csv):
    """One window of a periodic surface is that surface: written to x3p, read back and declared periodic it is
    the reference problem, so its d_eq and A/A0 agree to the solver tolerance (1e-8 on the gap: 1e-6 leaves room);
    the free and mirrored variants are different problems and differ by far more."""
    study.main(["--fast", "--tiles", "1", "--output", str(tmp_path)])
    rows = {row["variant"]: row for row in read_csv(tmp_path / "measured_boundary.csv")}
    assert set(rows) == set(study.VARIANTS)
    assert abs(float(rows["periodic"]["d_eq_error"])) < 1e-6
    assert abs(float(rows["periodic"]["contact_fraction_error"])) < 1e-6
    assert abs(float(rows["free"]["d_eq_error"])) > 1e-3 and abs(float(rows["mirrored"]["d_eq_error"])) > 1e-3


def test_windows_rows_and_summary(study, tmp_path, read_csv, capsys):
    study.main(["--fast", "--output", str(tmp_path)])
    rows = read_csv(tmp_path / "measured_boundary.csv")
    assert len(rows) == 16 * len(study.VARIANTS)                              # 4 x 4 windows
    reference = {row["window"]: row for row in rows if row["variant"] == "inside"}
    for row in rows:
        d_eq, fraction = float(row["d_eq"]), float(row["contact_fraction"])
        assert 0 < d_eq < 3e-6 and 0 < fraction < 1                             # below the 3 µm rms height
        expected = d_eq / float(reference[row["window"]]["d_eq"]) - 1
        assert float(row["d_eq_error"]) == pytest.approx(expected, rel=1e-9, abs=1e-15)
    printed = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in printed] == list(study.VARIANTS)
    assert np.isfinite([float(row["seconds"]) for row in rows]).all()
