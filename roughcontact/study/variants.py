"""Parameter studies of a scene: the ``[vary]`` table, the inputs it varies and the variants of its design.

A scene file with a ``[vary]`` table is a parameter study (``docs/guide/study.md``, "Parameter studies"): the
scene without the table is the *baseline*, and each *variant* is that scene with the varied inputs' values
substituted, validated as any scene is. Every physical number of the sections ``fingerpad``, ``ridges``,
``roughness``, ``skin`` and ``screen`` may vary (:func:`variable_keys`), the drive frequency
(``screen.frequency``, one number per variant) and the measured topography (``roughness.topography``, a list of
files) too; the loads and voltages are the study's own axes. An input takes a list of values, a range or the
published range of :data:`RANGES_FILE` ("literature")::

    [vary]
    design = "one-at-a-time"                       # or "morris" or "sobol" (SALib: roughcontact[sensitivity])
    "skin.layer_E_star" = [1e7, 1e8, 1e9]           # each value
    "screen.eps_sc" = { low = 1e3, high = 1e4, scale = "log" }
    "screen.d_sc" = "literature"                    # input_ranges.toml: 0.2-0.5 mm, with its source

Designs (:data:`DESIGNS`): "one-at-a-time", the baseline and each input at each listed value or at the ends of
its range, the others at the baseline (a tornado: 1 + Σ levels variants); "morris", ``samples`` trajectories of
SALib's Morris sampler on ``levels`` grid levels (samples × (inputs + 1) variants, for screening); "sobol", SALib's
Saltelli/Sobol' sample of ``samples`` (a power of 2) base points (samples × (inputs + 2) variants, first and total
order indices). The samplers work on the unit cube; :meth:`Input.at` maps a coordinate u to the input's value
(linear or logarithmic in a range, the ⌊u n⌋-th of n listed values). ``seed`` seeds the sampler; the roughness
realisations of every variant use the scene's own ``study.seed``, so that variants differ by their inputs only.
``point = [F_N, U]`` chooses the load and voltage of the report's sensitivity figure (default: the first load and
the highest voltage).

Every key and value is checked (a ValueError naming the file, the line, the key, its value and what is valid), and
every variant is built and validated before anything runs.
"""
from __future__ import annotations

import dataclasses
import functools
import json
import math
import re
import sys
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np

from .presets import auto_scene, parse_target
from .scene import (AUTO, SECTIONS, VARY, Scene, parse_scene_text, read_scene_file, RealKey, toml_value,
                    check_measured, load_scene)

if sys.version_info >= (3, 11):
    import tomllib
else:                                    # pragma: no cover - exercised on Python 3.10 only
    import tomli as tomllib

#: The designs of a parameter study (module docstring).
DESIGNS = ("one-at-a-time", "morris", "sobol")
#: How a range is sampled: uniformly in the value or in its logarithm.
SCALES = ("linear", "log")
#: The keys of a range.
RANGE_KEYS = ("low", "high", "scale", "source")
#: The value that takes an input's published range from :data:`RANGES_FILE`.
LITERATURE = "literature"
#: The settings of a ``[vary]`` table (its other keys are inputs, "section.key").
SETTINGS = ("design", "samples", "levels", "seed", "point")
#: The sections whose numbers a study varies: the physical inputs.
VARIABLE_SECTIONS = ("fingerpad", "ridges", "roughness", "skin", "screen")
#: The inputs that are not plain numbers: the drive frequency (one per variant) and a measured topography (files).
FREQUENCY, TOPOGRAPHY = "screen.frequency", "roughness.topography"
#: The published ranges of the inputs (package data), each with its unit, tag and source.
RANGES_FILE = "input_ranges.toml"
#: The largest number of variants a design may make.
MAX_VARIANTS = 4096


def variable_keys() -> tuple:
    """The scene keys a parameter study may vary: every real number of :data:`VARIABLE_SECTIONS`, the drive
    frequency and the measured topography."""
    keys = [f"{section}.{item.name}" for section in VARIABLE_SECTIONS
            for item in dataclasses.fields(SECTIONS[section]) if isinstance(item.metadata["check"], RealKey)]
    return tuple(keys) + (FREQUENCY, TOPOGRAPHY)


