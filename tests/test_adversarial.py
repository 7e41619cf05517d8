"""The adversarial audit of the public API and the command line (issue 26), kept and re-run.

Each row is one call a user could make by mistake (wrong types, NaN/inf, negative sizes, empty arrays, zero,
huge values, mismatched shapes, missing/empty/corrupt files, wrong extensions) and its expected outcome:

* ``right(check)``: the call returns, and ``check`` (against an independent value where cheap) holds;
* ``refused(kind, *fragments)``: it raises ``kind`` whose message holds every fragment (case-insensitive): the
  parameter's or file's name and the offending value, often the valid range;
* CLI rows: exit code != 0, exactly one line on stderr, no traceback.

No row may stall (every solve here is on a 16² or 32² grid with a small ``maxiter`` where it matters), give a
NaN, or raise anything else. docs/dev/investigations.md ("The adversarial audit") summarises the table.
"""
from __future__ import annotations

import contextlib
import math
import functools
import io
import os
import pickle
import runpy
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from surfaces import Grid, HeightField, MissingDataWarning, self_affine
from surfaces.heightfield import harmonic_fill
from surfaces.topography import from_topography, read_topography
from roughcontact import (ContactProblem, DielectricStack, ElasticHalfSpace, ElectrostaticInteraction,
                          ExponentialAdhesion, HardWall, MaugisDugdale, solve_contact)
from roughcontact.interactions import Interaction
from roughcontact.io.provenance import Provenance
from roughcontact.io.results import ConvergenceWarning
from roughcontact.solvers import ContactResult, load_cycle, pull_off
from roughcontact import macro, paper
from roughcontact.electrostatics import solve_field
from roughcontact.study import friction_recipe, load_scene, open_results, run_study, scene_at_preset
from roughcontact.study.presets import error_floor


# ---------------------------------------------------------------------------------------------- expectations

@dataclass(frozen=True)
class right:
    """The call returns and ``check(value)`` holds; with ``warns``, it warns that (and nothing else)."""
    check: object = None
    warns: type | None = None


@dataclass(frozen=True)
class refused:
    """The call raises ``kind`` with every fragment in its message (case-insensitive)."""
    kind: type
    fragments: tuple

    def __init__(self, kind, *fragments):
        object.__setattr__(self, "kind", kind)
        object.__setattr__(self, "fragments", fragments)


# ---------------------------------------------------------------------------------------------- shared inputs

@functools.cache
def grid16():
    return Grid((16, 16), (1e-4, 1e-4), periodic=True)


@functools.cache
def surface16():
    return self_affine(grid16(), hurst=0.8, rms_height=1e-6, rng=0)


@functools.cache
def half16():
    return ElasticHalfSpace(grid16(), E_star=1e6)


@functools.cache
def hard16():
    return solve_contact(surface16(), half16(), mean_pressure=1e3)


@functools.cache
def exponential16():
    return solve_contact(surface16(), half16(), mean_pressure=1e3,
                         interaction=ExponentialAdhesion(work_of_adhesion=1e-3, length=1e-7))


def flat16(offset=0.0):
    return HeightField(grid16(), np.full(grid16().shape, offset))


@dataclass(frozen=True)
class NoLength(Interaction):
    """A user's law that forgot ``length``."""
    work_of_adhesion: float = 1e-3

    def energy(self, gap):
        return -self.work_of_adhesion * np.exp(-np.asarray(gap) / 1e-7)

    def traction(self, gap):
        return self.energy(gap) / 1e-7

    def stiffness(self, gap):
        return -self.energy(gap) / 1e-14


@dataclass(frozen=True)
class NaNLaw(Interaction):
    """A user's law whose traction is NaN beyond some gap."""
    length: float = 1e-7

    def energy(self, gap):
        return np.where(np.asarray(gap) < 1e-6, -1e-3, np.nan)

    def traction(self, gap):
        return np.where(np.asarray(gap) < 1e-6, 0.0, np.nan)

    def stiffness(self, gap):
        return np.zeros_like(np.asarray(gap, float))


@dataclass(frozen=True)
class NegativeLength(Interaction):
    length: float = -1e-7

    def energy(self, gap):
        return np.zeros_like(np.asarray(gap, float))

    traction = stiffness = energy


@dataclass(frozen=True)
class UserExponential(Interaction):
    """ExponentialAdhesion written as a user would: the same equilibrium is the independent reference."""
    work_of_adhesion: float
    length: float

    def energy(self, gap):
        return -self.work_of_adhesion * np.exp(-np.asarray(gap, float) / self.length)

    def traction(self, gap):
        return self.energy(gap) / self.length

    def stiffness(self, gap):
        return -self.energy(gap) / self.length ** 2


#: A 4 × 4 height matrix as text (4 columns: not taken for a column export).
MATRIX = "".join(" ".join(str(4 * i + j + 1) for j in range(4)) + "\n" for i in range(4))


@dataclass(frozen=True)
class NoStiffness(Interaction):
    """ExponentialAdhesion without its stiffness: the base class takes differences of the traction."""
    work_of_adhesion: float = 1e-3
    length: float = 1e-7
    energy = UserExponential.energy
    traction = UserExponential.traction


@dataclass(frozen=True)
class Empty(Interaction):
    """A user's law with a length and nothing else."""
    length: float = 1e-7


def write(path: Path, content) -> Path:
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content)
    return path


def in_tmp(function):
    """A row whose call needs a fresh directory: ``function(tmp_path)``."""
    function.needs_tmp = True
    return function


def close(a, b, rtol):
    return abs(a - b) <= rtol * abs(b)


# ---------------------------------------------------------------------------------------------- the table

G = grid16
STACK = DielectricStack()

