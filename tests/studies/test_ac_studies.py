"""The AC drive's study scripts run in fast mode and their rows are self-consistent (no timing is asserted)."""
import math

import pytest


@pytest.fixture(scope="module")
def sweep(fast_run, read_csv):
    return read_csv(fast_run("ac_drive") / "ac_drive.csv")


def test_sweep_runs_from_dc_to_the_dielectric_limit(sweep):
    frequencies = [float(row["frequency_Hz"]) for row in sweep]
    assert frequencies[0] == 0.0 and frequencies[-1] == math.inf and frequencies == sorted(frequencies)
    assert all(row["converged"] == "True" for row in sweep)
    # DC: its surrogate is the DC law, no correction; a lossy drive corrects at least once; ∞ is the energy solve
    assert sweep[0]["corrections"] == "0" == sweep[-1]["corrections"]
    assert all(int(row["corrections"]) >= 1 for row in sweep[1:-1])
    # on a fixed gap ⟨σ̄⟩ falls with the frequency; each frequency's equilibrium is solved cold, and near a snap-in
    # two cold paths may end a contact pixel apart: one of the 4096 moves ⟨σ̄⟩ by about 3e-4 (3162 Hz ended at
    # 2.539 % contact, 10 kHz at 2.563 %: 19.040 against 19.045 kPa), so the solved ⟨σ̄⟩ falls to within 1e-3
    fixed = [float(row["fixed_mean_pressure_Pa"]) for row in sweep]
    assert all(a >= b for a, b in zip(fixed, fixed[1:])) and fixed[0] > fixed[-1]
    solved = [float(row["mean_pressure_Pa"]) for row in sweep]
    assert all(a >= b * (1 - 1e-3) for a, b in zip(solved, solved[1:])) and solved[0] > 1.05 * solved[-1]
    assert float(sweep[-1]["ratio_to_dielectric"]) == 1.0 == float(sweep[-1]["fixed_ratio_to_dielectric"])
    # the dielectric limit's AC-equivalent gap is its field-equivalent gap; the crossovers lie inside the sweep
    assert float(sweep[-1]["ac_equivalent_gap_m"]) == pytest.approx(float(sweep[-1]["field_equivalent_gap_m"]))
    measured, circuit = float(sweep[0]["fixed_measured_crossover_Hz"]), float(sweep[0]["fixed_circuit_crossover_Hz"])
    assert 10 < measured < 1e4 and circuit == pytest.approx(measured, rel=0.05)
    # the solved equilibria's halfway point: on 64² a snap-in between 1 and 3 kHz moves it (1586 Hz, circuit 1173)
    assert 10 < float(sweep[0]["measured_crossover_Hz"]) < 1e4


def test_bench_of_the_drive_reports_every_solve(fast_run, read_csv):
    rows = read_csv(fast_run("bench_ac_drive") / "bench_ac_drive.csv")
    assert [row["solve"] for row in rows] == ["dielectric", "dc-direct", "ac-drive", "surrogate"]
    assert all(row["converged"] == "True" for row in rows)
    for row in rows:
        corrections = float(row["correction_fft_pairs"])
        assert (corrections > 0) == (row["solve"] == "ac-drive") and corrections < float(row["fft_pairs"])
    drive = rows[2]
    assert sum(int(i) for i in drive["solve_iterations"].split()) == int(drive["iterations"])


def test_bench_counts_two_fft_pairs_per_cocg_iteration(fast_run, read_csv):
    rows = read_csv(fast_run("bench_ac") / "bench_ac.csv")
    assert {row["method"] for row in rows} == {"dielectric", "cocg", "gmres-block", "bicgstab-block", "fft-pair-real",
                                               "fft-pair-complex"}
    for row in rows:
        if row["method"].startswith("fft-pair"):
            continue
        assert float(row["residual"]) <= 1e-10
        if row["method"] == "cocg":
            assert int(row["fft_pairs"]) == 2 * (int(row["iterations"]) + 1)


def test_deferred_correction_converges(fast_run, read_csv):
    rows = read_csv(fast_run("ac_coupling") / "ac_coupling.csv")
    for frequency in {row["frequency_Hz"] for row in rows}:
        for surrogate in ("dielectric", "matched"):
            changes = [float(row["gap_change"]) for row in rows
                       if row["frequency_Hz"] == frequency and row["surrogate"] == surrogate and row["gap_change"]]
            # a contraction: each correction moves the gap less than the last, three steps gain two digits
            assert all(b <= a for a, b in zip(changes, changes[1:])) and changes[-1] < 1e-2 * changes[0]


def test_leak_sweep_falls_towards_dc_where_the_plain_drive_rises(fast_run, read_csv):
    """studies/ac_leak.py in fast mode (64², one realisation, DC, 100 Hz, 10 kHz): with the gap's conducting
    medium F_el vanishes at DC and falls below its 10 kHz value at 100 Hz; without it F_el rises towards DC."""
    rows = read_csv(fast_run("ac_leak") / "ac_leak.csv")
    leak = [row for row in rows if row["scene"] == "leak"]
    plain = [row for row in rows if row["scene"] == "no_leak"]
    assert [float(row["frequency_Hz"]) for row in leak] == [0.0, 100.0, 1e4] == [float(row["frequency_Hz"])
                                                                                   for row in plain]
    forces = [float(row["electrostatic_force_N"]) for row in leak]
    assert forces[0] == 0.0 < forces[1] < 0.5 * forces[2] and float(leak[-1]["ratio_to_highest"]) == 1.0
    assert float(plain[0]["ratio_to_highest"]) > float(plain[1]["ratio_to_highest"]) > 1.0
    assert all(row["converged"] == row["realisations"] == "1" for row in rows)
