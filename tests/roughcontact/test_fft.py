"""FFT backends: agreement with numpy.fft and with each other, buffer protocol, bad input."""
import numpy as np
import pytest

from roughcontact.fft import PyFFTW, ScipyFFT, make_backend

SHAPES = [(8, 8), (7, 5), (16, 1), (6, 9)]


def _forward_backward(backend, real):
    array = backend.empty()
    array[...] = real
    backend.forward(array)
    spectrum = backend.spectrum.copy()
    out = backend.empty()
    backend.backward(out)
    return spectrum, out, array


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("name", ["pyfftw", "scipy"])
def test_matches_numpy_and_pair_scales_by_size(name, shape):
    real = np.random.default_rng(1).standard_normal(shape)
    backend = make_backend(name, shape)
    spectrum, out, array = _forward_backward(backend, real)
    # double-precision transforms of O(1) data of <= 64 points: round-off ~1e-15
    np.testing.assert_allclose(spectrum, np.fft.rfft2(real), rtol=0, atol=1e-12)
    np.testing.assert_allclose(out, real * real.size, rtol=0, atol=1e-12)   # unnormalised pair
    np.testing.assert_array_equal(array, real)                              # forward keeps its input


@pytest.mark.parametrize("dtype, atol", [(np.float64, 1e-12), (np.float32, 2e-5)])
@pytest.mark.parametrize("threads", [1, 2])
def test_pyfftw_and_scipy_agree_to_round_off(dtype, atol, threads):
    shape = (32, 18)
    real = np.random.default_rng(2).standard_normal(shape).astype(dtype)
    results = [_forward_backward(make_backend(name, shape, dtype, threads), real) for name in ("pyfftw", "scipy")]
    (spectrum_a, out_a, _), (spectrum_b, out_b, _) = results
    assert spectrum_a.dtype == spectrum_b.dtype == (np.complex128 if dtype == np.float64 else np.complex64)
    scale = np.abs(spectrum_b).max()
    np.testing.assert_allclose(spectrum_a, spectrum_b, rtol=0, atol=atol * scale)
    np.testing.assert_allclose(out_a, out_b, rtol=0, atol=atol * real.size * np.abs(real).max())


def test_foreign_arrays_go_through_a_copy():
    """Unaligned or non-contiguous arrays give the same transform as aligned ones."""
    shape = (12, 10)
    real = np.random.default_rng(3).standard_normal(shape)
    backend = PyFFTW(shape)
    strided = np.zeros((12, 20))[:, ::2]
    strided[...] = real
    backend.forward(strided)
    np.testing.assert_allclose(backend.spectrum, np.fft.rfft2(real), atol=1e-12)
    out = np.zeros((12, 20))[:, ::2]
    backend.backward(out)
    np.testing.assert_allclose(out, real * real.size, atol=1e-11)
    np.testing.assert_array_equal(strided, real)


def test_planning_effort_does_not_clobber_results():
    shape = (16, 16)
    real = np.random.default_rng(4).standard_normal(shape)
    spectrum, _, _ = _forward_backward(PyFFTW(shape, planner_effort="FFTW_MEASURE"), real)
    np.testing.assert_allclose(spectrum, np.fft.rfft2(real), atol=1e-12)


@pytest.mark.parametrize("kwargs, word", [
    ({"name": "numpy"}, "backend"),
    ({"threads": 0}, "threads"),
    ({"threads": 1.5}, "threads"),
    ({"dtype": np.int32}, "dtype"),
    ({"planner_effort": "FAST"}, "planner_effort"),
])
def test_bad_input_names_the_parameter(kwargs, word):
    arguments = {"name": "pyfftw", "shape": (4, 4), **kwargs}
    with pytest.raises(ValueError, match=word):
        make_backend(**arguments)


def test_scipy_backend_type():
    backend = make_backend("scipy", (4, 6), np.float32, threads=2)
    assert isinstance(backend, ScipyFFT) and backend.spectrum.shape == (4, 4) and backend.threads == 2


def test_defaults_use_every_core_and_measured_plans_cached_as_wisdom(monkeypatch, tmp_path):
    import os

    from roughcontact import fft

    monkeypatch.delenv(fft.THREADS_VARIABLE, raising=False)
    monkeypatch.delenv(fft.PLANNER_VARIABLE, raising=False)
    monkeypatch.setenv(fft.CACHE_VARIABLE, str(tmp_path))
    assert fft.default_threads() == len(os.sched_getaffinity(0))
    backend = fft.PyFFTW((16, 12))
    assert backend.threads == len(os.sched_getaffinity(0)) and backend.planner_effort == "FFTW_MEASURE"
    assert fft.wisdom_path().parent == tmp_path and fft.wisdom_path().exists()      # measured once, kept
    monkeypatch.setenv(fft.THREADS_VARIABLE, "3")
    monkeypatch.setenv(fft.PLANNER_VARIABLE, "FFTW_ESTIMATE")
    assert fft.PyFFTW((8, 8)).threads == 3 and fft.PyFFTW((8, 8)).planner_effort == "FFTW_ESTIMATE"
    monkeypatch.setenv(fft.THREADS_VARIABLE, "many")
    with pytest.raises(ValueError, match="ROUGHCONTACT_FFT_THREADS"):
        fft.default_threads()


def test_pyfftw_is_imported_without_dask_array():
    # pyfftw.interfaces imports dask.array where dask is installed (1.5 s per process and pool worker); the
    # backend imports pyfftw without it, and dask.array stays importable afterwards
    pytest.importorskip("dask.array")
    import subprocess
    import sys
    code = ("import sys; from roughcontact.fft import PyFFTW; PyFFTW((8, 8), planner_effort='FFTW_ESTIMATE'); "
            "print('dask.array' in sys.modules); import dask.array.fft; print(callable(dask.array.fft.fft))")
    output = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert output.split() == ["False", "True"]
