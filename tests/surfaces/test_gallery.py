"""The surface gallery script runs in its fast mode and writes small pictures and consistent statistics."""
import runpy
import sys
from pathlib import Path

import pytest

from roughcontact.io import read_csv

SCRIPT = Path(__file__).parents[2] / "studies" / "surface_gallery.py"


def test_gallery_fast(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(sys, "argv", [str(SCRIPT), "--fast", "--output", str(tmp_path)])
    runpy.run_path(str(SCRIPT), run_name="__main__")
    assert "written to" in capsys.readouterr().out
    for name in ("fingerprint_classes", "fingerprint_detail", "roughness_hurst"):
        size = (tmp_path / f"{name}.png").stat().st_size
        assert 10_000 < size < 200_000                          # a real picture, small enough for docs/img
    with open(tmp_path / "gallery_statistics.csv") as stream:
        assert stream.readline().startswith("# roughcontact ")        # provenance
    rows = read_csv(tmp_path / "gallery_statistics.csv")
    prints = [row for row in rows if row["field"].startswith("fingerprint")]
    rough = [row for row in rows if row["field"].startswith("self_affine")]
    assert [row["field"].split()[1] for row in prints] == ["arch", "tented_arch", "left_loop", "right_loop",
                                                            "whorl"]
    for row in prints:   # 10 mm windows: the bars (3 % period, 10 % pore density)
        assert float(row["dominant_wavelength_mm"]) == pytest.approx(float(row["requested_period_mm"]), rel=0.03)
        assert float(row["pore_density_cm2"]) == pytest.approx(float(row["requested_pore_density_cm2"]), rel=0.1)
    assert [row["field"] for row in rough] == ["self_affine H=0.3", "self_affine H=0.5", "self_affine H=0.8"]
    for row in rough:    # normalised to the requested 1 µm rms height
        assert float(row["rms_height_um"]) == pytest.approx(1.0, rel=1e-9)
