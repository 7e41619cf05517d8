"""The FE fingertip's contact reduction at the friction level of the finger, like for like with Sirin et al. 2019b
and the seed's Eq. 44 (numpy only: reads an FE summary table).

    python studies/fe_friction_level.py --output out                    # the packaged table (default mesh)
    python studies/fe_friction_level.py --output out --summary DIR/fingertip_fe_summary.csv

At each F_N (0.5–2 N) and U (0, 100 V) the seed's friction law (Table 1, fitted to Sirin et al. 2019a's finger)
gives F_T/F_N = μ (μ0 = 0.26 at 0 V) and its reduction c₂ F_T²/A_R0² (Eq. 44). The FE compares at the same
F_T/F_N: its section at f_N = F_N/w (w the footprint's width, ``roughcontact.fe.feed``) and contact friction
μ_eff = F_T/F_N reaches full slip at f_T = μ_eff f_N, where its reduction is 1 − L/L0 (the linear mapping
A/A0 = L/L0) or 1 − (L/L0)² (isotropic). Beside them: the friction law's FE-fed reduction (the Eq. 34 fit at the
same f_T), and Sirin et al. 2019b's measured apparent-area reductions at the onset of sliding (oiled finger):
8 % / 13 % at 1 N (0 / 100 V), 15 % / 20 % at 2 N. Writes ``fe_friction_level.csv`` (one row per F_N, U) and
``fe_friction_level_exponent.csv`` (the reduction's growth per doubling of F_N, 1 → 2 N, per column) and prints
the μ at which the FE would reach the measured reductions.
"""
from __future__ import annotations

import argparse

import numpy as np

from roughcontact.fe.feed import PACKAGED_SUMMARY, FEAreaReduction
from roughcontact.io.provenance import output_directory, parse_arguments, write_csv
from roughcontact.macro import SlidingFrictionModel

#: Sirin et al. 2019b: relative apparent-area reduction at the onset of sliding, {(F_N [N], U [V]): reduction}.
SIRIN_2019B = {(1.0, 0.0): 0.08, (1.0, 100.0): 0.13, (2.0, 0.0): 0.15, (2.0, 100.0): 0.20}
FORCES = (0.5, 1.0, 1.5, 2.0)
VOLTAGES = (0.0, 100.0)


def level_rows(table: FEAreaReduction) -> list:
    seed = SlidingFrictionModel.paper_table1()
    rows = []
    for force in FORCES:
        for voltage in VOLTAGES:
            state = seed.state(force, voltage)
            mu = float(state.friction_coefficient)
            line = float(table.line_load(force))
            initial, xi, sliding = (float(v) for v in table.eq34(line, mu))
            ratio = sliding / initial
            rows.append({"normal_force_N": force, "voltage_V": voltage, "line_load_N_per_m": line,
                         "friction_F_T_over_F_N": mu,
                         "fe_reduction_linear": 1 - ratio, "fe_reduction_isotropic": 1 - ratio ** 2,
                         "fe_fed_reduction_linear": xi * (mu * line) ** 2 / initial,
                         "seed_eq44_reduction": float(state.area_reduction),
                         "sirin_2019b_reduction": SIRIN_2019B.get((force, voltage), float("nan"))})
    return rows


def exponent_rows(rows: list) -> list:
    """Reduction at 2 N over that at 1 N (per doubling of F_N) per column and voltage."""
    columns = ("fe_reduction_linear", "fe_reduction_isotropic", "fe_fed_reduction_linear", "seed_eq44_reduction",
               "sirin_2019b_reduction")
    out = []
    for voltage in VOLTAGES:
        at = {row["normal_force_N"]: row for row in rows if row["voltage_V"] == voltage}
        for column in columns:
            ratio = at[2.0][column] / at[1.0][column]
            out.append({"voltage_V": voltage, "column": column, "ratio_per_doubling": ratio,
                        "exponent": float(np.log2(ratio))})
    return out


def friction_for(table: FEAreaReduction, force: float, target: float, isotropic: bool) -> float:
    """The contact friction μ at which the FE's reduction at full slip reaches ``target`` at F_N [N] (nan if no μ
    of the table does)."""
    mus = np.linspace(table.frictions[0], table.frictions[-1], 2001)
    initial, _, sliding = table.eq34(np.full_like(mus, float(table.line_load(force))), mus)
    reduction = 1 - (sliding / initial) ** (2 if isotropic else 1)
    above = np.flatnonzero(reduction >= target)
    return float(mus[above[0]]) if above.size else float("nan")


def _needed(table, force, target, isotropic) -> str:
    mu = friction_for(table, force, target, isotropic)
    return f"<= {mu:.3g}" if mu == table.frictions[0] else f"{mu:.3g}"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default="out")
    parser.add_argument("--summary", default=str(PACKAGED_SUMMARY), help="an FE summary table")
    args, provenance = parse_arguments(parser, argv, "python studies/fe_friction_level.py")
    output = output_directory(args.output)
    table = FEAreaReduction.from_summary(args.summary)
    rows = level_rows(table)
    write_csv(output / "fe_friction_level.csv", rows, provenance, echo=True)
    write_csv(output / "fe_friction_level_exponent.csv", exponent_rows(rows), provenance, echo=True)
    for (force, voltage), measured in SIRIN_2019B.items():
        print(f"F_N = {force:g} N, U = {voltage:g} V: Sirin 2019b {measured:.0%} needs mu_eff = "
              f"{_needed(table, force, measured, False)} (linear), {_needed(table, force, measured, True)} (isotropic)")


if __name__ == "__main__":
    main()
