"""Scenes of the multiscale fingerpad study: a TOML file validated into frozen dataclasses.

A scene says what to model (``docs/getting-started/tutorial.md``): the fingerpad's apparent contact, the fingerprint ridges,
the micro-roughness on them, the skin, the screen's dielectric stack, the loads and voltages, the A_R
coarse-graining length and the accuracy preset. Values are SI (m, Pa, N, V). The defaults live in one place,
:data:`DEFAULT_SCENE_TOML` (each value with its source in ``docs/references.md``); a user's file overrides any
subset of them::

    from roughcontact.study.scene import load_scene
    scene = load_scene("my_scene.toml", preset="draft")     # or load_scene() for the default scene
    print(scene.to_toml())

An unknown section or key, a value of the wrong kind or out of range raises ``ValueError`` naming the key, its
line in the file and the valid values. Python 3.11+ reads TOML with the standard ``tomllib``; 3.10 needs
``tomli`` (a dependency there).
"""
from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import re
import sys
import warnings
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

from surfaces import Grid, HeightField, MissingDataWarning, read_topography
from surfaces.heightfield import FILL_WARNING_FRACTION, MISSING
from surfaces.io import LENGTH_UNITS
from surfaces.ridges import ridge_fraction
from surfaces.validation import check_integer, check_real

from ..electrostatics import DielectricStack, LeakyStack
from ..electrostatics.contact_line import parse_contact_line
from ..electrostatics.stack import SIGMA_SC
from ..interactions import FIELDS, ElectrostaticInteraction
from ..solvers.inputs import FLOAT32_TOL_FLOOR

#: The scene's contact line unless ``[screen] contact_line`` sets one (the library's default, air breakdown).
DEFAULT_CONTACT_LINE = "breakdown"

if sys.version_info >= (3, 11):
    import tomllib
else:                                    # pragma: no cover - exercised on Python 3.10 only
    import tomli as tomllib

PRESETS = ("draft", "standard", "reference")
#: The preset name of a setting chosen from the measured table for a target error (``roughcontact.study.presets``);
#: a scene at it carries the chosen setting as ``[presets.auto]``.
AUTO = "auto"
#: Floating-point types of the solves (``Preset.dtype``) and the scale paths (``Preset.scales``).
DTYPES = ("float64", "float32")
SCALES = ("resolved", "coupled")
#: Boundaries of a measured topography (``roughness.boundary``): mirrored periodic, declared periodic, free.
BOUNDARIES = ("mirrored", "periodic", "free")

#: The default scene, the package file ``default_scene.toml`` beside this module: every value with its source
#: (docs/references.md sections) or marked as an estimate.
DEFAULT_SCENE_TOML = resources.files(__package__).joinpath("default_scene.toml").read_text(encoding="utf-8")


# ---------------------------------------------------------------------------------------------------------
# Field validators: each returns the checked value or raises ValueError/TypeError; ``valid`` describes them
# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class RealKey:
    """The check of a real-valued scene key: a finite float in [low, high] (open where ``*_open``)."""
    low: float | None = None
    high: float | None = None
    low_open: bool = False

    @property
    def valid(self):
        low = "-inf" if self.low is None else f"{self.low:g}"
        return (f"a number in {'(' if self.low_open or self.low is None else '['}{low}, "
                f"{'inf)' if self.high is None else f'{self.high:g}]'}")

    def __call__(self, name, value):
        return check_real(name, value, low=self.low, high=self.high, low_open=self.low_open)


@dataclass(frozen=True)
class _Integer:
    low: int
    high: int

    @property
    def valid(self):
        return f"an integer in [{self.low}, {self.high}]"

    def __call__(self, name, value):
        return check_integer(name, value, low=self.low, high=self.high)


@dataclass(frozen=True)
class _Kind:
    """A value of one TOML type ``kind`` (bool, str), described by ``valid``."""
    kind: type
    valid: str

    def __call__(self, name, value):
        if not isinstance(value, self.kind):
            raise TypeError(f"{name} must be {self.valid}, got {value!r}")
        return value


_BOOLEAN, _TEXT = _Kind(bool, "true or false"), _Kind(str, "a string")


@dataclass(frozen=True)
class _Choice:
    options: tuple

    @property
    def valid(self):
        return "one of " + ", ".join(f'"{option}"' for option in self.options)

    def __call__(self, name, value):
        if value not in self.options:
            raise ValueError(f"{name} = {value!r} is not {self.valid}")
        return value


@dataclass(frozen=True)
class _Increasing:
    """A non-empty, strictly increasing list of numbers in ``element``'s range."""
    element: RealKey

    @property
    def valid(self):
        return f"a non-empty, strictly increasing list of numbers, each {self.element.valid[2:]}"

    def __call__(self, name, value):
        if not isinstance(value, (list, tuple)) or not value:
            raise ValueError(f"{name} must be {self.valid}, got {value!r}")
        values = tuple(self.element(f"{name}[{i}]", v) for i, v in enumerate(value))
        if any(b <= a for a, b in zip(values, values[1:])):
            raise ValueError(f"{name} = {list(values)} is not strictly increasing; valid: {self.valid}")
        return values


@dataclass(frozen=True)
class _Frequencies:
    """The drive frequency [Hz]: absent (None: the dielectric model), one number >= 0 or a strictly increasing
    list of them (a sweep), held as a tuple."""
    valid = "a number in [0, inf) [Hz] (0: DC) or a non-empty, strictly increasing list of them"

    def __call__(self, name, value):
        if value is None:
            return None
        if isinstance(value, (list, tuple)):
            return _Increasing(RealKey(0.0))(name, value)
        return (RealKey(0.0)(name, value),)