ROWS = [
    # --- surfaces.Grid
    ("grid-shape-zero", lambda: Grid((0, 4), (1, 1)), refused(ValueError, "shape[0]", "0", "[1, inf]")),
    ("grid-shape-negative", lambda: Grid((-4, 4), (1, 1)), refused(ValueError, "shape[0]", "-4")),
    ("grid-shape-float", lambda: Grid((4.5, 4), (1, 1)), refused(ValueError, "shape[0]", "4.5")),
    ("grid-shape-string", lambda: Grid("ab", (1, 1)), refused(ValueError, "shape[0]", "'a'")),
    ("grid-shape-3d", lambda: Grid((4, 4, 4), (1, 1, 1)), refused(ValueError, "shape", "(4, 4, 4)")),
    ("grid-lengths-nan", lambda: Grid((4, 4), (1, np.nan)), refused(ValueError, "lengths[1]", "nan")),
    ("grid-lengths-inf", lambda: Grid((4, 4), (np.inf, 1)), refused(ValueError, "lengths[0]", "inf")),
    ("grid-lengths-negative", lambda: Grid((4, 4), (1, -1)), refused(ValueError, "lengths[1]", "-1")),
    ("grid-lengths-zero", lambda: Grid((4, 4), (0, 1)), refused(ValueError, "lengths[0]", "0")),
    ("grid-lengths-count", lambda: Grid((4, 4), (1, 1, 1)), refused(ValueError, "lengths", "(1, 1, 1)")),
    ("grid-periodic-string", lambda: Grid((4, 4), (1, 1), periodic="yes"), refused(TypeError, "periodic", "'yes'")),
    ("grid-refined-zero", lambda: G().refined(0), refused(ValueError, "factor", "0")),
    ("grid-coarsened-nondivisor", lambda: G().coarsened(3), refused(ValueError, "factor", "3")),
    ("grid-coarsened-negative", lambda: G().coarsened(-2), refused(ValueError, "factor", "-2")),
    ("grid-area-right", lambda: Grid((4, 8), (2e-3, 4e-3)).pixel_area, right(lambda a: close(a, 2.5e-7, 1e-15))),

    # --- surfaces.HeightField
    ("hf-shape-mismatch", lambda: HeightField(G(), np.zeros((3, 16))), refused(ValueError, "heights", "(3, 16)", "(16, 16)")),
    ("hf-nan", lambda: HeightField.from_array(np.full((4, 4), np.nan), (1, 1)), refused(ValueError, "heights", "nan")),
    ("hf-inf", lambda: HeightField.from_array(np.full((4, 4), np.inf), (1, 1)), refused(ValueError, "heights", "inf")),
    ("hf-empty", lambda: HeightField.from_array(np.zeros((0, 4)), (1, 1)), refused(ValueError, "heights")),
    ("hf-3d", lambda: HeightField.from_array(np.zeros((2, 2, 2)), (1, 1)), refused(ValueError, "heights", "(2, 2, 2)")),
    ("hf-strings", lambda: HeightField.from_array(np.array([["a", "b"]]), (1, 1)), refused((ValueError, TypeError), "heights")),
    ("hf-scalar-lengths-nonsquare", lambda: HeightField.from_array(np.zeros((4, 8)), 1.0),
     refused(ValueError, "lengths", "1.0")),
    ("hf-pixel-size-negative", lambda: HeightField.from_array(np.zeros((4, 4)), pixel_size=-1e-6),
     refused(ValueError, "pixel_size", "-1e-06")),
    ("hf-lengths-and-pixel", lambda: HeightField.from_array(np.zeros((4, 4)), (1, 1), pixel_size=1e-6),
     refused(ValueError, "lengths", "pixel_size")),
    ("hf-no-size", lambda: HeightField.from_array(np.zeros((4, 4))), refused(ValueError, "lengths", "pixel_size")),
    ("hf-pixel-size-right", lambda: HeightField.from_array(np.zeros((4, 8)), pixel_size=1e-6).grid.lengths,
     right(lambda lengths: np.allclose(lengths, (4e-6, 8e-6)))),
    ("hf-detrend-bogus", lambda: surface16().detrended("bogus"), refused(ValueError, "kind", "'bogus'")),
    ("hf-detrend-plane-right", lambda: HeightField.from_array(
        np.add.outer(np.arange(8.0), 2 * np.arange(8.0)) * 1e-6, (1e-3, 1e-3)).detrended("plane").heights,
     right(lambda h: np.abs(h).max() < 1e-18)),
    ("hf-mirrored-periodic", lambda: surface16().mirrored(), refused(ValueError, "periodic")),
    ("hf-mirrored-right", lambda: HeightField.from_array(np.arange(6.0).reshape(2, 3), (1, 1)).mirrored(),
     right(lambda m: m.shape == (4, 6) and m.grid.fully_periodic and np.array_equal(m.heights[:2, :3],
                                                                                     np.arange(6.0).reshape(2, 3)))),
    ("hf-coarsened-nondivisor", lambda: surface16().coarsened(3), refused(ValueError, "factor", "3")),
    ("hf-add-other-grid", lambda: surface16() + HeightField.from_array(np.zeros((8, 8)), (1e-4, 1e-4), periodic=True),
     refused(ValueError, "grid")),
    ("hf-add-array", lambda: surface16() + np.zeros((16, 16)), refused(TypeError, "HeightField")),
    ("hf-times-nan", lambda: surface16() * np.nan, refused(ValueError, "nan")),
    ("hf-divide-zero", lambda: surface16() / 0.0, refused(ValueError, "0")),
    ("hf-immutable", lambda: surface16().heights.__setitem__((0, 0), 1.0), refused(ValueError, "read-only")),
    ("hf-save-nonexistent-parent", in_tmp(lambda tmp: surface16().save(tmp / "missing" / "s.npz")),
     refused(OSError, "missing")),
    ("hf-save-roundtrip-right", in_tmp(lambda tmp: HeightField.load(surface16().save(tmp / "s.npz"))),
     right(lambda loaded: loaded == surface16())),
    ("hf-load-missing", in_tmp(lambda tmp: HeightField.load(tmp / "none.npz")), refused(OSError, "none.npz")),
    ("hf-load-empty", in_tmp(lambda tmp: HeightField.load(write(tmp / "e.npz", b""))), refused(ValueError, "e.npz")),
    ("hf-load-garbage", in_tmp(lambda tmp: HeightField.load(write(tmp / "g.npz", b"PK\x03\x04garbage" * 10))),
     refused(ValueError, "g.npz")),
    ("hf-load-contact-result", in_tmp(lambda tmp: HeightField.load(hard16().save(tmp / "r.npz"))),
     refused(ValueError, "r.npz")),

    # --- HeightField.read
    ("read-missing", in_tmp(lambda tmp: HeightField.read(tmp / "none.txt", (1, 1))), refused(OSError, "none.txt")),
    ("read-empty", in_tmp(lambda tmp: HeightField.read(write(tmp / "e.txt", ""), (1, 1))), refused(ValueError, "e.txt")),
    ("read-binary", in_tmp(lambda tmp: HeightField.read(write(tmp / "b.txt", bytes(range(256)) * 4), (1, 1))),
     refused(ValueError, "b.txt")),
    ("read-letters", in_tmp(lambda tmp: HeightField.read(write(tmp / "l.txt", "1 2\nx y\n"), (1, 1))),
     refused(ValueError, "l.txt", "line 2")),
    ("read-ragged", in_tmp(lambda tmp: HeightField.read(write(tmp / "r.txt", "1 2 3\n4 5\n"), (1, 1))),
     refused(ValueError, "r.txt")),
    ("read-csv-right", in_tmp(lambda tmp: HeightField.read(write(tmp / "c.csv", MATRIX.replace(" ", ",")), (1, 1), delimiter=",")),
     right(lambda f: np.array_equal(f.heights, np.arange(1.0, 17.0).reshape(4, 4)))),
    ("read-csv-auto", in_tmp(lambda tmp: HeightField.read(write(tmp / "c.csv", MATRIX.replace(" ", ";")), (1, 1))),
     right(lambda f: np.array_equal(f.heights, np.arange(1.0, 17.0).reshape(4, 4)))),
    ("read-xyz-irregular", in_tmp(lambda tmp: HeightField.read(
        write(tmp / "xyz.txt", "0 0 1\n0.3 0 2\n1 0 3\n0 1 4\n1 1 5\n0.5 1 6\n"), layout="columns")),
     refused(ValueError, "xyz.txt")),
    ("read-xyz-right", in_tmp(lambda tmp: HeightField.read(write(tmp / "xyz.txt", "".join(
        f"{x} {y} {10 * x + y}\n" for y in range(3) for x in range(4))), unit=1e-6, lateral_unit=1e-3)),
     right(lambda f: f.shape == (4, 3) and np.allclose(f.grid.spacing, (1e-3, 1e-3))
           and np.isclose(f.heights[3, 2], 32e-6))),
    ("read-unit-negative", in_tmp(lambda tmp: HeightField.read(write(tmp / "u.txt", "1 2\n3 4\n"), (1, 1), unit=-1)),
     refused(ValueError, "unit", "-1")),
    ("read-unit-unknown", in_tmp(lambda tmp: HeightField.read(write(tmp / "u.txt", "1 2\n3 4\n"), (1, 1), unit="furlong")),
     refused(ValueError, "unit", "furlong")),
    ("read-rows-bogus", in_tmp(lambda tmp: HeightField.read(write(tmp / "u.txt", "1 2\n3 4\n"), (1, 1), rows="z")),
     refused(ValueError, "rows", "'z'")),
    ("read-layout-bogus", in_tmp(lambda tmp: HeightField.read(write(tmp / "u.txt", "1 2\n3 4\n"), (1, 1), layout="hex")),
     refused(ValueError, "layout", "'hex'")),
    ("read-missing-bogus", in_tmp(lambda tmp: HeightField.read(write(tmp / "u.txt", "1 2\n3 4\n"), (1, 1), missing="x")),
     refused(ValueError, "missing", "'x'")),
    ("read-skiprows-negative", in_tmp(lambda tmp: HeightField.read(write(tmp / "u.txt", "1 2\n3 4\n"), (1, 1), skiprows=-1)),
     refused(ValueError, "skiprows", "-1")),
    ("read-nan-refused", in_tmp(lambda tmp: HeightField.read(write(tmp / "n.txt", "1 nan 3 4\n5 6 7 8\n"), (1, 1))),
     refused(ValueError, "n.txt", "missing")),
    ("read-nan-filled-right", in_tmp(lambda tmp: HeightField.read(write(tmp / "n.txt", "".join(   # 1 of 25: not warned
        " ".join("nan" if (i, j) == (2, 2) else str(i + j) for j in range(5)) + "\n" for i in range(5))),
        (1, 1), missing="harmonic")), right(lambda f: np.isclose(f.heights[2, 2], 4.0))),
    ("read-directory", in_tmp(lambda tmp: HeightField.read(tmp, (1, 1))), refused(OSError, str(Path("/")))),
    ("read-npy-3d", in_tmp(lambda tmp: HeightField.read(_npy(tmp / "a.npy", np.zeros((2, 2, 2))), (1, 1))),
     refused(ValueError, "a.npy", "(2, 2, 2)")),
    ("read-npy-empty", in_tmp(lambda tmp: HeightField.read(write(tmp / "e.npy", b""), (1, 1))), refused(ValueError, "e.npy")),
    ("read-npy-garbage", in_tmp(lambda tmp: HeightField.read(write(tmp / "g.npy", b"\x93NUMPY garbage" * 8), (1, 1))),
     refused(ValueError, "g.npy")),
    ("read-npy-objects", in_tmp(lambda tmp: HeightField.read(_npy(tmp / "o.npy", np.array([{}, 1], dtype=object)), (1, 1))),
     refused(ValueError, "o.npy", "pickle")),
    ("read-npz-truncated", in_tmp(lambda tmp: HeightField.read(_truncated(surface16().save(tmp / "t.npz")))),
     refused(ValueError, "t.npz")),
    ("read-npz-no-heights", in_tmp(lambda tmp: HeightField.read(_npz(tmp / "a.npz", other=np.zeros(3)), (1, 1))),
     refused(ValueError, "a.npz")),
    ("read-png-extension", in_tmp(lambda tmp: HeightField.read(write(tmp / "a.png", b"\x89PNG\r\n\x1a\n" + bytes(64)),
                                                                (1, 1))),
     refused(ValueError, "a.png")),

    # --- self_affine, fingerprint, fingertip
    ("sa-hurst-zero", lambda: self_affine(G(), hurst=0.0, rms_height=1e-6), refused(ValueError, "hurst", "0")),
    ("sa-hurst-big", lambda: self_affine(G(), hurst=1.5, rms_height=1e-6), refused(ValueError, "hurst", "1.5", "(0, 1]")),
    ("sa-hurst-nan", lambda: self_affine(G(), hurst=np.nan, rms_height=1e-6), refused(ValueError, "hurst", "nan")),
    ("sa-rms-zero", lambda: self_affine(G(), hurst=0.8, rms_height=0.0), refused(ValueError, "rms_height", "0")),
    # a prefactor whose heights overflow (rms 1e154 m) or vanish (1e-96 m) beyond the lengths a grid holds
    ("sa-prefactor-huge", lambda: self_affine(G(), hurst=0.8, prefactor=1e300, rng=1),
     refused(ValueError, "prefactor = 1e+300", "rms", "valid range")),
    ("sa-prefactor-tiny", lambda: self_affine(G(), hurst=0.8, prefactor=1e-200, rng=1),
     refused(ValueError, "prefactor = 1e-200", "rms", "valid range")),
    ("sa-rms-negative", lambda: self_affine(G(), hurst=0.8, rms_height=-1e-6), refused(ValueError, "rms_height", "-1e-06")),
    ("sa-rms-and-slope", lambda: self_affine(G(), hurst=0.8, rms_height=1e-6, rms_slope=0.1),
     refused(ValueError, "rms_height", "rms_slope")),
    ("sa-cutoffs-crossed", lambda: self_affine(G(), hurst=0.8, rms_height=1e-6, short_cutoff=5e-5, long_cutoff=2e-5),
     refused(ValueError, "short_cutoff")),
    ("sa-rng-string", lambda: self_affine(G(), hurst=0.8, rms_height=1e-6, rng="abc"), refused((TypeError, ValueError), "rng")),
    ("sa-grid-array", lambda: self_affine(np.zeros((4, 4)), hurst=0.8, rms_height=1e-6), refused(TypeError, "grid")),
    ("sa-rms-right", lambda: self_affine(G(), hurst=0.8, rms_height=2e-6, rng=1).heights,
     right(lambda h: close(float(np.sqrt(np.mean((h - h.mean()) ** 2))), 2e-6, 1e-9))),
    ("fp-pattern-bogus", lambda: _fingerprint(pattern="spiral"), refused(ValueError, "pattern", "'spiral'")),
    ("fp-period-negative", lambda: _fingerprint(ridge_period=-1e-4), refused(ValueError, "ridge_period", "-0.0001")),
    ("fp-height-nan", lambda: _fingerprint(ridge_height=np.nan), refused(ValueError, "ridge_height", "nan")),
    ("fp-pores-negative", lambda: _fingerprint(pore_density=-1.0), refused(ValueError, "pore_density", "-1")),
    ("fp-grid-tuple", lambda: _fingerprint(grid=(16, 16)), refused(TypeError, "grid")),
    ("ft-radii-negative", lambda: _fingertip(radii=(-1e-3, 1e-3)), refused(ValueError, "radii", "-0.001")),
    ("ft-shape-bogus", lambda: _fingertip(shape="cube"), refused(ValueError, "shape", "'cube'")),

    # --- ElasticHalfSpace and layered bodies
    ("ehs-estar-zero", lambda: ElasticHalfSpace(G(), E_star=0.0), refused(ValueError, "E_star", "0")),
    ("ehs-estar-negative", lambda: ElasticHalfSpace(G(), E_star=-1e6), refused(ValueError, "E_star", "-1000000")),
    ("ehs-estar-nan", lambda: ElasticHalfSpace(G(), E_star=np.nan), refused(ValueError, "E_star", "nan")),
    ("ehs-estar-inf", lambda: ElasticHalfSpace(G(), E_star=np.inf), refused(ValueError, "E_star", "inf")),
    ("ehs-estar-string", lambda: ElasticHalfSpace(G(), E_star="1e6"), refused((TypeError, ValueError), "E_star", "1e6")),
    ("ehs-grid-array", lambda: ElasticHalfSpace(np.zeros((4, 4)), E_star=1e6), refused(TypeError, "grid")),
    ("ehs-thickness-negative", lambda: ElasticHalfSpace(G(), E_star=1e6, thickness=-1e-5, poisson=0.3),
     refused(ValueError, "thickness", "-1e-05")),
    ("ehs-poisson-big", lambda: ElasticHalfSpace(G(), E_star=1e6, thickness=1e-5, poisson=0.7),
     refused(ValueError, "poisson", "0.7")),
    ("ehs-layer-no-poisson", lambda: ElasticHalfSpace(G(), E_star=1e6, thickness=1e-5), refused(TypeError, "poisson", "None")),
    ("ehs-bottom-bogus", lambda: ElasticHalfSpace(G(), E_star=1e6, thickness=1e-5, poisson=0.3, bottom="glued"),
     refused(ValueError, "bottom", "'glued'")),
    ("ehs-substrate-no-layer", lambda: ElasticHalfSpace(G(), E_star=1e6, substrate_E_star=1e5),
     refused(ValueError, "substrate_E_star", "thickness")),
    ("ehs-backend-bogus", lambda: ElasticHalfSpace(G(), E_star=1e6, backend="cuda"), refused(ValueError, "backend", "'cuda'")),
    ("ehs-threads-zero", lambda: ElasticHalfSpace(G(), E_star=1e6, threads=0), refused(ValueError, "threads", "0")),
    ("ehs-dtype-int", lambda: ElasticHalfSpace(G(), E_star=1e6, dtype=np.int32), refused((TypeError, ValueError), "dtype", "int32")),
    ("ehs-uniform-compliance-right", lambda: ElasticHalfSpace(
        Grid((16, 16), (1e-4, 1e-4), periodic=True), E_star=1e6, thickness=1e-5, poisson=0.3, bottom="frictionless"),
     right(lambda body: np.isfinite(body.uniform_compliance) and body.uniform_compliance > 0)),

    # --- interaction laws
    ("law-stack-string", lambda: ElectrostaticInteraction("stack", 10.0), refused(TypeError, "stack", "str")),
    ("law-voltage-nan", lambda: ElectrostaticInteraction(STACK, np.nan), refused(ValueError, "voltage", "nan")),
    ("law-voltage-string", lambda: ElectrostaticInteraction(STACK, "10 V"), refused((TypeError, ValueError), "voltage", "10 V")),
    ("law-field-bogus", lambda: ElectrostaticInteraction(STACK, 10.0, field="fem"), refused(ValueError, "field", "'fem'")),
    ("law-exp-w-zero", lambda: ExponentialAdhesion(0.0, 1e-7), refused(ValueError, "work_of_adhesion", "0")),
    ("law-exp-length-negative", lambda: ExponentialAdhesion(1e-3, -1e-7), refused(ValueError, "length", "-1e-07")),
    ("law-dugdale-length-inf", lambda: MaugisDugdale(1e-3, np.inf), refused(ValueError, "length", "inf")),
    ("law-traction-nan", lambda: ExponentialAdhesion(1e-3, 1e-7).traction(np.array([np.nan])), refused(ValueError, "gap", "nan")),
    ("law-traction-negative", lambda: MaugisDugdale(1e-3, 1e-7).traction(-1e-9), refused(ValueError, "gap", "-1e-09")),
    ("law-stiffness-negative", lambda: ElectrostaticInteraction(STACK, 10.0).stiffness(-1e-9), refused(ValueError, "gap", "-1e-09")),
    ("law-traction-negative-electro", lambda: ElectrostaticInteraction(STACK, 10.0).traction(-1e-9),
     refused(ValueError, "gap", "-1e-09")),
    ("law-energy-penetrating-right", lambda: ExponentialAdhesion(1e-3, 1e-7).energy(np.array([-1e-9, 0.0])),
     right(lambda v: v[0] == np.inf and close(v[1], -1e-3, 1e-15))),
    ("law-energy-nan", lambda: HardWall().energy(np.nan), refused(ValueError, "gap", "nan")),
    ("law-electro-traction-right", lambda: ElectrostaticInteraction(STACK, 100.0).traction(np.array([0.0])),
     right(lambda p: close(float(p[0]), -float(STACK.attraction(0.0, 100.0)), 1e-15))),
    ("law-exp-strength-right", lambda: ExponentialAdhesion(2e-3, 1e-7).strength, right(lambda s: close(s, 2e4, 1e-15))),
    ("law-dugdale-traction-right", lambda: MaugisDugdale(1e-3, 1e-7).traction(np.array([0.0, 2e-7])),
     right(lambda p: np.array_equal(p, [-1e4, 0.0]))),

    # --- solve_contact with every method and option
    ("solve-no-load", lambda: solve_contact(surface16(), half16()), refused(ValueError, "mean_pressure", "penetration")),
    ("solve-two-loads", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, penetration=1e-7),
     refused(ValueError, "mean_pressure", "penetration")),
    ("solve-load-nan", lambda: solve_contact(surface16(), half16(), mean_pressure=np.nan), refused(ValueError, "mean_pressure", "nan")),
    ("solve-load-inf", lambda: solve_contact(surface16(), half16(), mean_pressure=np.inf), refused(ValueError, "mean_pressure", "inf")),
    ("solve-load-string", lambda: solve_contact(surface16(), half16(), mean_pressure="1 kPa"),
     refused((TypeError, ValueError), "mean_pressure", "1 kPa")),
    ("solve-force-nan", lambda: solve_contact(surface16(), half16(), total_force=np.nan), refused(ValueError, "total_force", "nan")),
    ("solve-penetration-nan", lambda: solve_contact(surface16(), half16(), penetration=np.nan), refused(ValueError, "penetration", "nan")),
    ("solve-method-bogus", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, method="newton"),
     refused(ValueError, "method", "'newton'")),
    ("solve-method-mismatch", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, method="polonsky-keer",
                                                    interaction=ExponentialAdhesion(1e-3, 1e-7)),
     refused(ValueError, "method", "polonsky-keer")),
    ("solve-tol-zero", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, tol=0.0), refused(ValueError, "tol", "0")),
    ("solve-tol-negative", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, tol=-1e-8), refused(ValueError, "tol", "-1e-08")),
    ("solve-tol-nan", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, tol=np.nan), refused(ValueError, "tol", "nan")),
    ("solve-tol-huge", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, tol=2.0), refused(ValueError, "tol", "2")),
    ("solve-maxiter-zero", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, maxiter=0),
     right(lambda r: not r.converged and "0 iterations" in r.solver.message, warns=ConvergenceWarning)),
    ("solve-maxiter-negative", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, maxiter=-5),
     refused(ValueError, "maxiter", "-5")),
    ("solve-maxiter-float", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, maxiter=2.5),
     refused((TypeError, ValueError), "maxiter", "2.5")),
    ("solve-heights-array-right", lambda: solve_contact(surface16().heights, half16(), mean_pressure=1e3),
     right(lambda r: np.array_equal(r.gap, hard16().gap))),      # an array is heights on the body's grid
    ("solve-heights-array-shape", lambda: solve_contact(np.zeros((8, 8)), half16(), mean_pressure=1e3),
     refused(ValueError, "(8, 8)", "(16, 16)")),
    ("solve-body-other-grid", lambda: solve_contact(surface16(), ElasticHalfSpace(Grid((8, 8), (1e-4, 1e-4)), E_star=1e6),
                                                    mean_pressure=1e3), refused(ValueError, "grid")),
    ("solve-interaction-string", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, interaction="jkr"),
     refused(TypeError, "interaction", "str")),
    ("solve-x0-other-grid", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, x0=_result8()),
     refused(ValueError, "x0")),
    ("solve-x0-array-shape", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, x0=np.zeros((8, 8))),
     refused(ValueError, "x0", "(8, 8)")),
    ("solve-x0-array-nan", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, x0=np.full((16, 16), np.nan)),
     refused(ValueError, "x0", "nan")),
    ("solve-callback-not-callable", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, callback=3),
     refused(TypeError, "callback", "int")),
    ("solve-callback-halts", lambda: _quiet(lambda: solve_contact(
        surface16(), half16(), mean_pressure=1e3, interaction=ExponentialAdhesion(1e-3, 1e-7), callback=_halt)),
     right(lambda r: not r.converged and "halted" in r.solver.message)),
    ("solve-hardwall-load-right", lambda: hard16(),
     right(lambda r: r.converged and close(float(r.pressure.mean()), 1e3, 1e-9))),
    ("solve-huge-load-full-contact", lambda: solve_contact(surface16(), half16(), mean_pressure=1e12),
     right(lambda r: r.converged and r.contact_fraction == 1.0 and close(float(r.pressure.mean()), 1e12, 1e-9))),
    ("solve-hardwall-zero-load", lambda: solve_contact(surface16(), half16(), mean_pressure=0.0),
     refused(ValueError, "mean_pressure", "0", "(0, inf)")),
    ("solve-penetration-negative-right", lambda: solve_contact(surface16(), half16(), penetration=-1e-7),
     right(lambda r: r.contact_fraction == 0 and np.all(r.pressure == 0) and close(float(r.gap.min()), 1e-7, 1e-9))),
    ("solve-flat-right", lambda: solve_contact(flat16(), half16(), mean_pressure=1e3),
     right(lambda r: r.contact_fraction == 1.0 and np.allclose(r.pressure, 1e3))),
    ("solve-hardwall-tension", lambda: solve_contact(surface16(), half16(), mean_pressure=-1e3),
     refused(ValueError, "mean_pressure", "-1000")),
    ("solve-exp-beyond-strength", lambda: _quiet(lambda: solve_contact(
        surface16(), half16(), mean_pressure=-2e4, interaction=ExponentialAdhesion(1e-3, 1e-7))),
     right(lambda r: not r.converged and r.solver.detached and "strongest attraction" in r.solver.message
           and np.isfinite(r.gap).all())),
    ("solve-exp-half-strength-flat", lambda: solve_contact(
        flat16(), half16(), mean_pressure=-5e3, interaction=ExponentialAdhesion(1e-3, 1e-7)),
     right(lambda r: r.converged and not r.solver.detached and r.contact_fraction == 1.0)),
    ("solve-exp-half-pull-off", lambda: _at_half_pull_off(ExponentialAdhesion(1e-3, 1e-7), step=50.0),
     right(lambda r: r.converged and not r.solver.detached and r.contact_fraction > 0)),
    ("solve-dugdale-half-pull-off", lambda: _at_half_pull_off(MaugisDugdale(1e-3, 1e-7), step=50.0),
     right(lambda r: r.converged and not r.solver.detached and r.contact_fraction > 0)),
    ("solve-electro-half-pull-off", lambda: _at_half_pull_off(PIXEL_LAW, step=5e3),
     right(lambda r: r.converged and not r.solver.detached and r.contact_fraction > 0)),
    ("solve-electro-flat-beyond-strength", lambda: solve_contact(flat16(), half16(), mean_pressure=-1.5 * PIXEL_LAW.strength,
                                                                 interaction=PIXEL_LAW),
     right(lambda r: not r.converged and r.solver.detached and np.isfinite(r.gap).all(), warns=ConvergenceWarning)),
    ("solve-electro-flat-half-strength", lambda: solve_contact(flat16(), half16(), mean_pressure=-0.5 * PIXEL_LAW.strength,
                                                               interaction=PIXEL_LAW),
     right(lambda r: r.converged and r.contact_fraction == 1.0 and close(float(r.pressure.mean()),
                                                                          -0.5 * PIXEL_LAW.strength, 1e-9))),
    ("pulloff-too-few-steps", lambda: pull_off(ContactProblem(surface16(), half16(), ElectrostaticInteraction(STACK, 100.0)),
                                               solve_contact(surface16(), half16(), mean_pressure=0.0,
                                                             interaction=ElectrostaticInteraction(STACK, 100.0)),
                                               step=50.0, max_steps=3),
     refused(RuntimeError, "3 steps", "50")),
    ("solve-user-law-right", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3,
                                                   interaction=UserExponential(1e-3, 1e-7)),
     right(lambda r: np.abs(r.gap - exponential16().gap).max() <= 1e-6 * 1e-6)),
    ("solve-user-law-no-length", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, interaction=NoLength()),
     refused(ValueError, "NoLength", "length")),
    ("solve-user-law-negative-length", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3,
                                                             interaction=NegativeLength()),
     refused(ValueError, "NegativeLength", "length", "-1e-07")),
    ("solve-user-law-nan", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, interaction=NaNLaw()),
     refused(ValueError, "NaNLaw", "non-finite")),
    ("law-user-derived-stiffness-right", lambda: NoStiffness().stiffness(np.array([0.0, 1e-9, 1e-7, 1e-6])),
     right(lambda k: np.allclose(k, 1e-3 / 1e-14 * np.exp(-np.array([0.0, 1e-9, 1e-7, 1e-6]) / 1e-7), rtol=1e-8,
                                 atol=0))),     # ~1e-10 measured: second order in the step ε^(1/3) (g + length)
    ("law-user-derived-stiffness-gap", lambda: NoStiffness().stiffness(-1e-9), refused(ValueError, "gap", "-1e-09")),
    ("solve-user-law-derived-stiffness", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3,
                                                               interaction=NoStiffness()),
     right(lambda r: r.converged and np.abs(r.gap - exponential16().gap).max() <= 1e-6 * 1e-6)),
    ("solve-user-law-empty", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3, interaction=Empty()),
     refused(NotImplementedError, "Empty", "must implement")),
    ("solve-electro-0V-zero-load", lambda: solve_contact(surface16(), half16(), mean_pressure=0.0,
                                                         interaction=ElectrostaticInteraction(STACK, 0.0)),
     right(lambda r: r.converged)),
    ("solve-electro-tiny-V-zero-load", lambda: solve_contact(surface16(), half16(), mean_pressure=0.0,
                                                             interaction=ElectrostaticInteraction(STACK, 1e-9)),
     right(lambda r: r.converged)),
    ("solve-electro-2kV", lambda: solve_contact(surface16(), half16(), mean_pressure=1e3,
                                                interaction=ElectrostaticInteraction(STACK, 2000.0, field="parallel_plate")),
     right(lambda r: r.converged and np.isfinite(r.gap).all())),
    ("solve-float32-tiny-tol", lambda: solve_contact(surface16(), ElasticHalfSpace(G(), E_star=1e6, dtype=np.float32),
                                                     mean_pressure=1e3, interaction=ExponentialAdhesion(1e-3, 1e-7),
                                                     tol=1e-12, maxiter=200),     # warned first, then reported
     right(lambda r: not r.converged and r.gap.dtype == np.float32, warns=ConvergenceWarning)),
    ("solve-legacy-cold-start", lambda: _quiet(lambda: solve_contact(surface16(), half16(), mean_pressure=1e3,
                                                                     cold_start="bogus")),
     refused((ValueError, TypeError), "cold_start")),
    ("problem-surface-array-right", lambda: ContactProblem(np.zeros((16, 16)), half16()).solve(mean_pressure=1e3),
     right(lambda r: r.contact_fraction == 1.0 and np.allclose(r.pressure, 1e3))),
    ("problem-body-string", lambda: ContactProblem(surface16(), "half"), refused(TypeError, "body")),

    # --- pull_off and load_cycle
    ("pulloff-max-steps-zero", lambda: pull_off(_exp_problem(), exponential16(), step=1e3, max_steps=0),
     refused(ValueError, "max_steps", "0")),
    ("pulloff-max-steps-float", lambda: pull_off(_exp_problem(), exponential16(), step=1e3, max_steps=2.5),
     refused((TypeError, ValueError), "max_steps", "2.5")),
    ("pulloff-step-zero", lambda: pull_off(_exp_problem(), exponential16(), step=0.0), refused(ValueError, "step", "0")),
    ("pulloff-step-nan", lambda: pull_off(_exp_problem(), exponential16(), step=np.nan), refused(ValueError, "step", "nan")),
    ("pulloff-tol-negative", lambda: pull_off(_exp_problem(), exponential16(), step=1e3, tol=-1.0),
     refused(ValueError, "tol", "-1")),
    ("pulloff-hard-wall", lambda: pull_off(ContactProblem(surface16(), half16()), hard16(), step=1e2),
     refused(ValueError, "HardWall")),
    ("pulloff-start-array", lambda: pull_off(_exp_problem(), np.zeros((16, 16)), step=1e3),
     refused((TypeError, ValueError), "start", "ContactResult")),
    ("pulloff-flat-right", lambda: pull_off(ContactProblem(flat16(), half16(), ExponentialAdhesion(1e-3, 1e-7)),
                                            _flat_exp(), step=2e3, tol=1e-3),
     right(lambda p: close(-p.mean_pressure, 1e4, 2e-3))),
    ("cycle-empty", lambda: load_cycle(_exp_problem(), []), refused(ValueError, "loads")),
    ("cycle-nan", lambda: load_cycle(_exp_problem(), [1e3, np.nan]), refused(ValueError, "loads", "nan")),
    ("cycle-2d-right", lambda: load_cycle(_exp_problem(), [[1e3], [2e3]]).loads,       # flattened, in order
     right(lambda loads: np.array_equal(loads, [1e3, 2e3]))),
    ("cycle-jump-negative", lambda: load_cycle(_exp_problem(), [1e3], jump_area=-0.1), refused(ValueError, "jump_area", "-0.1")),
    ("cycle-flat-right", lambda: load_cycle(ContactProblem(flat16(), half16(), ExponentialAdhesion(1e-3, 1e-7)),
                                            [1e3, 0.0, -5e3, -2e4]),
     right(lambda c: list(c.detached) == [False, False, False, True] and c.contact_fraction[2] == 1.0,
           warns=ConvergenceWarning)),

    # --- electrostatics: DielectricStack and solve_field
    ("stack-d-sc-negative", lambda: DielectricStack(d_sc=-1.0), refused(ValueError, "d_sc", "-1")),
    ("stack-eps-zero", lambda: DielectricStack(eps_i=0.0), refused(ValueError, "eps_i", "0")),
    ("stack-eps-nan", lambda: DielectricStack(eps_sc=np.nan), refused(ValueError, "eps_sc", "nan")),
    ("stack-gap-negative", lambda: STACK.work_of_adhesion(-1e-6, 200.0), refused(ValueError, "gap", "-1e-06")),
    ("stack-gap-nan", lambda: STACK.attraction(np.nan, 200.0), refused(ValueError, "gap", "nan")),
    ("stack-voltage-inf", lambda: STACK.attraction(1e-6, np.inf), refused(ValueError, "voltage", "inf")),
    ("stack-deq-empty", lambda: STACK.equivalent_gap(np.array([])), refused(ValueError, "gap_field", "empty")),
    ("stack-deq-weights-shape", lambda: STACK.equivalent_gap(np.ones((4, 4)), weights=np.ones((3, 3))),
     refused(ValueError, "weights", "(3, 3)")),
    ("stack-deq-weights-zero", lambda: STACK.equivalent_gap(np.ones((4, 4)), weights=np.zeros((4, 4))),
     refused(ValueError, "weights")),
    ("stack-deq-weights-negative", lambda: STACK.equivalent_gap(np.ones((4, 4)), weights=-np.ones((4, 4))),
     refused(ValueError, "weights")),
    ("stack-deq-uniform-right", lambda: STACK.equivalent_gap(np.full((4, 4), 2e-6)), right(lambda d: close(d, 2e-6, 1e-12))),
    ("stack-attraction-for-negative", lambda: STACK.gap_for_attraction(-1.0, 100.0),
     refused(ValueError, "mean_attraction", "-1")),
    ("stack-eq22-right", lambda: float(STACK.work_of_adhesion(1e-6, 200.0)),
     right(lambda w: close(w, 8.8541878128e-12 * 200.0 ** 2 / (2 * (250e-6 / 3000 + 1e-6 / 3.9 + 1e-6)), 1e-6))),
    ("field-gap-negative", lambda: solve_field(STACK, -np.ones((8, 8)) * 1e-6, (1e-4, 1e-4)), refused(ValueError, "gap")),
    ("field-gap-nan", lambda: solve_field(STACK, np.full((8, 8), np.nan), (1e-4, 1e-4)), refused(ValueError, "gap", "nan")),
    ("field-gap-empty", lambda: solve_field(STACK, np.zeros((0, 8)), (1e-4, 1e-4)), refused(ValueError, "gap", "(0, 8)")),
    ("field-model-bogus", lambda: solve_field(STACK, np.ones((8, 8)) * 1e-6, (1e-4, 1e-4), model="fem"),
     refused(ValueError, "model", "'fem'")),
    ("field-voltage-nan", lambda: solve_field(STACK, np.ones((8, 8)) * 1e-6, (1e-4, 1e-4), voltage=np.nan),
     refused(ValueError, "voltage", "nan")),
    ("field-tol-zero", lambda: solve_field(STACK, np.ones((8, 8)) * 1e-6, (1e-4, 1e-4), tol=0.0), refused(ValueError, "tol", "0")),
    ("field-lengths-negative", lambda: solve_field(STACK, np.ones((8, 8)) * 1e-6, (-1e-4, 1e-4)), refused(ValueError, "lengths")),
    ("field-uniform-right", lambda: solve_field(STACK, np.full((8, 8), 1e-6), (1e-4, 1e-4), voltage=200.0).attraction,
     right(lambda p: np.allclose(p, STACK.attraction(1e-6, 200.0), rtol=1e-9))),

    # --- ContactResult save/load/pickle/summary
    ("result-save-directory", in_tmp(lambda tmp: hard16().save(tmp)), refused((ValueError, OSError), str(Path("/")))),
    ("result-save-missing-parent", in_tmp(lambda tmp: hard16().save(tmp / "nope" / "r.npz")), refused(OSError, "nope")),
    ("result-roundtrip-right", in_tmp(lambda tmp: ContactResult.load(exponential16().save(tmp / "r.npz"))),
     right(lambda r: np.array_equal(r.gap, exponential16().gap) and r.interaction == exponential16().interaction)),
    ("result-load-missing", in_tmp(lambda tmp: ContactResult.load(tmp / "none.npz")), refused(OSError, "none.npz")),
    ("result-load-empty", in_tmp(lambda tmp: ContactResult.load(write(tmp / "e.npz", b""))), refused(ValueError, "e.npz")),
    ("result-load-text", in_tmp(lambda tmp: ContactResult.load(write(tmp / "t.npz", "not a zip"))), refused(ValueError, "t.npz")),
    ("result-load-truncated", in_tmp(lambda tmp: ContactResult.load(_truncated(hard16().save(tmp / "r.npz")))),
     refused(ValueError, "r.npz")),
    ("result-load-heightfield", in_tmp(lambda tmp: ContactResult.load(surface16().save(tmp / "s.npz"))),
     refused(ValueError, "s.npz")),
    ("result-load-tampered-shape", in_tmp(lambda tmp: ContactResult.load(_tampered(hard16().save(tmp / "r.npz")))),
     refused(ValueError, "r.npz", "gap")),
    ("result-user-law-unregistered", in_tmp(lambda tmp: _load_unregistered(tmp)),
     right(lambda pair: pair[0].interaction == {"work_of_adhesion": 1e-3, "length": 1e-7}
           and "GoneExponential" in pair[1])),
    ("result-user-law-registered", in_tmp(lambda tmp: ContactResult.load(
        solve_contact(surface16(), half16(), mean_pressure=1e3, interaction=UserExponential(1e-3, 1e-7)).save(
            tmp / "user.npz")).interaction), right(lambda law: law == UserExponential(1e-3, 1e-7))),
    ("result-pickle-readonly", lambda: pickle.loads(pickle.dumps(hard16())).gap.flags.writeable, right(lambda w: w is False)),
    ("result-frozen", lambda: setattr(hard16(), "gap", None), refused(AttributeError, "gap")),

    # --- study: scenes, runs, results, friction, presets
    ("scene-missing", in_tmp(lambda tmp: load_scene(tmp / "none.toml")), refused((OSError, ValueError), "none.toml")),
    ("scene-empty-right", in_tmp(lambda tmp: load_scene(write(tmp / "e.toml", ""))), right(lambda s: s == load_scene())),
    ("scene-not-utf8", in_tmp(lambda tmp: load_scene(write(tmp / "b.toml", b"[loads]\nnormal_forces = [1.0]\n# \xff\xfe\n"))),
     refused(ValueError, "b.toml", "UTF-8")),
    ("scene-bad-toml", in_tmp(lambda tmp: load_scene(write(tmp / "s.toml", "[loads\n"))), refused(ValueError, "s.toml", "line 1")),
    ("scene-unknown-key", lambda: load_scene(text="[loads]\nnormal_force = [1.0]\n"), refused(ValueError, "normal_force")),
    ("scene-negative-load", lambda: load_scene(text="[loads]\nnormal_forces = [-1.0]\n"), refused(ValueError, "normal_forces", "-1")),
    ("scene-nan-voltage", lambda: load_scene(text="[loads]\nvoltages = [nan]\n"), refused(ValueError, "voltages", "nan")),
    ("scene-string-load", lambda: load_scene(text='[loads]\nnormal_forces = ["1 N"]\n'), refused(ValueError, "normal_forces", "1 N")),
    ("scene-empty-loads", lambda: load_scene(text="[loads]\nnormal_forces = []\n"), refused(ValueError, "normal_forces")),
    ("scene-preset-bogus", lambda: load_scene(preset="fast"), refused(ValueError, "preset", "'fast'")),
    ("scene-directory", in_tmp(lambda tmp: load_scene(tmp)), refused((OSError, ValueError), str(Path("/")))),
    ("scene-path-and-text", in_tmp(lambda tmp: load_scene(write(tmp / "s.toml", ""), text="")), refused(ValueError, "text")),
    ("scene-topography-missing", lambda: load_scene(text='[ridges]\nenabled = false\n[roughness]\ntopography = "nowhere.x3p"\n'),
     refused((ValueError, OSError), "nowhere.x3p")),
    ("study-dict", lambda: run_study({"loads": {}}), refused(TypeError, "scene", "dict")),
    ("study-workers-zero", lambda: run_study(_tiny(), workers=0), refused(ValueError, "workers", "0")),
    ("study-workers-negative", lambda: run_study(_tiny(), workers=-2), refused(ValueError, "workers", "-2")),
    ("study-workers-float", lambda: run_study(_tiny(), workers=1.5), refused((TypeError, ValueError), "workers", "1.5")),
    ("study-directory-is-file", in_tmp(lambda tmp: run_study(_tiny(), write(tmp / "f", "x"))),
     refused((ValueError, OSError), "f")),
    ("open-missing", in_tmp(lambda tmp: open_results(tmp / "none")), refused((OSError, ValueError), "none")),
    ("open-empty-dir", in_tmp(lambda tmp: open_results(tmp)), refused((OSError, ValueError), str(Path("/")))),
    ("open-file", in_tmp(lambda tmp: open_results(write(tmp / "f.txt", "x"))), refused((OSError, ValueError), "f.txt")),
    ("recipe-mismatched", lambda: friction_recipe([0.5, 1.0], [0.0], np.ones((2, 2)) * 1e-6, np.ones((2, 1)) * 0.1, STACK),
     refused(ValueError, "ridge_gaps", "(2, 2)")),
    ("recipe-negative-gap", lambda: friction_recipe([0.5, 1.0], [0.0, 100.0], -np.ones((2, 2)) * 1e-6,
                                                    np.ones((2, 2)) * 0.1, STACK), refused(ValueError, "ridge_gaps")),
    ("recipe-area-negative", lambda: friction_recipe([0.5, 1.0], [0.0, 100.0], np.ones((2, 2)) * 1e-6,
                                                     -np.ones((2, 2)) * 1e-5, STACK), refused(ValueError, "ridge_areas", "-1e-05")),
    ("recipe-c2-negative", lambda: friction_recipe([0.5, 1.0], [0.0, 100.0], np.ones((2, 2)) * 1e-6,
                                                   np.ones((2, 2)) * 0.1, STACK, c2=-1.0), refused(ValueError, "c2", "-1")),
    ("recipe-stack-string", lambda: friction_recipe([0.5, 1.0], [0.0, 100.0], np.ones((2, 2)) * 1e-6,
                                                    np.ones((2, 2)) * 0.1, "stack"), refused(TypeError, "stack")),
    ("recipe-single-load", lambda: friction_recipe([1.0], [0.0, 100.0], np.ones((1, 2)) * 1e-6, np.ones((1, 2)) * 1e-5,
                                                   STACK), refused(ValueError, "normal_forces", ">= 2")),
    ("recipe-right", lambda: friction_recipe([0.5, 1.0], [0.0], np.full((2, 1), 1e-6), np.full((2, 1), 1e-5), STACK
                                             ).friction_coefficient(1.0, 0.0),
     right(lambda mu: close(float(mu), 0.26, 1e-12))),      # at 0 V only μ0 F_N: the seed's μ0 = 0.26
    ("preset-auto-below-floor", lambda: scene_at_preset(None, "auto", "0.2%"),
     refused(ValueError, "target", "0.2 %", f"{100 * error_floor()[0]:.3g} %")),
    ("preset-auto-garbage", lambda: scene_at_preset(None, "auto", "ten"), refused(ValueError, "target", "ten")),
    ("preset-auto-negative", lambda: scene_at_preset(None, "auto", "-5%"),
     refused(ValueError, "target", "-0.05", "(0, 1]")),
    ("preset-target-without-auto", lambda: scene_at_preset(None, "draft", "10%"), refused(ValueError, "auto")),

    # --- macro and paper
    ("macro-power-law-m-negative", lambda: macro.PowerLawContact(m=-1.0, alpha=1.0, n=1.0, beta=1.0), refused(ValueError, "m", "-1")),
    ("macro-power-law-nan", lambda: macro.PowerLawContact(m=1.0, alpha=np.nan, n=1.0, beta=1.0), refused(ValueError, "alpha", "nan")),
    ("macro-area-force-nan", lambda: _paper_contact().area(np.nan, 0.0), refused(ValueError, "normal_force", "nan")),
    ("macro-area-force-negative", lambda: _paper_contact().nonadhesive_area(-1.0), refused(ValueError, "normal_force", "-1")),
    ("macro-mu0-negative", lambda: macro.SlidingFrictionModel(mu0=-0.1), refused(ValueError, "mu0", "-0.1")),
    ("macro-mu-voltage-nan", lambda: macro.SlidingFrictionModel.paper_table1().friction_coefficient(1.0, np.nan),
     refused(ValueError, "voltage", "nan")),
    ("macro-mu-force-zero", lambda: macro.SlidingFrictionModel.paper_table1().friction_coefficient(0.0, 0.0),
     refused(ValueError, "normal_force", "0")),
    ("macro-mu-0V-right", lambda: float(macro.SlidingFrictionModel.paper_table1().friction_coefficient(1.0, 0.0)),
     right(lambda mu: np.isfinite(mu) and mu > 0)),
    ("macro-tabulated-gap-unsorted", lambda: macro.TabulatedGap(np.array([2.0, 1.0]), np.array([0.0, 100.0]),
                                                                np.ones((2, 2)) * 1e-6), refused(ValueError, "normal_forces")),
    ("macro-tabulated-gap-shape", lambda: macro.TabulatedGap(np.array([1.0, 2.0]), np.array([0.0, 100.0]),
                                                             np.ones((3, 2)) * 1e-6), refused(ValueError, "gaps", "(3, 2)")),
    ("macro-power-gap-negative", lambda: macro.PowerLawGap(gap_ref=-1e-6, force_ref=1.0, exponent=-0.5),
     refused(ValueError, "gap_ref", "-1e-06")),
    ("macro-constant-gap-nan", lambda: macro.ConstantGap(np.nan), refused(ValueError, "gap", "nan")),
    ("macro-peeling-radius-zero", lambda: macro.SavkoorBriggsPeeling(radius=0.0, E_star=1e6, G_star=1e5),
     refused(ValueError, "radius", "0")),
    ("macro-hutchinson-lam-negative", lambda: macro.hutchinson_suo_toughness(0.5, -1.0), refused(ValueError, "lam", "-1")),
    ("paper-hertz-force-negative", lambda: paper.hertz_modulus_matching(_paper_contact(), 0.01, -1.0),
     refused(ValueError, "normal_force", "-1")),
    ("paper-reproduce-into-file", in_tmp(lambda tmp: paper.reproduce(write(tmp / "f.txt", "x"))),
     refused((ValueError, OSError), "f.txt")),
]

