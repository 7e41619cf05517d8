"""Input validation shared by ``surfaces`` and ``roughcontact``.

Every check raises ``ValueError`` (or ``TypeError`` for a wrong kind of object) whose message names the
parameter, the offending value and the valid range, as the project's standards require.
"""
from __future__ import annotations

import math
from numbers import Real

import numpy as np


def plain(value) -> str:
    """``repr`` of ``value`` with numpy scalars printed as plain numbers (``-1.0``, not ``np.float64(-1.0)``)."""
    return repr(value.item() if isinstance(value, np.generic) else value)


def check_real(name: str, value, *, low=None, high=None, low_open=False, high_open=False,
               allow_none=False):
    """Return ``float(value)`` after checking it is a finite real number in the given range.

    ``low``/``high`` bound the range; ``*_open`` makes that bound exclusive. ``None`` bounds are absent.
    """
    if value is None and allow_none:
        return None
    if isinstance(value, bool) or not isinstance(value, (Real, np.floating, np.integer)):
        raise TypeError(f"{name} must be a real number, got {plain(value)} of type {type(value).__name__}")
    value = float(value)
    lo = "-inf" if low is None else f"{low:g}"
    hi = "inf" if high is None else f"{high:g}"
    interval = f"{'(' if low_open or low is None else '['}{lo}, {hi}{')' if high_open or high is None else ']'}"
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value!r}; valid range {interval}")
    if low is not None and (value < low or (low_open and value == low)):
        raise ValueError(f"{name} = {value!r} is out of range; valid range {interval}")
    if high is not None and (value > high or (high_open and value == high)):
        raise ValueError(f"{name} = {value!r} is out of range; valid range {interval}")
    return value


def check_positive(name: str, value, *, allow_none=False):
    """Return ``float(value)`` after checking it is finite and strictly positive."""
    return check_real(name, value, low=0.0, low_open=True, allow_none=allow_none)


def check_integer(name: str, value, *, low=None, high=None) -> int:
    """Return ``int(value)`` after checking it is an integer (not a bool) in ``[low, high]``."""
    lo = "-inf" if low is None else str(low)
    hi = "inf" if high is None else str(high)
    if (isinstance(value, bool) or not isinstance(value, (int, np.integer))
            or (low is not None and value < low) or (high is not None and value > high)):
        raise ValueError(f"{name} must be an integer in [{lo}, {hi}], got {plain(value)}")
    return int(value)


def check_finite_array(name: str, values, *, nonnegative=False, dtype=np.float64) -> np.ndarray:
    """Return ``values`` as a float array after checking there is no NaN/inf (and no negative entry)."""
    if np.iscomplexobj(values):
        raise TypeError(f"{name} must be real, got complex values (dtype {np.asarray(values).dtype}); "
                        "pass the real part explicitly if that is what is meant")
    try:
        array = np.asarray(values, dtype=dtype)
    except (TypeError, ValueError) as error:
        raise TypeError(f"{name} must be an array of real numbers, got {type(values).__name__}") from error
    finite = np.isfinite(array)
    if not finite.all():
        bad = array[~finite].flat[0]
        raise ValueError(f"{name} must be finite everywhere; found {plain(bad)} at "
                         f"{np.argwhere(~finite)[0].tolist()} (valid range: finite reals)")
    if nonnegative and (array < 0).any():
        raise ValueError(f"{name} must be >= 0 everywhere; minimum is {plain(array.min())} "
                         "(valid range [0, inf))")
    return array


def check_bool(name: str, value) -> bool:
    """Return ``bool(value)`` after checking it is a ``bool`` or ``numpy.bool_`` (a truthy string is refused)."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False, got {plain(value)} of type {type(value).__name__}")
    return bool(value)


def check_broadcast(**arrays) -> tuple:
    """The named arrays, each checked by :func:`check_finite_array` and broadcast to their common shape;
    ``ValueError`` naming them and their shapes if they do not broadcast."""
    checked = [check_finite_array(name, values) for name, values in arrays.items()]
    try:
        return tuple(np.broadcast_arrays(*checked))
    except ValueError:
        shapes = ", ".join(f"{name} {array.shape}" for name, array in zip(arrays, checked))
        raise ValueError(f"shapes do not broadcast: {shapes}; give equal shapes, scalars or numpy-broadcastable "
                         "shapes") from None


def check_choice(name: str, value, choices):
    """Return ``value`` after checking it is one of ``choices`` (which may mix kinds, e.g. ``None`` and strings;
    a value that cannot be compared with them, such as a list or an array, is not one)."""
    try:
        valid = bool(value in choices)
    except (TypeError, ValueError):             # unhashable in a set; an array's ambiguous truth value
        valid = False
    if not valid:
        listed = sorted(choices, key=lambda choice: (choice is None, type(choice).__name__, choice))
        raise ValueError(f"{name} = {plain(value)} is not valid; choose one of {listed}")
    return value


def check_rng(rng) -> tuple:
    """``(numpy Generator, int seed or None)`` from ``rng`` as ``numpy.random.default_rng`` takes it (None, an int
    seed >= 0, a SeedSequence, a BitGenerator or a Generator); a fresh seed is drawn and returned for None. The
    seed is the one that regenerates the stream: the int, or the entropy of an unspawned SeedSequence."""
    if rng is None:
        rng = np.random.SeedSequence().entropy
    if isinstance(rng, (int, np.integer)) and not isinstance(rng, bool):
        if rng < 0:
            raise ValueError(f"rng = {int(rng)} is a negative seed; valid range: int seeds >= 0, or a "
                             "numpy.random.Generator, SeedSequence or BitGenerator")
        return np.random.default_rng(int(rng)), int(rng)
    if isinstance(rng, (np.random.Generator, np.random.BitGenerator, np.random.SeedSequence)):
        replayable = isinstance(rng, np.random.SeedSequence) and not rng.spawn_key \
            and isinstance(rng.entropy, int) and rng.pool_size == np.random.SeedSequence().pool_size
        return np.random.default_rng(rng), (rng.entropy if replayable else None)
    raise TypeError(f"rng must be None, an int seed >= 0, or a numpy.random.Generator, SeedSequence or "
                    f"BitGenerator; got {type(rng).__name__}")