@dataclass(frozen=True)
class _ScanUnit:
    """The unit of a scan's numbers: "" (the file's own), a name of ``surfaces.io.LENGTH_UNITS``, or metres per
    number."""
    valid = ('"" (the unit the file stores), one of ' + ", ".join(f'"{unit}"' for unit in LENGTH_UNITS)
             + " or metres per number, in (0, inf)")

    def __call__(self, name, value):
        if isinstance(value, str):
            if value and value not in LENGTH_UNITS:
                raise ValueError(f"{name} = {value!r} is not a length unit; valid: {self.valid}")
            return value
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0 < value < float("inf"):
            raise ValueError(f"{name} = {value!r} is not a length unit; valid: {self.valid}")
        return float(value)


@dataclass(frozen=True)
class _Optional:
    """Absent (``[]``) or a list of ``count`` values, each checked by ``element``, held as a tuple; ``single``:
    one value alone stands for ``count`` equal ones."""
    count: int
    element: object
    single: bool = False

    @property
    def valid(self):
        return (f"[] (none), {'one value or ' if self.single else ''}a list of {self.count} values, each "
                f"{self.element.valid}")

    def __call__(self, name, value):
        if self.single and not isinstance(value, (list, tuple)):
            value = [value] * self.count
        if not isinstance(value, (list, tuple)) or len(value) not in (0, self.count):
            raise ValueError(f"{name} must be {self.valid}, got {value!r}")
        return tuple(self.element(f"{name}[{i}]", item) for i, item in enumerate(value))


@dataclass(frozen=True)
class _ContactLine:
    """The layered law's model of the contact line as :func:`~roughcontact.electrostatics.contact_line.parse_contact_line`
    reads it."""
    valid = 'one of "breakdown", "breakdown:<E_bd in V/m>", "film:<thickness in m>", "none"'

    def __call__(self, name, value):
        try:
            parse_contact_line(value)
        except ValueError as error:
            raise ValueError(f"{name} = {value!r} is not valid ({error}); valid: {self.valid}") from None
        return value


def _field(check, **default):
    return field(metadata={"check": check}, **default)


class _Section:
    """A scene section: every field is checked by the validator in its metadata (``ValueError`` naming it)."""

    section = ""

    def __post_init__(self):
        for item in dataclasses.fields(self):
            value = item.metadata["check"](f"{self.section}.{item.name}", getattr(self, item.name))
            object.__setattr__(self, item.name, value)


# ---------------------------------------------------------------------------------------------------------
# Sections
# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Fingerpad(_Section):
    """Apparent contact: ``model`` "power_law" (A0 = area_prefactor F_N^area_exponent [m²], uniform nominal
    pressure) or "fingertip" (Hertz cap of ``radius`` [m] on tissue of ``E_star`` [Pa]; with ``layer`` the cap
    pressed onto the skin's layer on that tissue, solved on ``layer_grid`` × ``layer_grid`` pixels)."""
    section = "fingerpad"
    model: str = _field(_Choice(("power_law", "fingertip")))
    area_prefactor: float = _field(RealKey(0.0, low_open=True))
    area_exponent: float = _field(RealKey(0.0, 1.0, low_open=True))
    radius: float = _field(RealKey(0.0, low_open=True))
    E_star: float = _field(RealKey(0.0, low_open=True))
    layer: bool = _field(_BOOLEAN)
    layer_grid: int = _field(_Integer(16, 2048))

    def __post_init__(self):
        super().__post_init__()
        if self.layer and self.model != "fingertip":
            raise ValueError(f"fingerpad.layer = true presses the fingertip's cap onto the skin's layer, but "
                             f"fingerpad.model = {self.model!r} has no cap; valid: model = \"fingertip\", or leave "
                             "layer out (false)")


@dataclass(frozen=True)
class Ridges(_Section):
    """Parallel ridges: ``period`` [m], crest-to-furrow ``height`` [m], ridge/furrow ``width_ratio``; sweat pores
    of ``pore_density`` [1/m²], ``pore_diameter`` and ``pore_depth`` [m] on the crests."""
    section = "ridges"
    enabled: bool = _field(_BOOLEAN)
    period: float = _field(RealKey(0.0, low_open=True))
    height: float = _field(RealKey(0.0))
    width_ratio: float = _field(RealKey(0.43, 2.33))
    pore_density: float = _field(RealKey(0.0))
    pore_diameter: float = _field(RealKey(0.0, low_open=True))
    pore_depth: float = _field(RealKey(0.0))

    def __post_init__(self):
        super().__post_init__()
        width = ridge_fraction(self.width_ratio) * self.period
        if self.pore_diameter > width:
            raise ValueError(f"ridges.pore_diameter = {self.pore_diameter!r} m is wider than a ridge ({width:g} m at "
                             f"period {self.period:g} m, width_ratio {self.width_ratio:g}); valid range (0, {width:g}]")


#: The [roughness] keys that say how a measured scan is read and windowed, each with its value when absent (the
#: file's own unit, size and first channel; no crop, no resampling): :func:`measured_topography`.
SCAN_KEYS = {"unit": "", "lengths": (), "pixel_size": (), "channel": 0, "rows": "", "crop": (),
             "crop_by": "pixels", "resample": ()}