# ---------------------------------------------------------------------------------------------- issue 36 (scans)
# Measured scans that cannot go silently wrong (surfaces: missing data, readers' arguments, crop and resample),
# SolverReport's equality and machine paths in provenance lines.

def _st(function):
    """A row that needs the optional SurfaceTopography: skipped without it."""
    def call(*arguments):
        pytest.importorskip("SurfaceTopography")
        return function(*arguments)
    call.needs_tmp = getattr(function, "needs_tmp", False)
    return call


def _st_map():
    import SurfaceTopography
    return SurfaceTopography.Topography(np.arange(16.0).reshape(4, 4), (4.0, 4.0), unit="um")


def _compact_hole(n, margin):
    """A square hole in an n x n map, ``margin`` pixels from two edges and 5 from the others."""
    hole = np.zeros((n, n), bool)
    hole[margin:n - 5, margin:n - 5] = True
    return hole


def _report_copy(**changes):
    """hard16's SolverReport rebuilt field by field (its arrays copied), with ``changes``."""
    import dataclasses
    report = hard16().solver
    fields = {f.name: getattr(report, f.name) for f in dataclasses.fields(report)}
    fields["residuals"] = np.array(report.residuals)
    return type(report)(**{**fields, **changes})


ROWS += [
    # --- HeightField.read: narrow integer matrices, non-numbers, channels, saved fields
    ("read-matrix-2wide-unsorted", in_tmp(lambda tmp: HeightField.read(write(tmp / "m.txt", "5 2\n1 4\n3 6\n"))),
     refused(ValueError, "m.txt", "layout='matrix'")),
    ("read-matrix-2wide-pixel-size", in_tmp(lambda tmp: HeightField.read(write(tmp / "m.txt", "5 2\n1 4\n3 6\n"),
                                                                           pixel_size=1e-6)),
     refused(ValueError, "m.txt", "layout='matrix'")),
    ("read-matrix-2wide-sorted-pixel-size", in_tmp(lambda tmp: HeightField.read(
        write(tmp / "m.txt", "1 2\n3 4\n5 6\n"), pixel_size=1e-6)), refused(ValueError, "m.txt", "column export",
                                                                           "pixel_size", "layout='matrix'")),
    ("read-matrix-2wide-right", in_tmp(lambda tmp: HeightField.read(write(tmp / "m.txt", "5 2\n1 4\n3 6\n"),
                                                                      pixel_size=1e-6, layout="matrix").heights),
     right(lambda h: h.tolist() == [[5, 2], [1, 4], [3, 6]])),
    ("read-matrix-3wide-integers", in_tmp(lambda tmp: HeightField.read(write(tmp / "m.txt", "1 2 7\n3 4 8\n5 6 9\n"))),
     refused(ValueError, "m.txt", "layout='matrix'")),
    ("read-npy-strings", in_tmp(lambda tmp: HeightField.read(_npy(tmp / "s.npy", np.array([["a", "b"]])), pixel_size=1e-6)),
     refused(ValueError, "s.npy", "<U1", "not numbers")),
    ("read-channel-one", in_tmp(lambda tmp: HeightField.read(write(tmp / "u.txt", MATRIX), (1, 1), channel=1)),
     refused(ValueError, "channel", "1", "u.txt", "channel 0")),
    ("read-npz-with-unit", in_tmp(lambda tmp: HeightField.read(surface16().save(tmp / "s.npz"), unit="um")),
     refused(ValueError, "s.npz", "unit", "'um'")),

    # --- missing data: refused, cropped, filled (warned above 5 %), bounded
    ("read-missing-crop-right", in_tmp(lambda tmp: HeightField.read(write(tmp / "n.txt", "nan" + MATRIX[1:] + "0 0 0 0\n"),
                                                                      pixel_size=1e-6, missing="crop")),
     right(lambda f: f.heights.tolist() == [[5, 6, 7, 8], [9, 10, 11, 12], [13, 14, 15, 16], [0, 0, 0, 0]]
           and f.metadata["crop"] == [[1, 5], [0, 4]])),
    ("read-missing-refused-names-crop", in_tmp(lambda tmp: HeightField.read(write(tmp / "n.txt", "nan" + MATRIX[1:]),
                                                                              pixel_size=1e-6)),
     refused(ValueError, "n.txt", "1 missing heights", "missing='crop'", "missing='harmonic'")),
    ("read-missing-harmonic-warned", in_tmp(lambda tmp: HeightField.read(write(tmp / "n.txt", "1 2 3 4\n4 nan 6 7\n7 8 9 10\n"),
                                                                           (1, 1), missing="harmonic")),
     right(lambda f: np.isclose(f.heights[1, 1], 5.0) and f.metadata["filled_fraction"] == 1 / 12,
           warns=MissingDataWarning)),
    ("fill-beyond-memory-bound", lambda: harmonic_fill(np.zeros((2048, 2048)), _compact_hole(2048, 100), (1.0, 1.0)),
     refused(ValueError, "3775249", "2048 x 2048", "max_points", "524288")),
    ("fill-max-points-negative", lambda: harmonic_fill(np.zeros((4, 4)), np.eye(4, dtype=bool), (1.0, 1.0), max_points=-1),
     refused(ValueError, "max_points", "-1")),

    # --- HeightField.cropped and resampled
    ("crop-empty", lambda: surface16().cropped((4, 4)), refused(ValueError, "x = (4, 4)", "keeps no pixel")),
    ("crop-beyond", lambda: surface16().cropped((0, 17)), refused(ValueError, "x[1]", "17", "[0, 16]")),
    ("crop-metres-beyond", lambda: surface16().cropped((0.0, 2e-4), by="metres"),
     refused(ValueError, "x[1]", "0.0002", "[0, 0.0001]")),
    ("crop-by-bogus", lambda: surface16().cropped((0, 4), by="px"), refused(ValueError, "by", "'px'")),
    ("crop-right", lambda: surface16().cropped((2, 10), (3, 16)),
     right(lambda f: np.array_equal(f.heights, surface16().heights[2:10, 3:16]) and f.grid.periodic == (False, False)
           and np.allclose(f.grid.lengths, (8 / 16 * 1e-4, 13 / 16 * 1e-4), rtol=1e-14))),
    ("resample-zero", lambda: surface16().resampled((0, 4)), refused(ValueError, "shape[0]", "0")),
    ("resample-to-profile", lambda: surface16().resampled((16, 1)), refused(ValueError, "shape", "(16, 1)", "profile")),
    ("resample-mean-right", lambda: surface16().resampled((5, 7)),
     right(lambda f: abs(f.heights.mean() - surface16().heights.mean()) < 1e-21 and f.grid.lengths == G().lengths)),

    # --- read_topography / from_topography (the optional SurfaceTopography)
    ("topo-detrend-bogus", _st(lambda: from_topography(_st_map(), detrend="bogus")),
     refused(ValueError, "detrend", "'bogus'", "'plane'")),
    ("topo-read-detrend-number", _st(in_tmp(lambda tmp: read_topography(write(tmp / "p.txt", MATRIX), unit="um",
                                                                         lengths=(1e-3, 1e-3), detrend=3))),
     refused(ValueError, "detrend", "3", "'plane'")),
    ("topo-empty-file", _st(in_tmp(lambda tmp: read_topography(write(tmp / "e.x3p", b"")))),
     refused(ValueError, "e.x3p", "0 bytes")),
    ("topo-missing-bogus", _st(lambda: from_topography(_st_map(), missing="zero")), refused(ValueError, "missing", "'zero'")),
    ("topo-pixel-size-right", _st(in_tmp(lambda tmp: read_topography(write(tmp / "p.txt", MATRIX), unit="um",
                                                                      pixel_size=(1e-6, 2.5e-6)).grid.spacing)),
     right(lambda spacing: np.allclose(spacing, (1e-6, 2.5e-6), rtol=1e-14))),
    ("topo-unit-factor-right", _st(in_tmp(lambda tmp: read_topography(write(tmp / "p.txt", MATRIX), unit=1e-6,
                                                                       lengths=(4e-6, 4e-6)).heights)),
     right(lambda h: np.isclose(h.max(), 16e-6, rtol=1e-14) and np.isclose(h.min(), 1e-6, rtol=1e-14))),
    ("topo-pixel-size-stored", _st(lambda: from_topography(_st_map(), unit="um")),
     refused(ValueError, "unit", "'um'", "carries its unit")),

    # --- SolverReport: field-wise equality, consistent hash; a saved-and-loaded result's report equals the original
    ("report-copy-equal", lambda: _report_copy() == hard16().solver, right(lambda equal: equal is True)),
    ("report-copy-hash", lambda: hash(_report_copy()) == hash(hard16().solver), right(lambda equal: equal is True)),
    ("report-nan-equal", lambda: _report_copy(fft_pairs=np.nan, residuals=np.array([np.nan, 1.0]))
     == _report_copy(fft_pairs=np.nan, residuals=np.array([np.nan, 1.0])), right(lambda equal: equal is True)),
    ("report-residuals-differ", lambda: _report_copy(residuals=2 * hard16().solver.residuals) == hard16().solver,
     right(lambda equal: equal is False)),
    ("report-other-type", lambda: hard16().solver == "report", right(lambda equal: equal is False)),
    ("result-load-report-equal", in_tmp(lambda tmp: ContactResult.load(hard16().save(tmp / "r.npz")).solver == hard16().solver),
     right(lambda equal: equal is True)),
    ("result-load-smooth-report-equal", in_tmp(lambda tmp: ContactResult.load(exponential16().save(tmp / "r.npz")).solver
                                                == exponential16().solver), right(lambda equal: equal is True)),

    # --- provenance: no machine path in a written line
    ("provenance-absolute-output", lambda: Provenance.of_command("python studies/x.py", ["--output", "/tmp/res2/out"],
                                                                 {"output": "/tmp/res2/out"}).line,
     right(lambda line: "/tmp" not in line and "--output out" in line and '"output": "out"' in line)),
]