@dataclass(frozen=True)
class InputRange:
    """The published range of input ``name``: ``low`` to ``high`` [``unit``] on ``scale``, ``tag`` "literature",
    "recalled" or "estimate", and its ``source`` in words (``docs/references.md``, section 12)."""

    name: str
    low: float
    high: float
    scale: str
    unit: str
    tag: str
    source: str


@functools.lru_cache(maxsize=1)
def literature_ranges() -> dict:
    """``{name: InputRange}`` of :data:`RANGES_FILE`."""
    table = tomllib.loads(resources.files(__package__).joinpath(RANGES_FILE).read_text(encoding="utf-8"))
    return {name: InputRange(name=name, **entry) for name, entry in table.items()}


@dataclass(frozen=True)
class Input:
    """One varied input ``name`` ("section.key"): its listed ``values`` (as in the scene: floats, or files for a
    topography), or a range ``low`` to ``high`` on ``scale`` with its ``source`` (where the range comes from;
    empty: the scene file)."""

    name: str
    values: tuple = ()
    low: float | None = None
    high: float | None = None
    scale: str = "linear"
    source: str = ""

    @property
    def levels(self) -> tuple:
        """The values of a one-at-a-time design: each listed value, or the range's two ends."""
        return self.values if self.values else (self.low, self.high)

    def at(self, unit: float):
        """The value at unit coordinate ``unit`` in [0, 1]: low + u (high − low), or its logarithmic
        counterpart; of listed values the ⌊u n⌋-th (the last at u = 1)."""
        if self.values:
            return self.values[min(int(math.floor(unit * len(self.values))), len(self.values) - 1)]
        if unit <= 0.0 or unit >= 1.0:                       # the ends exactly (shared with other designs' tasks)
            return self.low if unit <= 0.0 else self.high
        if self.scale == "log":
            return float(math.exp(math.log(self.low) + unit * (math.log(self.high) - math.log(self.low))))
        return float(self.low + unit * (self.high - self.low))

    def describe(self) -> str:
        """The values in words: "1e+07, 1e+08, 1e+09" or "1e+07 to 1e+09 (log)"."""
        if self.values:
            return ", ".join(Path(v).name if isinstance(v, str) else f"{v:g}" for v in self.values)
        return f"{self.low:g} to {self.high:g}" + (" (log)" if self.scale == "log" else "")

    def to_toml(self) -> str:
        """The input's line of a ``[vary]`` table."""
        if self.values:
            return f"{json.dumps(self.name)} = {toml_value(list(self.values))}"
        source = f", source = {json.dumps(self.source)}" if self.source else ""
        return (f"{json.dumps(self.name)} = {{ low = {self.low!r}, high = {self.high!r}, scale = "
                f"{json.dumps(self.scale)}{source} }}")


@dataclass(frozen=True)
class Variation:
    """A validated ``[vary]`` table: the ``inputs``, the ``design`` and its ``samples``, Morris ``levels`` and
    sampler ``seed``; ``point``, (F_N, U) of the report's sensitivity figure (None: the first load, highest
    voltage)."""

    inputs: tuple
    design: str = DESIGNS[0]
    samples: int | None = None
    levels: int = 4
    seed: int = 0
    point: tuple | None = None

    @property
    def names(self) -> tuple:
        return tuple(item.name for item in self.inputs)

    def to_toml(self) -> str:
        """The ``[vary]`` table; :func:`load_variant_study` reads it back equal."""
        lines = [f"[{VARY}]", f"design = {json.dumps(self.design)}"]
        if self.design != DESIGNS[0]:
            lines += [f"samples = {self.samples}", f"seed = {self.seed}"]
            if self.design == "morris":
                lines.append(f"levels = {self.levels}")
        if self.point is not None:
            lines.append(f"point = {toml_value(list(self.point))}")
        return "\n".join(lines + [item.to_toml() for item in self.inputs]) + "\n"