@dataclass(frozen=True)
class Roughness(_Section):
    """Self-affine micro-roughness: Hurst exponent, ``rms_height`` [m], cut-off wavelengths [m]; or a measured
    ``topography`` (a file path, "" for none) as the whole patch, with its ``boundary`` ("mirrored", "periodic",
    "free"), ``detrend`` ("plane", "mean") and handling of ``missing`` points ("refuse", "harmonic", "crop").

    How the scan is read (:data:`SCAN_KEYS`, for a file that does not store them): the ``unit`` of its numbers
    (a name or metres per number), its size as ``lengths`` [Lx, Ly] or ``pixel_size`` (dx or [dx, dy]) [m], its
    ``channel``, and for a text height matrix or ``.npy`` the layout of its ``rows`` ("x": row i holds the heights
    at x_i, as numpy writes an array; "y": row j holds those along x at y_j, the image layout; "" the reader's own,
    which is "y" for text and "x" for ``.npy``); then the window ``crop`` = [x0, x1, y0, y1] of the scan as read,
    half-open, in pixels or, with ``crop_by = "metres"``, in metres, and ``resample`` = [nx, ny] pixels over that
    window."""
    section = "roughness"
    enabled: bool = _field(_BOOLEAN)
    hurst: float = _field(RealKey(0.0, 1.0, low_open=True))
    rms_height: float = _field(RealKey(0.0, low_open=True))
    long_cutoff: float = _field(RealKey(0.0, low_open=True))
    short_cutoff: float = _field(RealKey(0.0, low_open=True))
    topography: str = _field(_TEXT)
    boundary: str = _field(_Choice(BOUNDARIES))
    detrend: str = _field(_Choice(("plane", "mean")))
    missing: str = _field(_Choice(MISSING))
    unit: str | float = _field(_ScanUnit(), default="")
    lengths: tuple = _field(_Optional(2, RealKey(0.0, low_open=True)), default=())
    pixel_size: tuple = _field(_Optional(2, RealKey(0.0, low_open=True), single=True), default=())
    channel: int = _field(_Integer(0, 1000), default=0)
    rows: str = _field(_Choice(("", "x", "y")), default="")
    crop: tuple = _field(_Optional(4, RealKey(0.0)), default=())
    crop_by: str = _field(_Choice(("pixels", "metres")), default="pixels")
    resample: tuple = _field(_Optional(2, _Integer(8, 4096)), default=())

    def __post_init__(self):
        super().__post_init__()
        if self.short_cutoff >= self.long_cutoff:
            raise ValueError(f"roughness.short_cutoff = {self.short_cutoff!r} m must be below roughness.long_cutoff "
                             f"= {self.long_cutoff!r} m")
        self._check_scan_keys()

    def _check_scan_keys(self):
        """The relations of the :data:`SCAN_KEYS`: set only with a topography, one size, a crop window that
        keeps something (whole pixels with ``crop_by = "pixels"``)."""
        if self.crop and self.crop_by == "pixels":
            if any(bound != int(bound) for bound in self.crop):
                raise ValueError(f"roughness.crop = {toml_value(self.crop)} with crop_by = \"pixels\" needs pixel "
                                 "indices; valid: whole numbers, or crop_by = \"metres\" for positions")
            object.__setattr__(self, "crop", tuple(int(bound) for bound in self.crop))
        given = [key for key, absent in SCAN_KEYS.items() if getattr(self, key) != absent]
        if given and not self.topography:
            raise ValueError(f"roughness.{given[0]} = {toml_value(getattr(self, given[0]))} says how a measured "
                             "scan is read, but roughness.topography is empty; valid: set roughness.topography, "
                             f"or leave {', '.join(given)} out")
        if self.lengths and self.pixel_size:
            raise ValueError(f"roughness.pixel_size = {toml_value(self.pixel_size)} with roughness.lengths = "
                             f"{toml_value(self.lengths)}: give the scan's size once; valid: one of the two")
        if self.crop and (self.crop[0] >= self.crop[1] or self.crop[2] >= self.crop[3]):
            raise ValueError(f"roughness.crop = {toml_value(self.crop)} keeps nothing; valid: [x0, x1, y0, y1] with "
                             "x0 < x1 and y0 < y1 (half-open, as a slice)")

    def items(self) -> dict:
        """The keys as written in a scene file: the :data:`SCAN_KEYS` only where set (a scene without them reads
        and writes as before they existed)."""
        return {key: value for key, value in dataclasses.asdict(self).items()
                if key not in SCAN_KEYS or value != SCAN_KEYS[key]}


@dataclass(frozen=True)
class Skin(_Section):
    """Half-space of ``E_star`` [Pa], or a layer (``layer_E_star`` [Pa], ``layer_thickness`` [m] > 0) bonded on
    it; one ``poisson`` ratio for both."""
    section = "skin"
    E_star: float = _field(RealKey(0.0, low_open=True))
    poisson: float = _field(RealKey(-1.0, 0.5, low_open=True))
    layer_E_star: float = _field(RealKey(0.0, low_open=True))
    layer_thickness: float = _field(RealKey(0.0))


#: The keys of a leak across the interface (:class:`LeakyStack`), each with its value when absent (no leak).
LEAK_KEYS = {"gap_conductance": 0.0, "gap_conductivity": 0.0, "gap_cpe": 0.0, "gap_cpe_exponent": 1.0,
             "surface_conductance": 0.0, "contact_transfer": False}