# ---------------------------------------------------------------------------------------------- issue 36 (fields)

def _ac_field_1x1():
    """The AC field of a 1 × 1 periodic grid, many times: the plan's strides must not depend on a buffer's address
    (it failed in about half of the calls); the one column is a uniform gap, so the series circuit answers."""
    from roughcontact.electrostatics.ac import solve_ac_field
    stack = DielectricStack()
    return [solve_ac_field(stack, np.full((1, 1), 1e-6), (1e-5, 1e-5), 100.0, frequency=100.0).mean_attraction
            for _ in range(20)]


def _series_circuit(values):
    """Every value the RMS-phasor series circuit of seed's stack at 1 µm, 100 V, 100 Hz (σ_sc of the stack)."""
    from roughcontact.electrostatics.ac import inverse_permittivity
    stack = DielectricStack()
    thickness = stack.d_sc * inverse_permittivity(stack, 100.0) + 1e-6 + stack.d_i / stack.eps_i   # complex [m]
    expected = 8.8541878128e-12 * 100.0 ** 2 / (2 * abs(thickness) ** 2)                           # ε0|V_a/g|²/2
    return all(abs(value / expected - 1) < 1e-9 for value in values)


ROWS += [
    ("ac-field-1x1-periodic", _ac_field_1x1, right(_series_circuit)),
    ("field-voltage-1e200", lambda: solve_field(DielectricStack(), np.full(16, 1e-6), 1e-4, 1e200),
     refused(ValueError, "voltage", "1e+200", "1e+100")),
    ("interaction-voltage-1e200", lambda: ElectrostaticInteraction(DielectricStack(), voltage=1e200),
     refused(ValueError, "voltage", "1e+200", "1e+100")),
    ("elastance-nan", lambda: DielectricStack().elastance(np.array([1e4, np.nan])), refused(ValueError, "q", "nan")),
    ("elastance-negative", lambda: DielectricStack().elastance(-1.0), refused(ValueError, "q", "-1")),
    ("elastance-string", lambda: DielectricStack().elastance("abc"), refused(TypeError, "q")),
    ("crossover-nan", lambda: _crossover(math.nan), refused(ValueError, "rest_thickness", "nan")),
    ("crossover-not-a-stack", lambda: _crossover(1e-6, stack="stack"), refused(TypeError, "stack", "str")),
]