@dataclass(frozen=True)
class Variant:
    """One variant: its ``index``, a ``label`` ("baseline", "skin.layer_E_star = 1e+09", "sample 3"), the
    ``values`` of the inputs in it (one per input, as in its scene; None for an absent drive frequency) and its
    ``scene``."""

    index: int
    label: str
    values: tuple
    scene: Scene


@dataclass(frozen=True, eq=False)
class VariantStudy:
    """A parameter study: the ``base`` scene (the baseline), its ``variation`` and the ``variants`` of the
    design; ``unit_sample``, the sampler's points in the unit cube (variants × inputs) of a global design (None
    for one at a time). Two studies are equal when their base scenes and variations are."""

    base: Scene
    variation: Variation
    variants: tuple
    unit_sample: np.ndarray | None = None

    def __eq__(self, other):
        if not isinstance(other, VariantStudy):
            return NotImplemented
        return self.base == other.base and self.variation == other.variation

    __hash__ = None

    @property
    def design(self) -> str:
        return self.variation.design

    @property
    def inputs(self) -> tuple:
        return self.variation.inputs

    def baseline_values(self) -> tuple:
        """The inputs' values in the base scene."""
        return tuple(scene_value(self.base, name) for name in self.variation.names)

    def to_toml(self) -> str:
        """The study as one scene file: the base scene's TOML and its ``[vary]`` table."""
        return self.base.to_toml() + "\n" + self.variation.to_toml()


def scene_value(scene: Scene, name: str):
    """The value of input ``name`` in ``scene`` (one drive frequency, or None without one; a topography's path)."""
    section, key = name.split(".")
    value = getattr(getattr(scene, section), key)
    if name == FREQUENCY:
        return None if value is None else value[0]
    return value


# ---------------------------------------------------------------------------------------------------------
# Reading
# ---------------------------------------------------------------------------------------------------------
class _Located:
    """Errors of a ``[vary]`` table located in the scene ``text`` of ``origin``, the scene file's ``folder``."""

    def __init__(self, origin: str, text: str, folder: Path):
        self.origin, self.text, self.folder = origin, text, folder

    def line(self, name: str | None) -> int | None:
        """1-based line of key ``name`` in the ``[vary]`` table (of its header for None)."""
        inside = False
        key = re.compile(r"^\s*(?:\"" + re.escape(name or "") + r"\"|'" + re.escape(name or "") + r"'|"
                         + re.escape(name or "") + r")\s*=")
        for number, line in enumerate(self.text.splitlines(), start=1):
            header = re.match(r"^\s*\[\s*([^\]]+?)\s*\]", line)
            if header:
                inside = header.group(1).strip() == VARY
                if inside and name is None:
                    return number
                continue
            if inside and name is not None and key.match(line):
                return number
        return None

    def error(self, name: str | None, value, reason: str, valid: str | None = None) -> ValueError:
        line = self.line(name)
        where = f"{self.origin}, line {line}" if line is not None else f"{self.origin} (line not found)"
        key = f"[{VARY}]" if name is None else f"[{VARY}] {json.dumps(name)} = {value!r}"
        hint = "" if valid is None or "valid" in reason else f"; valid: {valid}"
        return ValueError(f"{where}: {key}: {reason}{hint}")


def _entries(table: dict, prefix: str = ""):
    """``(name, value)`` of a ``[vary]`` table, dotted keys written unquoted (nested tables) joined again; a table
    with a range key (:data:`RANGE_KEYS`) is a value."""
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict) and not set(value) & set(RANGE_KEYS):
            yield from _entries(value, name + ".")
        else:
            yield name, value


