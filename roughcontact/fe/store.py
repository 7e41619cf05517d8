"""Finished press-and-slide runs on disk, so that an interrupted FE sweep resumes (numpy only).

:class:`RunStore` keeps one ``.npz`` file per (f_N, μ) run in ``directory`` (written to a temporary name and
renamed, so a file is whole or absent). Each file carries the fingerprint of what produced it (the model's
every parameter, the travel step and limit, the roughcontact and FElupe versions) and a SHA-256 digest of its
arrays; a file that cannot be read, was written for another model or version, or whose arrays do not match
their digest is named in a :class:`StaleRunWarning` and its run is computed again.
"""
from __future__ import annotations

import hashlib
import json
import os
import warnings
import zipfile
from pathlib import Path

import numpy as np

from .._version import __version__
from .model import ContactSnapshot, SlidingRun

#: The array fields of a :class:`~roughcontact.fe.model.SlidingRun`, stored as they are.
_RUN_ARRAYS = ("travel", "tangential_force", "contact_normal_force", "bone_tangential_force", "length",
               "length_gap", "slipping", "pressed_points", "final_points", "cells", "material")
#: The fields of each :class:`~roughcontact.fe.model.ContactSnapshot`, stored concatenated over the snapshots.
_SNAPSHOT_ARRAYS = ("x", "normal", "tangential", "gap", "slip")


class StaleRunWarning(UserWarning):
    """A stored run that cannot be reused (damaged, edited, another model's or version's): it is run again."""


def run_fingerprint(model, normal_force: float, travel_step: float | None, max_travel: float,
                    solver_version: str) -> str:
    """SHA-256 of everything that determines a run: ``repr(model)`` (every parameter, exact floats), f_N [N/m],
    the travel step (None: the default) and limit [m], and the versions of roughcontact and of the solver."""
    text = json.dumps([repr(model), repr(float(normal_force)), repr(travel_step), repr(float(max_travel)),
                       __version__, solver_version])
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _digest(arrays: dict) -> str:
    sha = hashlib.sha256()
    for name in sorted(arrays):
        value = np.ascontiguousarray(arrays[name])
        sha.update(f"{name}:{value.dtype.str}:{value.shape}".encode("ascii"))
        sha.update(value.tobytes())
    return sha.hexdigest()


def _arrays(run: SlidingRun) -> dict:
    arrays = {name: np.asarray(getattr(run, name)) for name in _RUN_ARRAYS}
    arrays["snapshot_sizes"] = np.array([len(s.x) for s in run.snapshots], dtype=np.int64)
    for name in _SNAPSHOT_ARRAYS:
        arrays[f"snapshot_{name}"] = np.concatenate([getattr(s, name) for s in run.snapshots])
    arrays["scalars"] = np.array([run.normal_force, run.friction, run.seconds, run.cpu_seconds], dtype=float)
    arrays["flags"] = np.array([run.full_slip, run.converged], dtype=bool)
    return arrays


def _run(arrays: dict) -> SlidingRun:
    bounds = np.concatenate([[0], np.cumsum(arrays["snapshot_sizes"])])
    snapshots = tuple(ContactSnapshot(**{name: arrays[f"snapshot_{name}"][a:b] for name in _SNAPSHOT_ARRAYS})
                      for a, b in zip(bounds[:-1], bounds[1:]))
    normal_force, friction, seconds, cpu_seconds = (float(v) for v in arrays["scalars"])
    full_slip, converged = (bool(v) for v in arrays["flags"])
    return SlidingRun(normal_force=normal_force, friction=friction, seconds=seconds, cpu_seconds=cpu_seconds,
                      full_slip=full_slip,
                      converged=converged, snapshots=snapshots, **{name: arrays[name] for name in _RUN_ARRAYS})


class RunStore:
    """Finished runs in ``directory`` (created if missing), one file per (f_N, μ) (module docstring)."""

    def __init__(self, directory):
        self.directory = Path(directory)
        self.directory.mkdir(exist_ok=True)

    def path(self, normal_force: float, friction: float) -> Path:
        return self.directory / f"run_fN{float(normal_force):.6g}_mu{float(friction):.6g}.npz"

    def load(self, fingerprint: str, normal_force: float, friction: float) -> SlidingRun | None:
        """The stored run of (f_N [N/m], μ) written with ``fingerprint``, or None (not stored, or stale: warned)."""
        path = self.path(normal_force, friction)
        if not path.exists():
            return None
        try:
            with np.load(path, allow_pickle=False) as stored:
                arrays = {name: stored[name] for name in stored.files}
            meta = json.loads(str(arrays.pop("meta")))
        except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile) as error:
            return _stale(path, f"cannot be read ({type(error).__name__}: {error})")
        if meta.get("fingerprint") != fingerprint:
            return _stale(path, "written for another model, travel step or version")
        if meta.get("digest") != _digest(arrays):
            return _stale(path, "its arrays do not match their digest (edited or damaged)")
        try:
            run = _run(arrays)
        except (KeyError, ValueError, TypeError) as error:
            return _stale(path, f"is not a complete run ({type(error).__name__}: {error})")
        if (run.normal_force, run.friction) != (float(normal_force), float(friction)):
            return _stale(path, f"holds f_N = {run.normal_force:g} N/m, μ = {run.friction:g}")
        return run

    def save(self, fingerprint: str, run: SlidingRun) -> Path:
        """Write ``run`` under its (f_N, μ) with ``fingerprint`` (atomically: to a temporary name, then renamed)."""
        arrays = _arrays(run)
        meta = json.dumps({"fingerprint": fingerprint, "digest": _digest(arrays)})
        path = self.path(run.normal_force, run.friction)
        temporary = path.with_name(path.name + ".part")
        with open(temporary, "wb") as handle:
            np.savez(handle, meta=np.array(meta), **arrays)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(temporary, path)
        return path


def _stale(path: Path, reason: str) -> None:
    warnings.warn(f"stored run {path}: {reason}; it is run again", StaleRunWarning, stacklevel=3)
    return None