@dataclass(frozen=True)
class Screen(_Section):
    """Dielectric stack (``roughcontact.electrostatics.DielectricStack`` fields) and the ``field`` model of its
    attraction over a gap field ("layered" or "parallel_plate", ``ElectrostaticInteraction.field``); under a drive
    (``frequency``) the stratum corneum's ``sigma_sc`` and a leak across the interface (:data:`LEAK_KEYS`, the
    fields of :class:`~roughcontact.electrostatics.LeakyStack`); the layered field's model of the contact line
    ``contact_line`` (default "breakdown": air breakdown at 350 V/µm, ``ElectrostaticInteraction.contact_line``; it
    acts on the layered field of the dielectric model only)."""
    section = "screen"
    d_sc: float = _field(RealKey(0.0, low_open=True))
    eps_sc: float = _field(RealKey(0.0, low_open=True))
    d_i: float = _field(RealKey(0.0, low_open=True))
    eps_i: float = _field(RealKey(0.0, low_open=True))
    eps_a: float = _field(RealKey(0.0, low_open=True))
    field: str = _field(_Choice(FIELDS))
    frequency: tuple | None = _field(_Frequencies(), default=None)
    sigma_sc: float = _field(RealKey(0.0), default=SIGMA_SC)
    gap_conductance: float = _field(RealKey(0.0), default=0.0)
    gap_conductivity: float = _field(RealKey(0.0), default=0.0)
    gap_cpe: float = _field(RealKey(0.0), default=0.0)
    gap_cpe_exponent: float = _field(RealKey(0.0, 1.0, low_open=True), default=1.0)
    surface_conductance: float = _field(RealKey(0.0), default=0.0)
    contact_transfer: bool = _field(_BOOLEAN, default=False)
    contact_line: str = _field(_ContactLine(), default=DEFAULT_CONTACT_LINE)

    def __post_init__(self):
        super().__post_init__()
        if self.frequency is None and self.sigma_sc != SIGMA_SC:
            raise ValueError(f"screen.sigma_sc = {self.sigma_sc!r} S/m acts only under a drive, but screen.frequency "
                             "is not set (the dielectric model); valid: set screen.frequency, or leave sigma_sc out")
        leak = [key for key, absent in LEAK_KEYS.items() if getattr(self, key) != absent]
        if self.frequency is None and leak:
            raise ValueError(f"screen.{leak[0]} = {getattr(self, leak[0])!r} is a leak across the interface, which "
                             "acts only under a drive, but screen.frequency is not set (the dielectric model); valid: "
                             f"set screen.frequency, or leave {', '.join(leak)} out")
        if self.frequency is not None and self.field != "layered":
            raise ValueError(f"screen.frequency = {list(self.frequency)!r} Hz needs screen.field = \"layered\" (the "
                             f"drive acts through the layered field), got field = {self.field!r}")
        if self.contact_line not in (DEFAULT_CONTACT_LINE, "none") and (self.field != "layered"
                                                                       or self.frequency is not None):
            raise ValueError(f"screen.contact_line = {self.contact_line!r} acts on the layered field of the dielectric "
                             f"model only, got field = {self.field!r}, frequency = {self.frequency!r}; valid: "
                             "field = \"layered\" without frequency, or leave contact_line out")
        self.stack()                                    # the leak's own relations (LeakyStack)

    @property
    def leaks(self) -> bool:
        """Whether a key of the leak (:data:`LEAK_KEYS`) is set."""
        return any(getattr(self, key) != absent for key, absent in LEAK_KEYS.items())

    def stack(self):
        """The :class:`DielectricStack` of the screen, with the stratum corneum's conductivity ``sigma_sc``; a
        :class:`LeakyStack` where a leak is set."""
        keys = {key: value for key, value in dataclasses.asdict(self).items()
                if key not in ("field", "frequency", "contact_line")}
        if self.leaks:
            return LeakyStack(**keys)
        return DielectricStack(**{key: value for key, value in keys.items() if key not in LEAK_KEYS})

    def interaction(self, voltage: float, frequency: float | None = None):
        """The attraction at ``voltage`` [V] (RMS under a drive of ``frequency`` [Hz]; None: the dielectric model)
        with the scene's field model; None at 0 V (the hard wall)."""
        if voltage == 0:
            return None
        dielectric_layered = self.field == "layered" and frequency is None
        return ElectrostaticInteraction(self.stack(), voltage=voltage, field=self.field, frequency=frequency,
                                        contact_line=parse_contact_line(self.contact_line) if dielectric_layered
                                        else None)

    def items(self) -> dict:
        """The keys as written in a scene file: ``frequency`` and ``sigma_sc`` only where a frequency is set, the
        leak's only where one is set, ``contact_line`` only where it is not the default (a scene without the drive,
        the leak or a contact line of its own reads and writes as before they existed)."""
        data = dataclasses.asdict(self)
        if self.frequency is None:
            del data["frequency"], data["sigma_sc"]
        if not self.leaks:
            for key in LEAK_KEYS:
                del data[key]
        if self.contact_line == DEFAULT_CONTACT_LINE:
            del data["contact_line"]
        return data


@dataclass(frozen=True)
class Loads(_Section):
    """``normal_forces`` F_N [N] (> 0) and ``voltages`` U [V] (>= 0), each strictly increasing."""
    section = "loads"
    normal_forces: tuple = _field(_Increasing(RealKey(0.0, low_open=True)))
    voltages: tuple = _field(_Increasing(RealKey(0.0, 1e5)))


@dataclass(frozen=True)
class RidgeArea(_Section):
    """A_R definition: the closing diameter ``coarse_graining`` [m] and the ``sensitivity`` factors on it."""
    section = "ridge_area"
    coarse_graining: float = _field(RealKey(0.0))
    sensitivity: tuple = _field(_Increasing(RealKey(0.0, low_open=True)))