def substitute(base: Scene, values: dict, folder: Path | None = None, read_scan: bool = True) -> Scene:
    """``base`` with each input ``{name: value}`` substituted and validated (ValueError or TypeError naming the
    key): a drive frequency is one number, a topography a file (relative to ``folder``, read with
    ``read_scan``)."""
    scene = base
    for name, value in values.items():
        section, key = name.split(".")
        if name == TOPOGRAPHY:
            if not isinstance(value, str) or not value:
                raise TypeError(f"{name} must be a file name, got {value!r}")
            location = Path(value).expanduser()
            value = str(((folder or Path.cwd()) / location).resolve() if not location.is_absolute() else location)
        if name == FREQUENCY and isinstance(value, (list, tuple)):
            raise TypeError(f"{name} of a variant is one frequency [Hz], got {value!r}")
        scene = dataclasses.replace(scene, **{section: dataclasses.replace(getattr(scene, section), **{key: value})})
    if TOPOGRAPHY in values:
        check_measured(scene, read_scan)
    return scene


def _read_input(name, value, base: Scene, where: _Located, read_scan: bool) -> Input:
    """The :class:`Input` of ``[vary]`` entry ``name = value``, every value checked in the base scene."""
    if name not in variable_keys():
        section = name.split(".")[0]
        why = ("the loads and voltages are the study's axes: list them in [loads]" if section == "loads" else
               "not a physical input" if section in ("presets", "study", "ridge_area") else "unknown input")
        raise where.error(name, value, why, "the inputs " + ", ".join(variable_keys()))
    written = value
    if value == LITERATURE:
        ranges = literature_ranges()
        if name not in ranges:
            raise where.error(name, value, "no published range is known for this input",
                              "a list or { low, high, scale } range; literature ranges exist for "
                              + ", ".join(ranges))
        known = ranges[name]
        value = {"low": known.low, "high": known.high, "scale": known.scale, "source": f"{known.source} [{known.tag}]"}
    if isinstance(value, list):
        if not value or len(set(map(repr, value))) != len(value):
            raise where.error(name, value, "the list is empty or repeats a value", "a list of distinct values")
        values = tuple(_checked(name, item, base, where, read_scan, value) for item in value)
        return Input(name=name, values=values)
    if not isinstance(value, dict) or name == TOPOGRAPHY:
        valid = ("a list of files" if name == TOPOGRAPHY else
                 'a list of values, a range { low = ..., high = ..., scale = "linear" or "log" } or "literature"')
        raise where.error(name, value, "not a list" + ("" if name == TOPOGRAPHY else ", a range or \"literature\""),
                          valid)
    return _read_range(name, value, written, base, where, read_scan)


def _read_range(name, value: dict, written, base: Scene, where: _Located, read_scan: bool) -> Input:
    """The :class:`Input` of a range ``{low, high, scale, source}`` (``written`` so in the scene file)."""
    unknown = set(value) - set(RANGE_KEYS)
    if unknown or "low" not in value or "high" not in value:
        raise where.error(name, written, f"unknown range key {sorted(unknown)[0]!r}" if unknown else
                          "a range needs low and high", "a table of low, high and optionally scale, source")
    scale, source = value.get("scale", "linear"), value.get("source", "")
    if scale not in SCALES:
        raise where.error(name, written, f"scale = {scale!r} is not " + " or ".join(map(json.dumps, SCALES)))
    if not isinstance(source, str):
        raise where.error(name, written, f"source = {source!r} is not a string")
    low, high = (_checked(name, value[end], base, where, read_scan, written) for end in ("low", "high"))
    if low is None or high is None or not low < high or (scale == "log" and low <= 0):
        raise where.error(name, written, f"low = {low!r} must be below high = {high!r}"
                          + (" and above 0 on a log scale" if scale == "log" else ""), "low < high")
    return Input(name=name, low=low, high=high, scale=scale, source=source)


def _checked(name, item, base: Scene, where: _Located, read_scan: bool, written):
    """``item`` as the scene holds it (validated by substituting it into ``base``), errors at ``name``'s line."""
    try:
        scene = substitute(base, {name: item}, where.folder, read_scan)
    except (TypeError, ValueError, ImportError, OSError) as error:
        raise where.error(name, written, str(error)) from None
    return scene_value(scene, name)


