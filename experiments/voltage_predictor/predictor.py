"""One-off: the FFT pairs of a voltage sweep started cold, from the last gap, or from a secant predictor in U².

    ROUGHCONTACT_FFT_THREADS=1 python experiments/voltage_predictor/predictor.py 256 10 20 ... 200

The bench patch (experiments/bench_interactions.py, E* 1 MPa, 1 kPa, tol 1e-8). The sweep starts from the hard
wall at 0 V. "previous" starts each solve from the last result's gap; "secant" from g_k + w (g_k − g_{k−1}),
w = (U² − U_k²)/(U_k² − U_{k−1}²) capped at 3 (the tolerance's noise is amplified by w), clipped at 0.
Printed per voltage: FFT pairs, steps, contact fraction, first residual; then the sweep's total.
"""
import dataclasses
import sys

import numpy as np

sys.path.insert(0, "experiments")
from bench_interactions import patch  # noqa: E402

from roughcontact import ElectrostaticInteraction, solve_contact  # noqa: E402
from roughcontact.electrostatics import DielectricStack  # noqa: E402

LOAD, WEIGHT_CAP = 1e3, 3.0


def start(mode, history, voltage):
    if mode == "cold":
        return None
    (u_before, before), (u_last, last) = history[-2] if len(history) > 1 else history[-1], history[-1]
    if mode == "previous" or len(history) < 2:
        return last
    weight = min((voltage ** 2 - u_last ** 2) / (u_last ** 2 - u_before ** 2), WEIGHT_CAP)
    return dataclasses.replace(last, gap=np.maximum(last.gap + weight * (last.gap - before.gap), 0.0))


def main(n, voltages):
    surface, half = patch(n, 1e6)
    for mode in ("cold", "previous", "secant"):
        history, total = [(0.0, solve_contact(surface, half, mean_pressure=LOAD, tol=1e-8))], 0.0
        for voltage in voltages:
            result = solve_contact(surface, half, mean_pressure=LOAD, tol=1e-8, x0=start(mode, history, voltage),
                                   interaction=ElectrostaticInteraction(DielectricStack(), voltage))
            total += result.params["fft_pairs"]
            print(f"{mode:>8} {voltage:6g} V: {result.params['fft_pairs']:6.1f} pairs, {result.iterations:3d} steps, "
                  f"contact {result.contact_fraction:.4f}, first residual {result.residuals[0]:.2g}")
            history.append((voltage, result))
        print(f"{mode:>8} total: {total:.1f} FFT pairs")


if __name__ == "__main__":
    main(int(sys.argv[1]), [float(v) for v in sys.argv[2:]])