@dataclass(frozen=True)
class Study(_Section):
    """The preset in use (a named one, or "auto": the ``[presets.auto]`` setting chosen for a target error)
    and the base rng ``seed`` (realisation r uses seed + r)."""
    section = "study"
    preset: str = _field(_Choice((*PRESETS, AUTO)))
    seed: int = _field(_Integer(0, 2 ** 31 - 1))


@dataclass(frozen=True)
class Preset(_Section):
    """Accuracy against cost (``docs/guide/presets.md``): ``grid`` pixels per side of a patch of ``periods`` ridge
    periods, ``realisations``, solver ``tolerance``, ``rings`` over the apparent area (fingertip),
    ``pixels_per_cutoff`` at the short cut-off, ``dtype`` of the solves, ``warm_start`` (continuation along
    load, else cold solves) and ``scales`` ("resolved" in one grid, or "coupled" through an interface law: an
    experimental research check of the equivalent-gap assumption, ``docs/guide/study.md``)."""
    section = "presets.*"
    grid: int = _field(_Integer(8, 4096))
    periods: int = _field(_Integer(1, 64))
    realisations: int = _field(_Integer(1, 1000))
    tolerance: float = _field(RealKey(1e-14, 0.1))
    rings: int = _field(_Integer(1, 64))
    pixels_per_cutoff: float = _field(RealKey(2.0, 64.0))
    dtype: str = _field(_Choice(DTYPES))
    warm_start: bool = _field(_BOOLEAN)
    scales: str = _field(_Choice(SCALES))

    def __post_init__(self):
        super().__post_init__()
        if self.dtype == "float32" and self.tolerance < FLOAT32_TOL_FLOOR:
            raise ValueError(f"tolerance = {self.tolerance!r} is below float32's round-off floor "
                             f"{FLOAT32_TOL_FLOOR:.3g}, where a solve's residual stalls short of it (the point is "
                             "left without a converged realisation); valid: "
                             f"tolerance in [{FLOAT32_TOL_FLOOR:.3g}, 0.1] with dtype = \"float32\", or "
                             "dtype = \"float64\"")


#: The table of a parameter study (:mod:`roughcontact.study.variants`), read beside the sections.
VARY = "vary"

SECTIONS = {"fingerpad": Fingerpad, "ridges": Ridges, "roughness": Roughness, "skin": Skin, "screen": Screen,
            "loads": Loads, "ridge_area": RidgeArea, "study": Study}


@dataclass(frozen=True)
class Scene:
    """A validated scene; ``presets`` maps each preset name to its :class:`Preset`."""
    fingerpad: Fingerpad
    ridges: Ridges
    roughness: Roughness
    skin: Skin
    screen: Screen
    loads: Loads
    ridge_area: RidgeArea
    study: Study
    presets: dict

    @property
    def preset(self) -> Preset:
        """The preset named by ``study.preset``."""
        return self.presets[self.study.preset]

    def with_preset(self, name: str) -> Scene:
        """The same scene at preset ``name`` (one of its ``presets``)."""
        if name not in self.presets:
            raise ValueError(f"preset = {name!r} is not one of the scene's presets: {', '.join(self.presets)}"
                             + (" (choose the auto setting with roughcontact.study.presets.auto_scene)"
                                if name == AUTO else ""))
        return dataclasses.replace(self, study=dataclasses.replace(self.study, preset=name))

    def with_setting(self, preset: Preset) -> Scene:
        """The same scene at the setting ``preset``, held as ``presets.auto`` (so that ``scene.toml`` and the
        results' attributes record it) and selected."""
        return dataclasses.replace(self, presets={**self.presets, AUTO: preset},
                                   study=dataclasses.replace(self.study, preset=AUTO))

    def to_dict(self) -> dict:
        """Plain nested dict of the scene (tuples as lists), as in the TOML file."""
        data = {name: {key: list(value) if isinstance(value, tuple) else value
                       for key, value in _items(getattr(self, name)).items()} for name in SECTIONS}
        data["presets"] = {name: dataclasses.asdict(preset) for name, preset in self.presets.items()}
        return data

    def to_toml(self) -> str:
        """The scene as TOML text (every value, exact floats); ``load_scene(text=...)`` reads it back equal."""
        lines = []
        for name, table in self.to_dict().items():
            tables = table.items() if name == "presets" else [(None, table)]
            for sub, values in tables:
                lines.append(f"[{name}]" if sub is None else f"[{name}.{sub}]")
                lines += [f"{key} = {toml_value(value)}" for key, value in values.items()]
                lines.append("")
        return "\n".join(lines)

    def flat(self) -> dict:
        """``{"section.key": value}`` of every parameter (lists kept), for result attributes."""
        flat = {}
        for name, table in self.to_dict().items():
            for key, value in table.items():
                if isinstance(value, dict):
                    flat.update({f"{name}.{key}.{k}": v for k, v in value.items()})
                else:
                    flat[f"{name}.{key}"] = value
        return flat


def _items(section) -> dict:
    """A section's keys and values as written in a scene file."""
    return section.items() if isinstance(section, (Screen, Roughness)) else dataclasses.asdict(section)