def _read_settings(table: dict, base: Scene, where: _Located) -> dict:
    """The settings of a ``[vary]`` table, checked."""
    design = table.get("design", DESIGNS[0])
    if design not in DESIGNS:
        raise where.error("design", design, "unknown design", " or ".join(map(json.dumps, DESIGNS)))
    settings = {"design": design}
    if design == DESIGNS[0]:
        for key in ("samples", "levels", "seed"):
            if key in table:
                raise where.error(key, table[key], "a one-at-a-time design has no sampler: its variants are the "
                                  "baseline and each input's values", 'design = "morris" or "sobol" to sample')
    else:
        settings["samples"] = _integer(table, "samples", None, 1, 1024, where)
        settings["seed"] = _integer(table, "seed", 0, 0, 2 ** 31 - 1, where)
        if design == "sobol" and settings["samples"] & (settings["samples"] - 1):
            raise where.error("samples", settings["samples"], "Sobol' points balance at powers of 2",
                              "a power of 2 (2, 4, 8, ...)")
        if design == "morris":
            settings["levels"] = _integer(table, "levels", 4, 2, 16, where)
            if settings["levels"] % 2:
                raise where.error("levels", settings["levels"], "Morris trajectories need an even number of "
                                  "levels", "an even integer in [2, 16]")
        elif "levels" in table:
            raise where.error("levels", table["levels"], "only a Morris design has levels", 'design = "morris"')
    if "point" in table:
        point = table["point"]
        forces, voltages = base.loads.normal_forces, base.loads.voltages
        if not (isinstance(point, list) and len(point) == 2 and point[0] in forces and point[1] in voltages):
            raise where.error("point", point, "not a load and a voltage of the scene",
                              f"[F_N, U] with F_N one of {list(forces)} N and U one of {list(voltages)} V")
        settings["point"] = (float(point[0]), float(point[1]))
    return settings


def _integer(table, key, default, low, high, where: _Located) -> int:
    value = table.get(key, default)
    if value is None:
        raise where.error(None, None, f"a {table.get('design')} design needs {key}", f"{key} = an integer in "
                          f"[{low}, {high}]")
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise where.error(key, value, "out of range", f"an integer in [{low}, {high}]")
    return value


def read_variation(table, base: Scene, where: _Located, read_scan: bool = True) -> Variation:
    """The :class:`Variation` of the ``[vary]`` ``table`` on the ``base`` scene."""
    if not isinstance(table, dict):
        raise where.error(None, None, "[vary] must be a table", "[vary] with its inputs and settings")
    inputs, settings = [], {}
    for name, value in _entries(table):
        if "." not in name:
            if name not in SETTINGS:
                raise where.error(name, value, "unknown key", "the settings " + ", ".join(SETTINGS)
                                  + ' or an input "section.key"')
            settings[name] = value
        elif name in (item.name for item in inputs):
            raise where.error(name, value, "given twice (once quoted, once as a dotted key?)", "each input once")
        else:
            inputs.append(_read_input(name, value, base, where, read_scan))
    if not inputs:
        raise where.error(None, None, "no input varies", '"section.key" = [values] for at least one input')
    frequency = base.screen.frequency
    if frequency is not None and len(frequency) > 1:
        raise where.error(None, None, f"the scene sweeps screen.frequency = {list(frequency)} Hz; a parameter "
                          "study compares its variants at one frequency", "one screen.frequency, or vary it")
    return Variation(inputs=tuple(inputs), **_read_settings(settings, base, where))


# ---------------------------------------------------------------------------------------------------------
# Designs
# ---------------------------------------------------------------------------------------------------------
def salib_problem(names) -> dict:
    """SALib's problem of the inputs ``names`` on the unit cube (:meth:`Input.at` maps it to the values)."""
    return {"num_vars": len(names), "names": list(names), "bounds": [[0.0, 1.0]] * len(names)}


def _salib(design: str):
    try:
        import SALib.sample.morris
        import SALib.sample.sobol
    except ImportError:
        raise ImportError(f"[vary] design = {design!r} samples with SALib: pip install 'roughcontact[sensitivity]'"
                          ) from None
    return SALib.sample


