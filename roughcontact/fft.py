"""Real 2-D FFT backends: plans made once per shape, executed many times on caller or internal buffers.

A backend serves one transform ``shape`` (real) and owns the half spectrum ``spectrum`` (complex,
``(shape[0], shape[1]//2 + 1)``). :meth:`forward(real)` maps a real array into ``spectrum`` and
:meth:`backward(out)` maps ``spectrum`` into the real array ``out``; both are **unnormalised** (a pair
multiplies by ``shape[0]*shape[1]``), so a caller folds ``1/N`` into its Fourier multiplier once.
``backward`` may overwrite ``spectrum``; ``forward`` never writes its input. Arrays from :meth:`empty` are
used in place (no copy); other arrays of the right shape work too, through a copy.

* ``"pyfftw"`` (default): FFTW plans made once at construction on SIMD-aligned buffers and re-pointed at the
  caller's arrays (``update_arrays``) at every call; ``planner_effort`` is an FFTW flag
  (``"FFTW_ESTIMATE"`` plans instantly, ``"FFTW_MEASURE"`` times candidate plans and runs faster),
  ``threads`` FFTW threads. Measured plans are kept as FFTW wisdom in a cache file (:func:`wisdom_path`), so
  each shape is measured once per machine, not once per process.

Defaults (``threads=None``, ``planner_effort=None``): the cores this process may run on
(``$ROUGHCONTACT_FFT_THREADS`` overrides; a pool worker sets 1) and ``FFTW_MEASURE``
(``$ROUGHCONTACT_FFTW_PLANNER`` overrides; the test suite uses ``FFTW_ESTIMATE``).

* ``"scipy"``: ``scipy.fft`` with ``workers=threads``; always available, agrees with pyFFTW to round-off
  (``scipy.fft`` cannot write into a given buffer, so each call allocates its result).

A backend is not thread-safe (``spectrum`` is shared state); use one per worker process or thread.
"""
from __future__ import annotations

import os
import pickle
import tempfile
from pathlib import Path

import numpy as np
import scipy.fft

from surfaces.validation import check_choice, check_integer

BACKENDS = ("pyfftw", "scipy")
PLANNER_EFFORTS = ("FFTW_ESTIMATE", "FFTW_MEASURE", "FFTW_PATIENT", "FFTW_EXHAUSTIVE")
_COMPLEX = {np.dtype(np.float64): np.complex128, np.dtype(np.float32): np.complex64}
THREADS_VARIABLE = "ROUGHCONTACT_FFT_THREADS"
PLANNER_VARIABLE = "ROUGHCONTACT_FFTW_PLANNER"
CACHE_VARIABLE = "ROUGHCONTACT_CACHE"
DEFAULT_PLANNER = "FFTW_MEASURE"
_wisdom_known = {}             # wisdom file -> the wisdom this process last read from it or wrote to it
_planned = set()               # (wisdom file, shape, dtype, threads, effort) planned and saved by this process


def default_threads() -> int:
    """FFT threads when none are given: ``$ROUGHCONTACT_FFT_THREADS``, else the cores this process may run on."""
    value = os.environ.get(THREADS_VARIABLE)
    if value:
        if not value.strip().isdigit() or int(value) < 1:
            raise ValueError(f"{THREADS_VARIABLE} = {value!r} must be a whole number >= 1")
        return int(value)
    return available_cores()