def measured_topography(roughness: Roughness):
    """The scene's measured patch: ``roughness.topography`` read as a HeightField (a saved ``.npz`` field, or
    any format of ``surfaces.read_topography``, which needs the optional SurfaceTopography) with the scan keys
    (:data:`SCAN_KEYS`: unit, size, channel) and its ``missing`` points refused, filled or cropped away, then
    cropped to ``crop`` and resampled to ``resample``, its tilt or mean removed (``detrend``), then mirrored,
    declared periodic or left free (``boundary``); None without one. A reader's error names the scene key that
    remedies it.

    A file is read once per content: the fields read are cached by the SHA-256 of the file's bytes and the read
    options, so a scan replaced under the same path is read again. The field's metadata names the file
    (``source``), the SHA-256 of its bytes (``sha256``), the read options and, where points were missing, the
    reader's record of them (``missing_points``, ``filled_fraction``, and for a crop ``kept_fraction`` and the
    pixel ranges kept, ``measured_window``). A fill of more than 5 % of the scan warns
    (:class:`surfaces.MissingDataWarning`) every time the patch is used."""
    if not roughness.topography:
        return None
    options = tuple((key, getattr(roughness, key)) for key in SCAN_KEYS)
    patch = _measured(roughness.topography, file_digest(roughness.topography), roughness.boundary, roughness.detrend,
                      roughness.missing, options)
    record = patch.metadata
    if record["missing"] == "harmonic" and record.get("filled_fraction", 0.0) > FILL_WARNING_FRACTION:
        warnings.warn(f"{Path(roughness.topography).name}: roughness.missing = \"harmonic\" invented "
                      f"{record['missing_points']} of its heights ({record['filled_fraction']:.1%}, above "
                      f"{FILL_WARNING_FRACTION:.0%}), which the study solves as measured ones; roughness.missing = "
                      "\"crop\" keeps the largest fully measured rectangle instead", MissingDataWarning,
                      stacklevel=1)            # one place: a run warns once however often it uses the patch
    return patch


def file_digest(path) -> str:
    """The SHA-256 of the bytes of the file ``path`` (hex); a ValueError naming the file if it cannot be read."""
    digest = hashlib.sha256()
    try:
        with open(path, "rb") as stream:
            for block in iter(lambda: stream.read(1 << 20), b""):
                digest.update(block)
    except FileNotFoundError:
        raise ValueError(f"cannot read the topography {path}: no such file") from None
    except OSError as error:
        raise ValueError(f"cannot read the topography {path}: {error.strerror or error}") from None
    return digest.hexdigest()


#: The reader's record of missing points carried to the top of a measured patch's metadata, by the names there.
_MISSING_RECORD = {"missing_points": "missing_points", "filled_fraction": "filled_fraction",
                   "kept_fraction": "kept_fraction", "crop": "measured_window"}


@functools.lru_cache(maxsize=4)
def _measured(path: str, digest: str, boundary: str, detrend: str, missing: str, options: tuple):
    """The patch of the scan ``path`` whose bytes have the SHA-256 ``digest`` (the cache's key with the options;
    ``options``, the :data:`SCAN_KEYS` as pairs)."""
    options = dict(options)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MissingDataWarning)      # measured_topography warns, by the scene's keys
        field = _read_scan(path, missing, options)
    if field.grid.is_profile:
        raise ValueError(f"{path} is a line scan ({field.grid.shape[0]} points); the patch needs a 2-D map")
    record = {name: field.metadata[key] for key, name in _MISSING_RECORD.items() if key in field.metadata}
    field = _window(field, options).detrended(detrend)
    if boundary == "mirrored":
        field = field.mirrored()
    else:
        field = HeightField(Grid(field.grid.shape, field.grid.lengths, periodic=boundary == "periodic"), field.heights,
                            {"generator": f"declared {boundary}", "parts": [field.metadata]})
    given = {key: list(value) if isinstance(value, tuple) else value for key, value in options.items()
             if value != SCAN_KEYS[key]}
    return HeightField(field.grid, field.heights, {"generator": "measured patch", "source": path, "sha256": digest,
                                                   "boundary": boundary, "detrend": detrend, "missing": missing,
                                                   **given, **record, "parts": [field.metadata]})


def _read_scan(path: str, missing: str, options: dict) -> HeightField:
    """The scan ``path`` as read with the scene's ``missing`` and :data:`SCAN_KEYS` ``options`` (the reader's
    errors in the scene's keys)."""
    if path.endswith(".npz"):
        given = [f"roughness.{key}" for key in ("unit", "lengths", "pixel_size", "channel", "rows")
                 if options[key] != SCAN_KEYS[key]]
        if given:
            raise ValueError(f"{path} is a saved HeightField, which stores its size and its heights in metres, one "
                             f"map (channel 0); valid: leave {', '.join(given)} out")
        return HeightField.load(path)
    size = {key: options[key] or None for key in ("lengths", "pixel_size")}
    try:
        if options["rows"]:
            return _read_matrix(path, missing, options, size)
        return read_topography(path, channel=options["channel"], unit=options["unit"] or None, missing=missing,
                               **size)
    except ValueError as error:
        raise ValueError(_in_scene_keys(str(error))) from None


def _read_matrix(path: str, missing: str, options: dict, size: dict) -> HeightField:
    """A text height matrix or ``.npy`` in the layout of ``roughness.rows`` (HeightField.read: numpy only), with
    the unit and size the file does not store."""
    if not path.endswith(".npy"):
        with open(path, "rb") as stream:
            if b"\0" in stream.read(4096):
                raise ValueError(f'roughness.rows = "{options["rows"]}" says how a text height matrix or .npy is laid '
                                 f"out, but {path} is a binary file (an instrument's format, which fixes its axes); "
                                 "valid: leave roughness.rows out")
    if not options["unit"]:
        raise ValueError(f'{path} stores no length unit; set roughness.unit (e.g. "um" or metres per number)')
    if not (size["lengths"] or size["pixel_size"]):
        raise ValueError(f"{path} stores no physical size; set roughness.lengths = [Lx, Ly] or roughness.pixel_size "
                         "= dx or [dx, dy] in m")
    return HeightField.read(path, unit=options["unit"], channel=options["channel"], rows=options["rows"],
                            layout="matrix", missing=missing, **size)