def unit_sample(variation: Variation) -> np.ndarray:
    """The sampler's points of a global design in the unit cube, shape (variants, inputs): SALib's Morris
    trajectories or its Sobol'/Saltelli sample (first and total order, no second order)."""
    sample, problem = _salib(variation.design), salib_problem(variation.names)
    if variation.design == "morris":
        return sample.morris.sample(problem, variation.samples, num_levels=variation.levels, seed=variation.seed)
    return sample.sobol.sample(problem, variation.samples, calc_second_order=False, seed=variation.seed)


def design_variants(base: Scene, variation: Variation, folder: Path | None = None, read_scan: bool = True,
                    where: _Located | None = None) -> tuple:
    """``(variants, unit sample)`` of ``variation`` on ``base``: one at a time, the baseline then each input at
    each of its levels; a global design, one variant per sampled point. Each variant's scene is validated (a
    relation between inputs, such as the two cut-offs, can fail for one combination: ValueError naming it)."""
    baseline = tuple(scene_value(base, name) for name in variation.names)
    if variation.design == DESIGNS[0]:
        points = [("baseline", {})]
        points += [(f"{item.name} = {Path(level).name if isinstance(level, str) else format(level, 'g')}",
                    {item.name: level}) for item in variation.inputs for level in item.levels]
        unit = None
    else:
        unit = unit_sample(variation)
        points = [(f"sample {n}", {item.name: item.at(u) for item, u in zip(variation.inputs, row)})
                  for n, row in enumerate(unit)]
    if len(points) > MAX_VARIANTS:
        raise ValueError(f"the design makes {len(points)} variants; at most {MAX_VARIANTS}: fewer samples or inputs")
    variants = []
    for index, (label, values) in enumerate(points):
        try:
            scene = substitute(base, values, folder, read_scan)
        except (TypeError, ValueError, ImportError, OSError) as error:
            message = f"variant {index} ({label}; {', '.join(f'{k} = {v!r}' for k, v in values.items())}): {error}"
            raise (where.error(None, None, message) if where is not None else ValueError(message)) from None
        variants.append(Variant(index=index, label=label, values=tuple(
            scene_value(scene, name) for name in variation.names) if values else baseline, scene=scene))
    return tuple(variants), unit


def has_variation(path=None, *, text: str | None = None) -> bool:
    """Whether the scene file ``path`` (or ``text``) has a ``[vary]`` table (False where it is not valid TOML:
    :func:`~.scene.load_scene` names the error)."""
    if path is not None:
        text = read_scene_file(path)
    try:
        return VARY in tomllib.loads(text or "")
    except tomllib.TOMLDecodeError:
        return False


def load_variant_study(path=None, *, text: str | None = None, preset: str | None = None, target_error=None,
                       read_scan: bool = True) -> VariantStudy:
    """The parameter study of the scene file ``path`` (or TOML ``text``) with its ``[vary]`` table: the base
    scene at ``preset`` (with "auto" the cheapest measured setting meeting ``target_error``, as ``roughcontact
    run --preset auto``), the variation and every variant, built and validated (ValueError naming the file, line,
    key and value). ``read_scan`` False leaves measured scans unread (a results directory's study)."""
    if path is not None and text is not None:
        raise ValueError("give a scene path or its text, not both")
    if (preset == AUTO) != (target_error is not None):
        raise ValueError(f"--preset auto and --target-error go together (got preset {preset!r}, target error "
                         f"{target_error!r})")
    base = load_scene(path, text=None if path is not None else text, preset=None if preset == AUTO else preset,
                      read_scan=read_scan, vary=True)
    if preset == AUTO:
        base = auto_scene(base, parse_target(target_error))
    origin = str(path) if path is not None else "scene"
    text = read_scene_file(path) if path is not None else (text or "")
    folder = Path(path).parent if path is not None else Path.cwd()
    table = parse_scene_text(text, origin).get(VARY)
    where = _Located(origin, text, folder)
    if table is None:
        raise where.error(None, None, "the scene has no [vary] table", "a [vary] table with the inputs to vary")
    variation = read_variation(table, base, where, read_scan)
    variants, unit = design_variants(base, variation, folder, read_scan, where)
    return VariantStudy(base=base, variation=variation, variants=variants, unit_sample=unit)