def _crossover(rest_thickness, stack=None):
    from roughcontact.electrostatics.ac import crossover_frequency
    return crossover_frequency(DielectricStack() if stack is None else stack, rest_thickness)


# ---------------------------------------------------------------------------------------------- issue 36 (solvers)
# The contact solvers' answers meet their stated tolerance or say that they do not.

@functools.cache
def _snap_patch():
    """A smooth 32² patch (rms 0.1 µm, E* = 1 MPa) under the layered field at 200 V and 10 Pa (air breakdown at its
    contact lines, the default): it snaps into full contact in one step, the field last solved at the start's 1e-2
    (the residual is 0 at once: no free point)."""
    grid = Grid((32, 32), (1e-4, 1e-4), periodic=True)
    return (self_affine(grid, hurst=0.8, rms_height=1e-7, rng=0), ElasticHalfSpace(grid, E_star=1e6),
            ElectrostaticInteraction(DielectricStack(), 200.0))


def _layered_traction_error(tol=1e-8):
    """(converged, contact fraction, max |p_int − p_int,exact| / max σ_el, tol) of the snap patch's solve, the exact
    traction an independent tight field solve (1e-12) of the result's own gap."""
    surface, half, law = _snap_patch()
    result = solve_contact(surface, half, mean_pressure=10.0, interaction=law, tol=tol)
    exact = solve_field(law.stack, np.asarray(result.gap, dtype=np.float64), surface.grid.lengths, law.voltage,
                        tol=1e-12, contact_line=law.contact_line).attraction
    error = np.max(np.abs(np.asarray(result.interaction_traction) + exact)) / np.max(exact)
    return result.converged, result.contact_fraction, float(error), tol