#: The reader's arguments as the [roughness] keys that set them (:func:`_in_scene_keys`).
_READER_PHRASES = (
    (re.compile(r"pass (\w+)=None and (\w+)=None"), r"leave roughness.\1 and roughness.\2 out"),
    (re.compile(r"pass (\w+)=None"), r"leave roughness.\1 out"),
    (re.compile(r"pass unit= \(e\.g\. 'um'"), 'set roughness.unit (e.g. "um"'),
    (re.compile(r"pass lengths=\(Lx, Ly\) or pixel_size \(dx or \(dx, dy\)\)"),
     "set roughness.lengths = [Lx, Ly] or roughness.pixel_size = dx or [dx, dy]"),
    (re.compile(r"pass missing='(\w+)'"), r'set roughness.missing = "\1"'),
    (re.compile(r"\bmissing='(\w+)'"), r'roughness.missing = "\1"'),
    (re.compile(r"^(unit|lengths|pixel_size|channel) = "), r"roughness.\1 = "),
    (re.compile(r"(roughness\.\w+ = )'([^']*)'"), r'\1"\2"'),               # TOML's quotes
)


def _in_scene_keys(message: str) -> str:
    """A reader's ``message`` with its arguments (``pass unit=``, ``missing='crop'``, …) written as the
    [roughness] keys a scene sets."""
    for pattern, replacement in _READER_PHRASES:
        message = pattern.sub(replacement, message)
    return message


def _window(field: HeightField, options: dict) -> HeightField:
    """``field`` cropped to ``options["crop"]`` (by ``crop_by``) and resampled to ``options["resample"]``."""
    crop, by = options["crop"], options["crop_by"]
    if crop:
        try:
            field = field.cropped(crop[:2], crop[2:], by=by)
        except (TypeError, ValueError) as error:
            raise ValueError(f"roughness.crop = {toml_value(crop)} ({by}) does not fit the scan as read, "
                             f"{field.shape[0]} x {field.shape[1]} pixels over {field.grid.lengths[0]:g} x "
                             f"{field.grid.lengths[1]:g} m: {error}") from None
    if options["resample"]:
        field = field.resampled(options["resample"])
    return field


