"""The κ study (studies/contact_area_coefficient.py) runs in fast mode and writes sane, self-consistent files."""
import numpy as np
import pytest
from PIL import Image

from roughcontact.solvers import PERIMETER_CORRECTION


@pytest.fixture(scope="module")
def study(load_experiment):
    return load_experiment("contact_area_coefficient")


@pytest.fixture(scope="module")
def output(fast_run):
    return fast_run("contact_area_coefficient")


def test_files_written_with_provenance(output):
    for name in ("contact_area_coefficient.csv", "contact_area_summary.csv"):
        assert (output / name).read_text().startswith("# roughcontact ")
    with Image.open(output / "contact_area_coefficient.png") as image:
        assert image.format == "PNG"
        assert "command: python studies/contact_area_coefficient.py --fast" in image.text["Comment"]


def test_rows_consistent(study, output, read_csv):
    rows = read_csv(output / "contact_area_coefficient.csv")
    solved = [row for row in rows if float(row["load"]) > 0]
    assert {row["series"] for row in rows} == {"resolution", "breadth", "ensemble"}
    assert len(solved) == 5 * len(rows) // 6                     # five loads + one extrapolated row per case
    for row in solved:
        load, fraction = float(row["load"]), float(row["contact_fraction"])
        assert row["converged"] == "True"
        # κ is A/A0 over p̄/(E* h'); the surfaces are normalised to the spectral slope 0.1 exactly
        assert float(row["kappa_pixels"]) == pytest.approx(fraction / load, rel=1e-12)
        assert float(row["rms_slope_spectral"]) == pytest.approx(study.RMS_SLOPE, rel=1e-9)
        # central differences see less slope than the band-limited field (at most 1, ≈ 0.87 at λ_s = 4 px)
        assert 0.8 < float(row["rms_slope_fd"]) / study.RMS_SLOPE < 1
        # corrected area = pixel area − 0.1178 × boundary edges: smaller, and exactly so
        n2 = int(row["n"]) ** 2
        corrected = (fraction * n2 - PERIMETER_CORRECTION * int(row["boundary_edges"])) / n2 / load
        assert float(row["kappa_corrected"]) == pytest.approx(corrected, rel=1e-12)
        assert float(row["kappa_corrected"]) < float(row["kappa_pixels"])
        assert 1 <= int(row["patches"]) <= fraction * n2
        # fast mode's tiny grids measure κ_corrected from 2.16 to 3.96 (above Persson's √(8/π) = 1.60: coarse
        # pixels and few contacts); the band keeps 8 % either side
        assert 2.0 < float(row["kappa_corrected"]) < 4.3


def test_summary_means(output, read_csv):
    rows = read_csv(output / "contact_area_coefficient.csv")
    summary = read_csv(output / "contact_area_summary.csv")
    for entry in summary:
        values = [float(row["kappa_pixels"]) for row in rows if all(row[key] == entry[key] for key in
                                                                     ("series", "n", "breadth", "load"))]
        assert len(values) == int(entry["seeds"]) == 2
        assert float(entry["kappa_pixels_mean"]) == pytest.approx(np.mean(values), rel=1e-12)
        assert float(entry["kappa_pixels_std"]) == pytest.approx(np.std(values, ddof=1), rel=1e-9, abs=1e-15)


def test_extrapolation_recovers_a_line(study):
    # straight lines up to the fit limit p̄ = 0.01 E* h'; the larger loads (set to 0) must be left out of the fit
    rows = [{"load": p, "kappa_pixels": 2.5 - 10 * p if p <= 0.01 else 0.0, "kappa_corrected": 2.2 - 5 * p,
             "kappa_pixels_fd_slope": 2.0, "patches": 50, "converged": True} for p in study.LOADS]
    row = study.extrapolated(rows)
    assert row["load"] == 0 and row["kappa_pixels"] == pytest.approx(2.5, rel=1e-12)
    assert row["kappa_corrected"] == pytest.approx(2.2, rel=1e-12)