def _meets_tol(outcome):
    # a field solved to a relative residual ρ moves the traction by about 5 ρ of σ_el at most on this gap; the
    # converged solve has its field to tol/10 or tighter, so within tol (measured 2e-16 with air breakdown, every
    # column broken; 3e-12 with the plain field, 3.3e-4 while its field stayed at the start's 1e-4)
    converged, contact_fraction, error, tol = outcome
    return converged and contact_fraction == 1.0 and error <= tol


def _field_stalled_at_start():
    """The snap patch with the layered field's CG cut to one iteration and the start's field bound at 1e-4 (its
    default 1e-2 is met in one iteration): its very first field solve stalls. Returns the result and the traction of
    an independent field solve (1e-12) of its gap."""
    from unittest import mock
    from roughcontact.electrostatics.field import StackField
    from roughcontact.solvers import projected_cg_gap
    original = StackField.conjugate_gradients

    def one_iteration(self, column, inverse_diagonal, flux, tol, maxiter, *args, **keywords):
        return original(self, column, inverse_diagonal, flux, tol, 1, *args, **keywords)
    surface, half, law = _snap_patch()
    with mock.patch.object(StackField, "conjugate_gradients", one_iteration), \
            mock.patch.object(projected_cg_gap, "FIELD_TOL_START", 1e-4):
        result = solve_contact(surface, half, mean_pressure=10.0, interaction=law)
    exact = solve_field(law.stack, np.asarray(result.gap, dtype=np.float64), surface.grid.lengths, law.voltage,
                        tol=1e-12, contact_line=law.contact_line)
    return result, exact.traction


def _reported_unconverged_start(outcome):
    # not converged, at the start (no step taken), the message naming the stalled field solve; every field finite,
    # the traction the stalled solve's own (one CG iteration per active-set sweep, relative residual 2.3e-4: 1.6e-3
    # of the exact field's largest σ_el off with air breakdown, 2.2e-2 with the plain field; zeros would be 1 off)
    result, exact = outcome
    fields = (result.gap, result.pressure, result.displacement, result.interaction_traction, result.contact_pressure)
    error = np.max(np.abs(np.asarray(result.interaction_traction) - exact)) / np.max(np.abs(exact))
    return (not result.converged and result.iterations == 0 and "field's solve stalled" in result.message
            and all(np.isfinite(np.asarray(field)).all() for field in fields)
            and math.isfinite(result.interaction_energy) and result.interaction_energy < 0 and error < 5e-2)


def _field_law_at(gap):
    """FieldLaw's traction at a 4² gap field [m] (the contact solver's layered law), to its default tol."""
    from roughcontact.electrostatics.field import FieldLaw
    grid = Grid((4, 4), (1e-4, 1e-4))
    arrays = [np.zeros(grid.shape) for _ in range(4)]
    FieldLaw(DielectricStack(), 100.0, grid).evaluate(np.full(grid.shape, gap), *arrays)
    return arrays[0]


def _result_copy(**changes):
    """hard16's result (exponential16's where the law changes) rebuilt with ``changes``, its arrays copied."""
    import dataclasses
    result = exponential16() if "interaction" in changes else hard16()
    arrays = {name: np.array(value) for name, value in vars(result).items() if isinstance(value, np.ndarray)}
    return dataclasses.replace(result, **{**arrays, **changes})


def _flat_pulled_off(**law):
    """A flat (16², E* = 1 MPa) under the layered field at 100 V and twice the tension the dielectric stack's
    contact attraction σ_el(0) holds (767 kPa): beyond every pull-off here (at DC the conducting stratum corneum
    leaves the insulator alone: σ_el(0) = 673 kPa)."""
    stack = DielectricStack(**{key: value for key, value in law.items() if key != "frequency"})
    tension = 2 * float(DielectricStack().attraction(0.0, 100.0))
    return solve_contact(flat16(), half16(), mean_pressure=-tension,
                         interaction=ElectrostaticInteraction(stack, 100.0, frequency=law.get("frequency")))


def _detached(result):
    return (result.detached and not result.converged and "detached" in result.message
            and "pull-off" in result.message and math.isfinite(result.mean_gap))


ROWS += [
    ("layered-snap-to-full-contact-traction", _layered_traction_error, right(_meets_tol)),
    ("layered-field-stalls-at-start", _field_stalled_at_start, right(_reported_unconverged_start,
                                                                      warns=ConvergenceWarning)),
    # a gap beyond float range in the columns' elastance: the solve's residual is NaN, which is no convergence
    ("field-law-gap-1e300", lambda: _field_law_at(1e300), refused(FloatingPointError, "stalled", "nan")),
    # a flat pulled off as a whole: its first step opens it along a direction without elastic curvature, which
    # the line search once took as far as 1e297 m (the field then NaN: "stalled", not detached)
    ("driven-dc-flat-beyond-pull-off", lambda: _flat_pulled_off(frequency=0.0), right(_detached, warns=ConvergenceWarning)),
    ("layered-flat-beyond-pull-off", lambda: _flat_pulled_off(eps_sc=1000.0), right(_detached, warns=ConvergenceWarning)),

    # --- ContactResult: field-wise equality (arrays by value, NaN equal to NaN), no hash
    ("result-load-equal", in_tmp(lambda tmp: ContactResult.load(hard16().save(tmp / "r.npz")) == hard16()),
     right(lambda equal: equal is True)),
    ("result-load-smooth-equal", in_tmp(lambda tmp: ContactResult.load(exponential16().save(tmp / "r.npz"))
                                         == exponential16()), right(lambda equal: equal is True)),
    ("result-pressure-differs", lambda: _result_copy(pressure=2 * hard16().pressure) == hard16(),
     right(lambda equal: equal is False)),
    ("result-law-differs", lambda: _result_copy(interaction=ExponentialAdhesion(2e-3, 1e-7)) == exponential16(),
     right(lambda equal: equal is False)),
    ("result-nan-equal", lambda: _result_copy(requested=math.nan) == _result_copy(requested=math.nan),
     right(lambda equal: equal is True)),
    ("result-other-type", lambda: hard16() == "result", right(lambda equal: equal is False)),
    ("result-unhashable", lambda: hash(hard16()), refused(TypeError, "unhashable", "ContactResult")),
]


# ---------------------------------------------------------------------------------------------- issue 36 (the study)
# Measured scans in a scene: the reader's arguments as [roughness] keys, missing data visible, A_R on non-square
# pixels, a patch narrower than its length scales, no field-equivalent gap below zero, the run's estimate.

def _scan_scene(tmp, keys="", scan="s.txt", content=MATRIX):
    """The scene of the scan ``scan`` (written with ``content``: text, or a HeightField saved as .npz) with the
    [roughness] ``keys``."""
    if isinstance(content, HeightField):
        content.save(tmp / scan)
    else:
        write(tmp / scan, content)
    return load_scene(write(tmp / "scan.toml", f'[ridges]\nenabled = false\n[roughness]\ntopography = "{scan}"\n'
                                                 f"{keys}"), preset="draft")


def _holes():
    """A 10 x 10 height matrix (rows along y, as SurfaceTopography reads text) with its height at x = y = 0
    undefined (1 %)."""
    return "nan" + " 1" * 9 + "\n" + "".join(" ".join(str(i + j) for j in range(10)) + "\n" for i in range(9))


def _study_patch(scene):
    from roughcontact.study.patch import patch_surface
    return patch_surface(scene, 0)


def _stripes_fraction(spacing):
    """A_R of two contact stripes along x, 30 µm apart along y (a 20 µm gap) on 4 x 10 µm pixels, closed with a
    12 µm disc: they stay apart (2/8 of the rows); a disc of 1.5 pixels of dx on both axes bridges them (4/8)."""
    from roughcontact.study.patch import ridge_area_fraction
    contact = np.zeros((8, 8))
    contact[:, 1] = contact[:, 4] = 1.0
    return ridge_area_fraction(contact, spacing, 12e-6)


def _clipped_record():
    """patch_record of a patch whose mean attraction is 2 % above that of uniform contact."""
    from types import SimpleNamespace
    from roughcontact.study.records import patch_record
    stack = load_scene().screen.stack()
    contact = np.zeros((8, 8), bool)
    contact[:, :6] = True
    result = SimpleNamespace(gap=np.where(contact, 0.0, 1e-8), contact=contact, grid=Grid((8, 8), (8e-6, 8e-6)),
                             contact_fraction=0.75, converged=True, iterations=1, unstable_steps=0,
                             electrostatic_force=1.02 * float(stack.attraction(0.0, 200.0)) * 64e-12)
    return patch_record(stack, "layered", 200.0, [result], (2e-6,), (1e-6, 1e-6), 1, 0.0)


def _small_scan_plan(tmp):
    from roughcontact.study.plan import plan_study
    field = self_affine(Grid((16, 16), (1e-5, 1e-5), periodic=False), hurst=0.8, rms_height=1e-7, rng=1)
    return plan_study(_scan_scene(tmp, scan="afm.npz", content=field))


def _scan_file(tmp, keys):
    """A scene file whose scan is surface16 saved as .npz, with the [roughness] ``keys``."""
    surface16().save(tmp / "s.npz")
    return write(tmp / "scan.toml", f'[ridges]\nenabled = false\n[roughness]\ntopography = "s.npz"\n{keys}')


def _patch_scale_warning():
    from roughcontact.study.patch import PatchScaleWarning
    return PatchScaleWarning