def toml_value(value) -> str:
    """``value`` (bool, number, string, list or None) as TOML text: floats exact (``repr``)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)
    return "[" + ", ".join(toml_value(v) for v in value) + "]"


# ---------------------------------------------------------------------------------------------------------
# Reading
# ---------------------------------------------------------------------------------------------------------
_HEADER = re.compile(r"^\s*\[\s*([A-Za-z0-9_.\-\s\"]+?)\s*\]\s*(#.*)?$")
_KEY = re.compile(r"^\s*([A-Za-z0-9_\-]+)\s*=")


def _line_of(text: str, table: tuple, key: str | None) -> int | None:
    """1-based line of ``key`` in ``[table]`` (of the header itself when ``key`` is None) in TOML ``text``."""
    current = ()
    for number, line in enumerate(text.splitlines(), start=1):
        header = _HEADER.match(line)
        if header:
            current = tuple(part.strip().strip('"') for part in header.group(1).split("."))
            if key is None and current == table:
                return number
            continue
        match = _KEY.match(line)
        if match and current == table and match.group(1) == key:
            return number
    return None


def _error(origin, text, table, key, reason, valid) -> ValueError:
    line = _line_of(text, table, key)
    where = f"{origin}, line {line}" if line is not None else f"{origin} (line not found)"
    name = ".".join(table) + ("" if key is None else f".{key}")
    hint = "" if valid is None or "valid" in reason else f"; valid: {valid}"
    return ValueError(f"{where}: scene key {name}: {reason}{hint}")


def _build(cls, table, defaults: dict, given: dict, origin, text):
    """``cls`` from ``defaults`` updated by ``given`` (the user's table), errors located in ``text``."""
    names = {item.name: item for item in dataclasses.fields(cls)}
    for key, value in given.items():
        if key not in names:
            raise _error(origin, text, table, key, "unknown key", "the keys " + ", ".join(names))
        try:
            names[key].metadata["check"](".".join(table + (key,)), value)
        except (TypeError, ValueError) as error:
            raise _error(origin, text, table, key, str(error), names[key].metadata["check"].valid) from None
    try:
        return cls(**{**defaults, **given})
    except (TypeError, ValueError) as error:      # a relation between keys (e.g. the two cut-offs)
        key = min((k for k in given if k in str(error)), key=str(error).index, default=None)   # the one named first
        raise _error(origin, text, table, key, str(error), None) from None


def parse_scene_text(text: str, origin: str) -> dict:
    """The TOML ``text`` of a scene as a dict; a ValueError naming ``origin`` (a file or "scene text") and the line
    where it is not TOML."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{origin}: not valid TOML: {error}") from None


_DEFAULTS = parse_scene_text(DEFAULT_SCENE_TOML, "the default scene")


def read_scene_file(path) -> str:
    """The text of the scene file ``path`` (TOML is UTF-8); a ValueError naming the file if it cannot be read."""
    try:
        data = Path(path).read_bytes()
    except TypeError:
        raise TypeError(f"scene path must be a str or os.PathLike, got {type(path).__name__}") from None
    except OSError as error:
        raise ValueError(f"cannot read the scene file {path}: {error.strerror}") from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        line = data.count(b"\n", 0, error.start) + 1
        column = error.start - data.rfind(b"\n", 0, error.start)
        raise ValueError(f"the scene file {path} is not UTF-8 text: byte 0x{data[error.start]:02x} at line {line}, "
                         f"column {column} (TOML files are UTF-8; save it as UTF-8 in the editor)") from None


def load_scene(path=None, *, text: str | None = None, preset: str | None = None, read_scan: bool = True,
               vary: bool = False) -> Scene:
    """The scene of the TOML file ``path`` (or of the TOML ``text``; neither: the default scene), every value
    not given taken from :data:`DEFAULT_SCENE_TOML`; ``preset`` overrides ``study.preset``. A measured
    topography is read once to validate it, unless ``read_scan`` is False (a results directory's scene, whose
    patch is stored beside it: the scan may have moved since). A ``[vary]`` table (a parameter study,
    :mod:`roughcontact.study.variants`) is refused unless ``vary`` is True, which leaves it to the caller and
    returns the base scene."""
    if path is not None and text is not None:
        raise ValueError("give a scene path or its text, not both")
    origin = "the default scene" if path is None and text is None else str(path) if path is not None else "scene"
    if path is not None:
        text = read_scene_file(path)
    text = "" if text is None else text
    given = parse_scene_text(text, origin)
    if VARY in given and not vary:
        raise _error(origin, text, (VARY,), None, "a [vary] table makes a parameter study of the scene, not one "
                     "scene", "roughcontact run (or roughcontact.study.load_variant_study) for a [vary] table")
    for name, value in given.items():
        if name == VARY and vary:
            continue
        if name not in SECTIONS and name != "presets":
            raise _error(origin, text, (name,), None, "unknown section",
                         "the sections " + ", ".join([*SECTIONS, "presets", VARY]))
        if not isinstance(value, dict):
            raise _error(origin, text, (name,), None, "a section must be a table", f"[{name}] with its keys")
    sections = {name: _build(cls, (name,), _DEFAULTS[name], given.get(name, {}), origin, text)
                for name, cls in SECTIONS.items()}
    presets = {}
    tables = given.get("presets", {})
    for name, table in tables.items():
        if name not in (*PRESETS, AUTO) or not isinstance(table, dict):
            raise _error(origin, text, ("presets", name), None, "unknown preset or not a table",
                         "[presets.NAME] with NAME " + _Choice((*PRESETS, AUTO)).valid)
    for name in PRESETS:
        presets[name] = _build(Preset, ("presets", name), _DEFAULTS["presets"][name], tables.get(name, {}),
                               origin, text)
    if AUTO in tables:                              # a chosen setting has no defaults: every key is given
        missing = [item.name for item in dataclasses.fields(Preset) if item.name not in tables[AUTO]]
        if missing:
            raise _error(origin, text, ("presets", AUTO), None, "missing keys " + ", ".join(missing),
                         "every key of a preset")
        presets[AUTO] = _build(Preset, ("presets", AUTO), {}, tables[AUTO], origin, text)
    elif sections["study"].preset == AUTO:
        raise _error(origin, text, ("study",), "preset", 'study.preset = "auto" without a [presets.auto] table',
                     "a named preset, or [presets.auto] (roughcontact run --preset auto --target-error chooses it)")
    scene = Scene(**sections, presets=presets)
    scene = scene if preset is None else scene.with_preset(preset)
    return _with_measured_topography(scene, path, origin, text, read_scan)


def _with_measured_topography(scene: Scene, path, origin, text, read_scan: bool = True) -> Scene:
    """``scene`` with ``roughness.topography`` made absolute (from the scene file's folder) and read once (with
    ``read_scan``), so that a missing or unreadable scan, ridges on top of it or a coupled preset stop at
    validation."""
    roughness = scene.roughness
    if not roughness.topography:
        return scene
    location = Path(roughness.topography).expanduser()
    if not location.is_absolute():
        location = (Path(path).parent if path is not None else Path.cwd()) / location
    scene = dataclasses.replace(scene, roughness=dataclasses.replace(roughness, topography=str(location.resolve())))
    try:
        check_measured(scene, read_scan)
    except (ValueError, TypeError, ImportError, OSError) as error:
        raise _error(origin, text, ("roughness",), _key_named(str(error), text), str(error), None) from None
    return scene


def check_measured(scene: Scene, read_scan: bool = True) -> None:
    """Refuse a scene whose measured topography (an absolute path) has ridges on top, a coupled preset or, with
    ``read_scan``, a scan that cannot be read (ValueError naming the reason and what is valid)."""
    if scene.ridges.enabled:
        raise ValueError("a measured topography is the whole patch, its ridges included, but ridges.enabled = true; "
                         "valid: ridges.enabled = false with a topography")
    if scene.preset.scales == "coupled":
        raise ValueError(f"presets.{scene.study.preset}.scales = 'coupled' reduces synthetic roughness to an "
                         "interface law; a measured topography is solved resolved; valid: scales = \"resolved\"")
    if read_scan:
        measured_topography(scene.roughness)


def _key_named(message: str, text: str) -> str:
    """The [roughness] key that a scan's error ``message`` names first and the scene ``text`` sets (its line is
    the error's), else ``topography``."""
    for key in re.findall(r"roughness\.(\w+)", message):
        if _line_of(text, ("roughness",), key) is not None:
            return key
    return "topography"