def available_cores() -> int:
    """The cores this process may run on (its affinity; all cores where the platform has none)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:                 # (no affinity on this platform)
        return os.cpu_count() or 1


def default_planner() -> str:
    """FFTW planner flag when none is given: ``$ROUGHCONTACT_FFTW_PLANNER``, else ``FFTW_MEASURE``."""
    return check_choice(PLANNER_VARIABLE, os.environ.get(PLANNER_VARIABLE) or DEFAULT_PLANNER, PLANNER_EFFORTS)


def _pyfftw():
    """The ``pyfftw`` module, imported without its dask interface: ``pyfftw.interfaces`` imports ``dask.array``
    wherever dask is installed (1.5 s of the 2.2 s import, measured with ``python -X importtime``), which every
    process and pool worker would pay for an interface that is not used here. Where ``dask.array`` is already
    imported, pyFFTW imports as usual."""
    import sys
    if "pyfftw" in sys.modules or "dask.array" in sys.modules:
        import pyfftw
        return pyfftw
    sys.modules["dask.array.fft"] = None               # makes pyfftw's optional "from dask.array.fft import" fail
    try:
        import pyfftw
    finally:
        del sys.modules["dask.array.fft"]
    return pyfftw


def wisdom_path() -> Path:
    """The FFTW wisdom cache: ``$ROUGHCONTACT_CACHE`` (default ``~/.cache/roughcontact``), one file per pyFFTW
    version."""
    pyfftw = _pyfftw()
    root = Path(os.environ.get(CACHE_VARIABLE) or Path.home() / ".cache" / "roughcontact")
    return root / f"fftw-wisdom-pyfftw-{pyfftw.__version__}.pickle"


def _import_wisdom(pyfftw):
    path = wisdom_path()
    if path in _wisdom_known:
        return
    try:
        with open(path, "rb") as stream:
            pyfftw.import_wisdom(pickle.load(stream))
    except (OSError, pickle.UnpicklingError, ValueError, TypeError, EOFError):
        pass                               # no cache yet, or an unreadable one: plans are measured afresh
    _wisdom_known[path] = pyfftw.export_wisdom()


def _save_wisdom(pyfftw):
    """Write this process's FFTW wisdom to the cache file if planning added to it (atomically; an unwritable
    cache is skipped)."""
    path, wisdom = wisdom_path(), pyfftw.export_wisdom()
    if wisdom == _wisdom_known.get(path):
        return
    _wisdom_known[path] = wisdom
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile("wb", dir=path.parent, delete=False) as stream:
            pickle.dump(wisdom, stream)
        os.replace(stream.name, path)
    except OSError:
        pass


def _check_dtype(dtype) -> np.dtype:
    dtype = np.dtype(dtype)
    if dtype not in _COMPLEX:
        raise ValueError(f"dtype = {dtype} is not supported; choose float64 or float32")
    return dtype


def _check_threads(threads) -> int:
    return check_integer("threads", threads, low=1)


def spectrum_shape(shape) -> tuple:
    """Shape of the half spectrum of a real ``shape`` array: ``(n0, n1//2 + 1)``."""
    return (shape[0], shape[1] // 2 + 1)


class ScipyFFT:
    """``scipy.fft`` backend (always available). See the module docstring for the protocol."""

    name = "scipy"

    def __init__(self, shape, dtype=np.float64, threads=None):
        self.shape = tuple(int(n) for n in shape)
        self.dtype = _check_dtype(dtype)
        self.threads = default_threads() if threads is None else _check_threads(threads)
        self.spectrum = np.zeros(spectrum_shape(self.shape), _COMPLEX[self.dtype])
        self._work = None

    def empty(self) -> np.ndarray:
        return np.empty(self.shape, self.dtype)

    def work_array(self) -> np.ndarray:
        """A real array of ``shape`` owned by the backend, for a caller's padding (allocated once)."""
        if self._work is None:
            self._work = self.empty()
        return self._work

    def forward(self, real):
        self.spectrum[...] = scipy.fft.rfft2(real, workers=self.threads)

    def backward(self, out):
        out[...] = scipy.fft.irfft2(self.spectrum, s=self.shape, norm="forward", workers=self.threads)


class PyFFTW:
    """pyFFTW backend: plans built once on aligned buffers, re-pointed at aligned caller arrays."""

    name = "pyfftw"

    def __init__(self, shape, dtype=np.float64, threads=None, planner_effort=None):
        pyfftw = _pyfftw()
        self._pyfftw = pyfftw
        self.shape = tuple(int(n) for n in shape)
        self.dtype = _check_dtype(dtype)
        self.threads = default_threads() if threads is None else _check_threads(threads)
        self.planner_effort = (default_planner() if planner_effort is None
                               else check_choice("planner_effort", planner_effort, PLANNER_EFFORTS))
        measured = self.planner_effort != "FFTW_ESTIMATE"
        if measured:
            _import_wisdom(pyfftw)
        self._scratch = self.empty()              # planning buffer; later the copy target of foreign arrays
        self.spectrum = pyfftw.empty_aligned(spectrum_shape(self.shape), _COMPLEX[self.dtype])
        self._forward = pyfftw.FFTW(self._scratch, self.spectrum, axes=(0, 1), direction="FFTW_FORWARD",
                                    flags=(self.planner_effort,), threads=self.threads)
        self._backward = pyfftw.FFTW(self.spectrum, self._scratch, axes=(0, 1), direction="FFTW_BACKWARD",
                                     flags=(self.planner_effort, "FFTW_DESTROY_INPUT"), threads=self.threads)
        if measured:
            key = (wisdom_path(), self.shape, self.dtype, self.threads, self.planner_effort)
            if key not in _planned:             # a plan made before in this process added its wisdom then
                _save_wisdom(pyfftw)
                _planned.add(key)

    def empty(self) -> np.ndarray:
        """An uninitialised real array of ``shape`` that the plans use in place."""
        return self._pyfftw.empty_aligned(self.shape, self.dtype)

    def work_array(self) -> np.ndarray:
        """The aligned planning buffer, lent to a caller for its padding (saves one transform-sized array);
        while the caller uses it, foreign arrays must not be passed to :meth:`forward`/:meth:`backward`."""
        return self._scratch

    def _usable(self, array) -> bool:
        # the strides too: numpy calls a one-element view contiguous whatever its strides (the real part of a
        # complex 1 × 1 array has strides (16, 16)), and a plan refuses arrays with other strides than its own
        return (array.dtype == self.dtype and array.shape == self.shape and array.flags.c_contiguous
                and array.strides == self._scratch.strides and array.ctypes.data % self._pyfftw.simd_alignment == 0)

    def forward(self, real):
        if not self._usable(real):
            np.copyto(self._scratch, real)
            real = self._scratch
        self._forward.update_arrays(real, self.spectrum)
        self._forward.execute()

    def backward(self, out):
        target = out if self._usable(out) and out.flags.writeable else self._scratch
        self._backward.update_arrays(self.spectrum, target)
        self._backward.execute()
        if target is not out:
            np.copyto(out, target)


def make_backend(name, shape, dtype=np.float64, threads=None, planner_effort=None):
    """Backend ``name`` (``"pyfftw"`` or ``"scipy"``) for real transforms of ``shape`` (defaults: module
    docstring)."""
    check_choice("backend", name, BACKENDS)
    if name == "pyfftw":
        return PyFFTW(shape, dtype, threads, planner_effort)
    if planner_effort is not None:
        check_choice("planner_effort", planner_effort, PLANNER_EFFORTS)
    return ScipyFFT(shape, dtype, threads)