ROWS += [
    # --- [roughness] keys of a scan: validated at the scene, the reader's errors in the scene's keys
    ("scene-scan-key-without-scan", lambda: load_scene(text="[roughness]\nunit = \"um\"\n"),
     refused(ValueError, "roughness.unit", "topography is empty")),
    ("scene-scan-unit-bogus", in_tmp(lambda tmp: _scan_scene(tmp, 'unit = "furlong"\n')),
     refused(ValueError, "roughness.unit", "'furlong'", '"um"')),
    ("scene-scan-two-sizes", in_tmp(lambda tmp: _scan_scene(tmp, "lengths = [1e-4, 1e-4]\npixel_size = 1e-6\n")),
     refused(ValueError, "roughness.pixel_size", "roughness.lengths", "once")),
    ("scene-scan-crop-half-pixel", in_tmp(lambda tmp: _scan_scene(tmp, "crop = [0, 2.5, 0, 4]\n")),
     refused(ValueError, "roughness.crop", "2.5", "pixel indices", 'crop_by = "metres"')),
    ("scene-scan-resample-one", in_tmp(lambda tmp: _scan_scene(tmp, "resample = [1, 16]\n")),
     refused(ValueError, "roughness.resample[0]", "[8, 4096]")),
    ("scene-scan-text-no-unit", _st(in_tmp(lambda tmp: _scan_scene(tmp, "pixel_size = 1e-6\n"))),
     refused(ValueError, "s.txt", "set roughness.unit")),
    ("scene-scan-text-no-size", _st(in_tmp(lambda tmp: _scan_scene(tmp, 'unit = "um"\n'))),
     refused(ValueError, "s.txt", "roughness.lengths", "roughness.pixel_size")),
    ("scene-scan-npz-pixel-size", in_tmp(lambda tmp: _scan_scene(tmp, "pixel_size = 1e-6\n", "s.npz", surface16())),
     refused(ValueError, "s.npz", "saved heightfield", "leave roughness.pixel_size out")),
    ("scene-scan-crop-beyond", in_tmp(lambda tmp: _scan_scene(tmp, "crop = [0, 17, 0, 4]\nboundary = \"free\"\n",
                                                              "s.npz", surface16())),
     refused(ValueError, "roughness.crop", "[0, 17, 0, 4]", "does not fit", "16 x 16 pixels")),
    ("scene-scan-missing-refused", _st(in_tmp(lambda tmp: _scan_scene(tmp, 'unit = "um"\npixel_size = 1e-6\n',
                                                                      content=_holes()))),
     refused(ValueError, "s.txt", "1 missing heights", 'roughness.missing = "crop"')),
    ("scene-scan-missing-crop-right", _st(in_tmp(lambda tmp: _scan_scene(
        tmp, 'unit = "um"\npixel_size = 1e-6\nmissing = "crop"\nboundary = "free"\n', content=_holes()))),
     right(lambda scene: _study_patch(scene).shape == (9, 10))),                  # the x = 0 column cut
    ("scene-scan-missing-harmonic-right", _st(in_tmp(lambda tmp: _scan_scene(
        tmp, 'unit = "um"\npixel_size = 1e-6\nmissing = "harmonic"\n', content=_holes()))),
     right(lambda scene: np.isfinite(_study_patch(scene)).all())),                  # 1 % filled: no warning
    ("scene-scan-crop-metres-right", in_tmp(lambda tmp: _scan_scene(
        tmp, 'crop = [0.0, 5e-5, 2.5e-5, 1e-4]\ncrop_by = "metres"\nboundary = "free"\n', "s.npz", surface16())),
     right(lambda scene: _study_patch(scene).shape == (8, 12))),

    # --- A_R on non-square pixels, the field-equivalent gap, the patch's length scales
    ("ridge-area-anisotropic-right", lambda: _stripes_fraction((4e-6, 10e-6)), right(lambda a: a == 0.25)),
    ("ridge-area-disc-in-dx-pixels", lambda: _stripes_fraction(4e-6), right(lambda a: a == 0.5)),
    ("field-gap-above-contact-right", _clipped_record,
     right(lambda r: r.field_equivalent_gap == 0.0 and r.field_ratio > 1.0)),
    ("plan-scan-narrower-than-scales", in_tmp(_small_scan_plan),
     right(lambda plan: plan.grid.shape == (32, 32), warns=_patch_scale_warning())),
]


# ---------------------------------------------------------------------------------------------- the second audit
# An independent audit's findings: a crash, an answer silently wrong or an error that does not name its cause.

ROWS += [
    # a float32 preset below float32's round-off: no solve converged, then friction.csv raised on the NaN means
    ("scene-float32-tolerance-below-floor", lambda: load_scene(text='[presets.draft]\ndtype = "float32"\n'
                                                                    "tolerance = 1e-8\n"),
     refused(ValueError, "presets.draft.tolerance", "1e-08", "[4.77e-07, 0.1]", 'dtype = "float64"')),
    # the FE's area reduction is even in F_T: beyond full slip (|F_T| > mu F_N) NaN for either sign, not an
    # extrapolation of Eq. 34 for a negative F_T (F_N = 1 N, mu = 1: full slip at |F_T| = 1 N)
    ("fe-area-ratio-negative-ft-beyond-slip", lambda: _fe_reduction().area_ratio(1.0, np.array([-1.5, -0.9, 0.9]), 1.0),
     right(lambda ratio: np.isnan(ratio[0]) and ratio[1] == ratio[2] and 0 < ratio[1] < 1)),
    ("fe-effective-friction-mu0-negative", lambda: _effective_friction(-1.0, 0.0, 1.0),
     refused(ValueError, "mu0", "-1", "(0, inf)")),
    ("fe-effective-friction-mu0-nan", lambda: _effective_friction(np.nan, 0.0, 1.0),
     refused(ValueError, "mu0", "nan", "(0, inf)")),
    # periodic is checked as Grid checks it: "no" (a truthy string) made the grid periodic
    ("topo-read-periodic-string", _st(in_tmp(lambda tmp: read_topography(write(tmp / "p.txt", MATRIX), unit="um",
                                                                          pixel_size=1e-6, periodic="no"))),
     refused(TypeError, "periodic", "'no'")),
    # read_topography opens (and closes) the file itself: SurfaceTopography's NPY reader left the one it opened
    # open, a ResourceWarning when it was collected
    ("topo-read-npy-closes-its-file", _st(in_tmp(lambda tmp: _collected(lambda: read_topography(
        _npy(tmp / "a.npy", np.arange(16.0).reshape(4, 4)), unit="um", pixel_size=1e-6)))),
     right(lambda field: field.shape == (4, 4))),
    # an rms height beyond the range of a grid's lengths: numpy's OverflowError (1e300), or heights that
    # underflowed to 0 (1e-300); at the range's ends the realisation has its rms exactly
    ("sa-rms-huge", lambda: self_affine(G(), hurst=0.8, rms_height=1e300, rng=0),
     refused(ValueError, "rms_height", "1e+300", "[1e-50, 1e+50]")),
    ("sa-rms-tiny", lambda: self_affine(G(), hurst=0.8, rms_height=1e-300, rng=0),
     refused(ValueError, "rms_height", "1e-300", "[1e-50, 1e+50]")),
    # a key that acts only with another is refused without it (as screen.sigma_sc without screen.frequency)
    ("scene-power-law-with-layer", lambda: load_scene(text='[fingerpad]\nmodel = "power_law"\nlayer = true\n'),
     refused(ValueError, "fingerpad.layer", "'power_law'", 'model = "fingertip"')),
    ("plan-flat-patch", lambda: _plan(load_scene(text=FLAT_PATCH_SCENE)), refused(ValueError, "the patch is flat")),
    ("plan-long-cutoff-beyond-patch", lambda: _plan(load_scene(text=WIDE_ROUGHNESS_SCENE)),
     refused(ValueError, "roughness.long_cutoff", "0.001", "patch side 0.00045")),
    ("study-tasks-is-file", in_tmp(lambda tmp: run_study(_tiny(), tasks=write(tmp / "f", "x"))),
     refused(ValueError, "tasks path", "is a file")),
    ("sa-rms-range-ends-right", lambda: [self_affine(G(), hurst=0.8, rms_height=rms, rng=1).heights
                                         for rms in (1e-50, 1e50)],
     right(lambda pair: all(close(float(np.sqrt(np.mean((h - h.mean()) ** 2))), rms, 1e-9)
                            for h, rms in zip(pair, (1e-50, 1e50))))),
]


#: Scenes that no realisation can make a patch of: flat (neither ridges nor roughness), roughness wider than the
#: patch side (one ridge period, 0.45 mm).
FLAT_PATCH_SCENE = "[ridges]\nenabled = false\n[roughness]\nenabled = false\n"
WIDE_ROUGHNESS_SCENE = "[roughness]\nlong_cutoff = 1e-3\n"


def _plan(scene):
    from roughcontact.study.plan import plan_study
    return plan_study(scene)


def _collected(call):
    """``call()``, with the garbage it leaves collected (a file left open then warns here)."""
    import gc
    value = call()
    gc.collect()
    return value


def _fe_reduction():
    from roughcontact.fe.feed import FEAreaReduction
    return FEAreaReduction.from_summary()


def _effective_friction(*arguments):
    from roughcontact.fe.feed import effective_friction
    return effective_friction(*arguments)


# ---------------------------------------------------------------------------------------------- helpers of rows

#: The tiny scene of the study tests (32² patches, two loads, 0 and 150 V; under a second to run).
TINY = runpy.run_path(str(Path(__file__).parent / "roughcontact" / "study" / "study_scenes.py"))["TINY"]


def _tiny():
    return load_scene(text=TINY, preset="draft")


def _tiny_file(tmp):
    return write(tmp / "tiny.toml", TINY)


def _npy(path, array):
    np.save(path, array)
    return path


def _npz(path, **arrays):
    np.savez(path, **arrays)
    return path


def _fingerprint(grid=None, **options):
    from surfaces import fingerprint
    return fingerprint(grid16() if grid is None else grid, rng=0, **options)


def _fingertip(**options):
    from surfaces import fingertip
    return fingertip(grid16(), **options)


@functools.cache
def _result8():
    return solve_contact(self_affine(Grid((8, 8), (1e-4, 1e-4)), hurst=0.8, rms_height=1e-6, rng=0),
                         ElasticHalfSpace(Grid((8, 8), (1e-4, 1e-4)), E_star=1e6), mean_pressure=1e3)


def _halt(state):
    raise StopIteration


def _quiet(call):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return call()


#: The seed's per-pixel electrostatic law at 100 V (its strength σ_el(0) is known).
PIXEL_LAW = ElectrostaticInteraction(DielectricStack(), 100.0, field="parallel_plate")


def _at_half_pull_off(law, step):
    """A cold solve at half the pull-off tension that pull_off finds on the same rough patch (the issue's case:
    it must stay attached, as the retract path does)."""
    start = solve_contact(surface16(), half16(), mean_pressure=0.0, interaction=law)
    found = pull_off(ContactProblem(surface16(), half16(), law), start, step=step)
    return solve_contact(surface16(), half16(), mean_pressure=0.5 * found.mean_pressure, interaction=law)


def _exp_problem():
    return ContactProblem(surface16(), half16(), ExponentialAdhesion(1e-3, 1e-7))


@functools.cache
def _flat_exp():
    return solve_contact(flat16(), half16(), mean_pressure=0.0, interaction=ExponentialAdhesion(1e-3, 1e-7))


def _paper_contact():
    return macro.SlidingFrictionModel.paper_table1().contact


def _truncated(path):
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])
    return path


def _tampered(path):
    with np.load(path, allow_pickle=False) as stored:
        arrays = dict(stored)
    key = next(name for name in arrays if name.endswith("gap"))
    arrays[key] = arrays[key][:8]
    np.savez(path, **arrays)
    return path


def _load_unregistered(tmp):
    """A result with a user's law whose class cannot be found on loading (as if its module were not imported:
    the saved class name renamed to one that exists nowhere): a dict and a warning naming the class."""
    import json
    from surfaces.io import load_npz, save_npz
    path = solve_contact(surface16(), half16(), mean_pressure=1e3, interaction=UserExponential(1e-3, 1e-7)).save(
        tmp / "user.npz")
    arrays, metadata = load_npz(path)
    renamed = json.loads(json.dumps(metadata).replace('"UserExponential"', '"GoneExponential"'))
    assert renamed != metadata
    save_npz(path, arrays, renamed)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        loaded = ContactResult.load(path)
    return loaded, " ".join(str(w.message) for w in caught)


# ---------------------------------------------------------------------------------------------- the API rows

def _param(name, call, expected, known=None):
    """A row; ``known``: a misbehaviour in a module another change owns (reported), kept as a strict xfail."""
    marks = [pytest.mark.xfail(strict=True, reason=known)] if known else []
    return pytest.param(call, expected, id=name, marks=marks)


@pytest.mark.parametrize("call, expected", [_param(*row) for row in ROWS])
def test_call(call, expected, tmp_path):
    arguments = (tmp_path,) if getattr(call, "needs_tmp", False) else ()
    if isinstance(expected, right):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            value = call(*arguments)
        kinds = {type(w.message) for w in caught}
        assert kinds == ({expected.warns} if expected.warns else set()), [str(w.message) for w in caught]
        if expected.check is not None:
            assert expected.check(value), value
        return
    with pytest.raises(expected.kind) as raised:
        call(*arguments)
    message = str(raised.value).lower()
    missing = [fragment for fragment in expected.fragments if fragment.lower() not in message]
    assert not missing, f"{type(raised.value).__name__}: {raised.value!r} lacks {missing}"


