"""The modules a macroscopic code imports must be cheap: no numba, no FFT library, no scipy.fft.

Issue #2's bar: ``import roughcontact.macro`` and ``roughcontact.electrostatics`` < 0.5 s without numba or
FFT code. Measured ~0.05-0.1 s (numpy dominates); each check runs in a fresh interpreter.
"""
import subprocess
import sys

import pytest

HEAVY = ("numba", "llvmlite", "pyfftw", "scipy.fft", "matplotlib")


@pytest.mark.parametrize("module", ["roughcontact", "roughcontact.electrostatics", "roughcontact.macro",
                                    "surfaces"])
def test_import_is_light(module):
    code = ("import sys, time; t = time.perf_counter(); import {m}; t = time.perf_counter() - t; "
            "heavy = sorted(n for n in sys.modules if n.startswith({heavy!r})); print(t); print(heavy)"
            ).format(m=module, heavy=HEAVY)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    seconds, heavy = out.strip().splitlines()
    assert heavy == "[]"
    assert float(seconds) < 0.5
