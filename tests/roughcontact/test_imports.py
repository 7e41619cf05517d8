"""The modules a macroscopic code imports must be cheap: no numba, no FFT library, no scipy.fft.

Issue #2's bar: ``import roughcontact.macro`` and ``roughcontact.electrostatics`` < 0.5 s without numba or
FFT code. Measured ~0.05-0.1 s (numpy dominates). The test asserts on what a fresh interpreter has imported,
not on how long it took (a shared machine makes timings flaky; the heavy modules are what cost the time).
"""
import subprocess
import sys

import pytest

HEAVY = ("numba", "llvmlite", "pyfftw", "scipy.fft", "matplotlib")


@pytest.mark.parametrize("module", ["roughcontact", "roughcontact.electrostatics", "roughcontact.macro",
                                    "roughcontact.interactions", "surfaces"])
def test_import_is_light(module):
    code = ("import sys; import {m}; "
            "heavy = sorted(n for n in sys.modules if n.startswith({heavy!r})); print({m!r} in sys.modules); "
            "print(heavy)").format(m=module, heavy=HEAVY)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    imported, heavy = out.strip().splitlines()
    assert imported == "True" and heavy == "[]"