def test_table_size():
    assert len(ROWS) >= 150


# ---------------------------------------------------------------------------------------------- the command line

def _cli(argv, monkeypatch=None):
    """Run ``roughcontact argv`` in this process: (exit code, stdout, stderr); an exception escaping main() (a
    traceback on the console) fails the row."""
    from roughcontact.cli import main
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main([str(a) for a in argv])
        except SystemExit as exit_:
            code = exit_.code
    return code, out.getvalue(), err.getvalue()


CLI_ROWS = [
    ("no-command", lambda tmp: []),
    ("bogus-command", lambda tmp: ["explode"]),
    ("run-preset-bogus", lambda tmp: ["run", _tiny_file(tmp), "--preset", "fast", "--out", tmp / "o"]),
    ("run-workers-zero", lambda tmp: ["run", _tiny_file(tmp), "--workers", "0", "--out", tmp / "o"]),
    ("run-workers-negative", lambda tmp: ["run", _tiny_file(tmp), "--workers", "-3", "--out", tmp / "o"]),
    ("run-workers-text", lambda tmp: ["run", _tiny_file(tmp), "--workers", "many", "--out", tmp / "o"]),
    ("run-workers-and-dask", lambda tmp: ["run", _tiny_file(tmp), "--workers", "2", "--dask", "tcp://x:1", "--out", tmp / "o"]),
    ("run-scene-missing", lambda tmp: ["run", tmp / "none.toml", "--out", tmp / "o"]),
    ("run-scene-directory", lambda tmp: ["run", tmp, "--out", tmp / "o"]),
    ("run-scene-not-utf8", lambda tmp: ["run", write(tmp / "b.toml", b"# \xff\xfe\n"), "--out", tmp / "o"]),
    ("run-scene-bad-toml", lambda tmp: ["run", write(tmp / "s.toml", "[loads\n"), "--out", tmp / "o"]),
    ("run-scene-unknown-key", lambda tmp: ["run", write(tmp / "s.toml", "[loads]\nforce = 1\n"), "--out", tmp / "o"]),
    ("run-scene-negative-load", lambda tmp: ["run", write(tmp / "s.toml", "[loads]\nnormal_forces = [-1.0]\n"),
                                             "--out", tmp / "o"]),
    ("run-scene-binary", lambda tmp: ["run", write(tmp / "s.toml", bytes(range(256))), "--out", tmp / "o"]),
    ("run-out-parent-missing", lambda tmp: ["run", _tiny_file(tmp), "--preset", "draft", "--out", tmp / "a" / "b"]),
    ("run-out-is-file", lambda tmp: ["run", _tiny_file(tmp), "--preset", "draft", "--out", write(tmp / "f", "x")]),
    ("run-target-text", lambda tmp: ["run", _tiny_file(tmp), "--preset", "auto", "--target-error", "ten", "--out", tmp / "o"]),
    ("run-target-below-floor", lambda tmp: ["run", _tiny_file(tmp), "--preset", "auto", "--target-error", "0.2%", "--out", tmp / "o"]),
    ("run-target-negative", lambda tmp: ["run", _tiny_file(tmp), "--preset", "auto", "--target-error", "-5%", "--out", tmp / "o"]),
    ("run-target-without-auto", lambda tmp: ["run", _tiny_file(tmp), "--preset", "draft", "--target-error", "10%", "--out", tmp / "o"]),
    ("run-unknown-flag", lambda tmp: ["run", "--fast"]),
    ("scene-missing", lambda tmp: ["scene", tmp / "none.toml"]),
    ("scene-bad", lambda tmp: ["scene", write(tmp / "s.toml", "[loads]\nvoltages = [nan]\n"), "--show"]),
    ("scene-not-utf8", lambda tmp: ["scene", write(tmp / "b.toml", b"\xff\xfe\x00")]),
    ("figures-output-is-file", lambda tmp: ["figures", "--output", write(tmp / "f", "x")]),
    ("figures-output-parent-missing", lambda tmp: ["figures", "--output", tmp / "a" / "b"]),
]
CLI_ROWS += [        # issue 36 (the study): a scene's scan keys, one line naming the key
    ("scene-scan-key-without-scan", lambda tmp: ["scene", write(tmp / "s.toml", "[roughness]\ncrop = [0, 4, 0, 4]\n")]),
    ("run-scan-crop-beyond", lambda tmp: ["run", _scan_file(tmp, "crop = [0, 17, 0, 4]\n"), "--preset", "draft",
                                          "--out", tmp / "o"]),
    ("run-scan-npz-with-unit", lambda tmp: ["run", _scan_file(tmp, 'unit = "um"\n'), "--out", tmp / "o"]),
]
CLI_ROWS += [        # the second audit: what the scene check refuses, and flags named as given
    ("scene-float32-tolerance-below-floor", lambda tmp: ["scene", write(tmp / "s.toml", '[presets.draft]\n'
                                                                        'dtype = "float32"\ntolerance = 1e-8\n')]),
    # what roughcontact run refuses at its plan, `scene` refuses too (it called them valid)
    ("scene-flat-patch", lambda tmp: ["scene", write(tmp / "s.toml", FLAT_PATCH_SCENE)]),
    ("scene-long-cutoff-beyond-patch", lambda tmp: ["scene", write(tmp / "s.toml", WIDE_ROUGHNESS_SCENE)]),
    ("scene-power-law-with-layer", lambda tmp: ["scene", write(tmp / "s.toml", '[fingerpad]\nmodel = "power_law"\n'
                                                                                'layer = true\n')]),
    ("run-flat-patch", lambda tmp: ["run", write(tmp / "s.toml", FLAT_PATCH_SCENE), "--preset", "draft", "--out",
                                    tmp / "o"]),
]
#: A bad task directory on the command line: named as --tasks, not as the output directory.
TASKS_ROWS = [
    ("run-tasks-parent-missing", lambda tmp: ["run", _tiny_file(tmp), "--preset", "draft", "--tasks", tmp / "a" / "b",
                                              "--out", tmp / "o"]),
    ("run-tasks-is-file", lambda tmp: ["run", _tiny_file(tmp), "--preset", "draft", "--tasks", write(tmp / "f", "x"),
                                       "--out", tmp / "o"]),
]
CLI_ROWS += TASKS_ROWS


def _check_one_line(code, err):
    assert code not in (0, None), f"exit code {code}"
    assert "traceback" not in err.lower(), err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err


@pytest.mark.parametrize("argv", [pytest.param(argv, id=name) for name, argv in CLI_ROWS])
def test_command_line(argv, tmp_path):
    code, _, err = _cli(argv(tmp_path))
    _check_one_line(code, err)


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="permissions do not bind root")
def test_command_line_unwritable_output(tmp_path):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        code, _, err = _cli(["run", _tiny_file(tmp_path), "--out", locked / "o"])
    finally:
        locked.chmod(0o700)
    _check_one_line(code, err)
    assert "locked" in err


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="permissions do not bind root")
def test_command_line_unreadable_scene(tmp_path):
    scene = write(tmp_path / "s.toml", "")
    scene.chmod(0o000)
    try:
        code, _, err = _cli(["run", scene, "--out", tmp_path / "o"])
    finally:
        scene.chmod(0o600)
    _check_one_line(code, err)
    assert "s.toml" in err


def test_command_line_interrupted(tmp_path, monkeypatch):
    """Ctrl-C during a run: exit code 130, one line naming the results directory."""
    from roughcontact import study

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt
    monkeypatch.setattr(study, "run_study", interrupted)
    code, _, err = _cli(["run", "--preset", "draft", "--out", tmp_path / "o"])
    _check_one_line(code, err)
    assert code == 130 and "interrupted" in err and str(tmp_path / "o") in err


@pytest.mark.parametrize("argv", [pytest.param(argv, id=name) for name, argv in TASKS_ROWS])
def test_command_line_names_the_tasks_flag(argv, tmp_path):
    code, _, err = _cli(argv(tmp_path))
    _check_one_line(code, err)
    assert "--tasks" in err and "output" not in err, err


# ---------------------------------------------------------------------------------------------- a finished run, damaged

@pytest.fixture(scope="module")
def finished(tmp_path_factory):
    """A finished run of the tiny scene in a results directory (under a second)."""
    directory = tmp_path_factory.mktemp("finished") / "run"
    return directory, run_study(_tiny(), directory, workers=1)


def _damaged(finished, tmp_path, damage):
    import shutil
    directory = tmp_path / "run"
    shutil.copytree(finished[0], directory)
    task = sorted((directory / "tasks").glob("*.json"))[0]
    damage(task)
    return directory, task


def _edited(task, edit):
    import json
    stored = json.loads(task.read_text())
    edit(stored)
    task.write_text(json.dumps(stored))


DAMAGES = [
    ("zero-bytes", lambda task: task.write_bytes(b""), "empty"),
    ("truncated", lambda task: task.write_bytes(task.read_bytes()[:50]), "not valid JSON"),
    ("not-utf8", lambda task: task.write_bytes(b"\xff\xfe{}"), "cannot be read"),
    ("json-list", lambda task: task.write_text("[1, 2]"), "older roughcontact"),
    ("json-number", lambda task: task.write_text("3"), "not a task file"),
    ("nan-record", lambda task: _edited(task, lambda s: s["records"][0].__setitem__("equivalent_gap", float("nan"))),
     "equivalent_gap = nan"),
    ("edited-record", lambda task: _edited(task, lambda s: s["records"][0].__setitem__("equivalent_gap", 1e-6)),
     "digest"),
    ("other-inputs", lambda task: _edited(task, lambda s: s["inputs"].__setitem__("voltage", 1.0)), "other inputs"),
    ("one-record-short", lambda task: _edited(task, lambda s: s["records"].pop()), "one record per load"),
]


@pytest.mark.parametrize("damage, reason", [pytest.param(d, r, id=name) for name, d, r in DAMAGES])
def test_resume_solves_a_damaged_task_again(finished, tmp_path, damage, reason):
    """Resume over a damaged task file: a warning naming the file and the reason, the task solved again, the
    same numbers as the undamaged run (the solves are deterministic); open_results refuses it, naming it."""
    from roughcontact.study import StaleTaskWarning
    directory, task = _damaged(finished, tmp_path, damage)
    with pytest.raises(ValueError, match="not finished"):
        with pytest.warns(StaleTaskWarning, match=reason):
            open_results(directory)
    with pytest.warns(StaleTaskWarning) as caught:
        resumed = run_study(_tiny(), directory, workers=1)
    assert any(task.name in str(w.message) and reason in str(w.message) for w in caught)
    assert resumed.computed == len(_tiny().loads.normal_forces)         # one task: one point per load
    assert resumed.points == finished[1].points or all(
        np.array_equal(a.equivalent_gap, b.equivalent_gap) for row_a, row_b in zip(resumed.points, finished[1].points)
        for a, b in zip(row_a, row_b))


def test_resume_with_the_scene_file_deleted_and_another_scene(finished, tmp_path):
    """scene.toml deleted, another scene run into the directory: the old tasks are keyed by their inputs, so
    only those with the new scene's inputs (0 V) are reused, and the numbers are the new scene's, as from a
    fresh directory."""
    directory, _ = _damaged(finished, tmp_path, lambda task: None)
    (directory / "scene.toml").unlink()
    other = load_scene(text=TINY.replace("voltages = [0.0, 150.0]", "voltages = [0.0, 100.0]"), preset="draft")
    resumed = run_study(other, directory, workers=1)
    assert resumed.computed == len(other.loads.normal_forces)              # the 100 V points only
    fresh = run_study(other, tmp_path / "fresh", workers=1)
    assert [p.voltage for row in resumed.points for p in row] == [p.voltage for row in fresh.points for p in row]
    assert all(a.equivalent_gap == b.equivalent_gap for row_a, row_b in zip(resumed.points, fresh.points)
               for a, b in zip(row_a, row_b))


def test_finished_results_misused(finished, tmp_path):
    """open_results on a finished directory, then the calls a user gets wrong on it."""
    from roughcontact.study import bottom_up_friction
    result = open_results(finished[0])
    assert result.points == finished[1].points                  # read back exactly, nothing solved
    with pytest.raises(ValueError, match="'bogus'.*valid: equivalent_gap"):
        result.summary("bogus")
    with pytest.raises(ValueError, match="realisation.*5"):
        bottom_up_friction(result, realisation=5)
    with pytest.raises(ValueError, match="c2.*-1"):
        bottom_up_friction(result, c2=-1.0)
    with pytest.raises(Exception) as locked:                    # the directory while another run holds it
        from roughcontact.study import ResultsDirectory
        holder = ResultsDirectory(finished[0], result.plan)
        try:
            run_study(result.scene, finished[0], workers=1)
        finally:
            holder.release()
    assert "run.lock" in str(locked.value) and type(locked.value).__name__ == "DirectoryInUse"
    code, _, err = _cli(["run", write(tmp_path / "other.toml", TINY.replace("0.5, 2.0", "0.5, 3.0")), "--out",
                         finished[0]])
    _check_one_line(code, err)
    assert "another scene" in err and str(finished[0]) in err
