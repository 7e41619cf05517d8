"""Measured errors and costs of the study's settings, and the cheapest setting for a target error.

``preset_errors.csv`` beside this module is written by ``studies/preset_pareto.py --library``: one row per
measured setting (the :class:`~roughcontact.study.scene.Preset` keys :data:`SETTING_KEYS` and ``realisations``), its
CPU seconds on the default scene's four points (F_N = 0.5, 2 N; U = 0, 200 V; one FFT thread) and its error on
each scene of the experiment, the largest relative difference of d_eq, A_R/A0 and F_T at 200 V from the
reference setting (``docs/guide/presets.md``). :func:`measured` looks a preset up in it, so that a run's report quotes
its error; :func:`choose` picks the cheapest setting whose error meets a target (``roughcontact run --preset
auto --target-error 2%``), and :func:`auto_scene` puts it into a scene as ``[presets.auto]``.

The columns :data:`RESOLUTION_COLUMNS`, written by ``studies/resolution.py --library`` after the table, hold the
discretisation error of the setting's pixel (ridge period / grid × periods) against 0.11 µm pixels
(``docs/guide/presets.md``, "Discretisation error of F_el and d_eq"; with the layered law's default model of
the contact line, air breakdown, F_el changes by less than 0.1 % beyond that pixel): ``fel_error`` of the layered
attraction F_el at 200 V, ``deq_error`` of Eq. 25's d_eq (0 and 200 V) and ``field_deq_error`` of the
field-equivalent gap at 200 V, each the largest magnitude of the relative error of the realisation mean over
F_N = 0.5 and 2 N, measured on 1-D profiles of the default scene; empty (nan) for a pixel not measured. The
errors of the other columns are against the reference setting, which is itself that far from converged: the reference's
discretisation error is the floor of what ``--preset auto`` can promise (:func:`error_floor`).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path

from surfaces.validation import check_real

from ..io.provenance import read_csv, write_atomic, write_csv
from .scene import AUTO, Preset, Scene, load_scene

#: The discretisation errors of a setting's pixel (fractions; module docstring).
RESOLUTION_COLUMNS = ("fel_error", "deq_error", "field_deq_error")
#: The measured table (package data).
TABLE_PATH = Path(__file__).with_name("preset_errors.csv")
#: The Preset keys that a measured setting fixes (with ``realisations``); ``rings`` acts on the fingertip model
#: only, which the measurement does not use.
SETTING_KEYS = ("grid", "periods", "tolerance", "dtype", "warm_start", "scales", "pixels_per_cutoff")
_TYPES = {"grid": int, "periods": int, "realisations": int, "tolerance": float, "pixels_per_cutoff": float,
          "dtype": str, "scales": str, "warm_start": lambda text: {"True": True, "False": False}[text]}
#: The scenes of the measurement: the default one, on which the presets are chosen, and two that are not.
SCENES = ("default", "rough", "smooth")


@dataclass(frozen=True)
class Measurement:
    """One measured setting: ``setting`` (the :data:`SETTING_KEYS` and ``realisations``), ``cpu_seconds`` of the
    default scene's four points, ``errors`` per scene (fractions) and ``error``, the largest of them, against the
    reference setting; ``discretisation``: the :data:`RESOLUTION_COLUMNS` of its pixel (nan: not measured)."""

    setting: dict
    cpu_seconds: float
    errors: dict
    error: float
    discretisation: dict = None

    @property
    def discretisation_error(self) -> float:
        """The largest of the :data:`RESOLUTION_COLUMNS` (nan when none was measured)."""
        values = [value for value in (self.discretisation or {}).values() if not math.isnan(value)]
        return max(values) if values else math.nan

    def preset(self, rings: int) -> Preset:
        """The setting as a :class:`Preset`, with ``rings`` (not measured) given."""
        return Preset(rings=rings, **self.setting)

    def matches(self, preset: Preset) -> bool:
        return all(getattr(preset, key) == value for key, value in self.setting.items())


def read_table(path=TABLE_PATH) -> tuple:
    """The measured settings of the CSV table ``path`` (default: the library's), by increasing cost."""
    rows = read_csv(path)
    table = [Measurement(setting={key: _TYPES[key](row[key]) for key in (*SETTING_KEYS, "realisations")},
                         cpu_seconds=float(row["cpu_seconds"]),
                         errors={scene: float(row[f"error_{scene}"]) for scene in SCENES},
                         error=float(row["error"]),
                         discretisation={column: float(row.get(column) or "nan") for column in RESOLUTION_COLUMNS})
             for row in rows]
    return tuple(sorted(table, key=lambda entry: entry.cpu_seconds))


def write_table(entries, provenance, path=TABLE_PATH) -> Path:
    """Write the per-setting ``entries`` (dicts with the :data:`SETTING_KEYS`, ``realisations``,
    ``cpu_seconds``, ``error_<scene>`` for each of :data:`SCENES` and ``error``, optionally the
    :data:`RESOLUTION_COLUMNS`) as the table ``path``."""
    columns = (*SETTING_KEYS, "realisations", "cpu_seconds", *(f"error_{scene}" for scene in SCENES), "error",
               *RESOLUTION_COLUMNS)
    return write_csv(path, entries, provenance, columns)


def add_resolution_errors(errors: dict, period: float, provenance, path=TABLE_PATH) -> Path:
    """Fill the :data:`RESOLUTION_COLUMNS` of the table ``path`` from ``errors`` ({pixels per ridge period:
    (fel_error, deq_error, field_deq_error)}, fractions; ``period`` [m] the ridge period), matching each row by
    its pixel, grid / periods per period; empty for a pixel not in ``errors``. The table's provenance comment
    is kept and ``provenance``'s added below it."""
    with open(path) as stream:
        comments = [line for line in stream if line.startswith("#") and "resolution.py" not in line]
    rows = read_csv(path)
    for row in rows:
        measured_errors = errors.get(int(row["grid"]) / int(row["periods"]), ("",) * len(RESOLUTION_COLUMNS))
        row.update(zip(RESOLUTION_COLUMNS, measured_errors))
    write_table(rows, None, path)
    with open(path) as stream:
        body = stream.read()
    return write_atomic(path, "".join(comments) + f"# {provenance.line}\n" + body)


def measured(preset: Preset, table=None) -> Measurement | None:
    """The measurement of ``preset``'s setting, or None when it was not measured."""
    return next((entry for entry in (read_table() if table is None else table) if entry.matches(preset)), None)


def parse_target(text) -> float:
    """A target error as a fraction: ``"2%"`` → 0.02, ``"0.02"`` → 0.02; in (0, 1]."""
    original = text
    text = str(text).strip()
    scale = 0.01 if text.endswith("%") else 1.0
    try:
        value = float(text.removesuffix("%")) * scale
    except ValueError:
        raise ValueError(f"target error {original!r} is not a number or a percentage (e.g. 2% or 0.02)") from None
    return check_real("target error", value, low=0.0, high=1.0, low_open=True)


def error_floor(table=None) -> tuple:
    """``(floor, reason)``: the smallest error a measured setting can promise (a fraction). The reference
    setting's error against itself is 0 by definition and promises nothing; its own error is its
    discretisation error (the :data:`RESOLUTION_COLUMNS` of its row) where measured, else the smallest
    non-zero error of the table (the best that a comparison with the reference resolves)."""
    table = read_table() if table is None else table
    references = [entry for entry in table if entry.error == 0]
    measured_floor = max((entry.discretisation_error for entry in references), default=math.nan)
    if not math.isnan(measured_floor):
        return measured_floor, ("the reference setting's own discretisation error of F_el and the equivalent "
                                "gaps, measured on 1-D profiles against 0.11 um pixels")
    if not references:
        return min(entry.error for entry in table), "the smallest error of any measured setting"
    return (min(entry.error for entry in table if entry.error > 0),
            "the smallest error measured against the reference setting, whose own error is not measured")


def choose(target_error: float, table=None) -> Measurement:
    """The cheapest measured setting whose error (the largest over the measured scenes) is at most
    ``target_error`` (a fraction in (0, 1]); ``ValueError`` below :func:`error_floor`, which no measured
    setting can promise."""
    target_error = check_real("target_error", target_error, low=0.0, high=1.0, low_open=True)
    table = read_table() if table is None else table
    floor, reason = error_floor(table)
    if target_error < floor:
        raise ValueError(f"target error {100 * target_error:g} % cannot be promised: the most accurate measured "
                         f"setting is the reference, whose error against itself is 0 by definition; the floor is "
                         f"{100 * floor:.3g} %, {reason} (docs/guide/presets.md); valid: at least {100 * floor:.3g} %")
    meeting = [entry for entry in table if entry.error <= target_error]
    return min(meeting, key=lambda entry: entry.cpu_seconds)


def auto_scene(scene: Scene, target_error: float, table=None) -> Scene:
    """``scene`` at the cheapest setting meeting ``target_error``, held as ``presets.auto`` (``rings`` from the
    scene's standard preset)."""
    chosen = choose(target_error, table)
    return scene.with_setting(chosen.preset(rings=scene.presets["standard"].rings))


def describe(preset: Preset, name: str, table=None) -> str:
    """One paragraph for a run's report: the measured error and cost of ``preset`` (named ``name``), or that
    its setting was not measured, and the discretisation error of its pixel where measured."""
    entry = measured(preset, table)
    if entry is None:
        return (f"The setting of preset `{name}` is not among the measured settings of `docs/guide/presets.md`: its "
                "error against the reference setting is not known.")
    chosen = " (chosen by --preset auto)" if name == AUTO else ""
    if entry.error == 0:
        floor, reason = error_floor(table)
        text = (f"Preset `{name}`{chosen} is the reference setting of `docs/guide/presets.md`: its error against "
                f"itself is 0 by definition and not a measured error. Its floor is {100 * floor:.2g} %, {reason}; "
                f"{entry.cpu_seconds:.3g} CPU seconds for the four measured points.")
    else:
        errors = ", ".join(f"{100 * entry.errors[scene]:.2g} % on the {scene} scene" for scene in SCENES)
        text = (f"Measured error of preset `{name}`{chosen} against the reference setting (largest relative "
                f"difference of d_eq, A_R/A0 and F_T at 200 V at F_N = 0.5, 2 N and U = 0, 200 V; "
                f"`docs/guide/presets.md`): {errors}; {entry.cpu_seconds:.3g} CPU seconds for those four points. It "
                "holds for scenes like these; a scene far from them may err differently.")
    return text + _discretisation_sentence(entry)


#: The sections of a scene whose physics the measured errors depend on, and the range of the one key the measured
#: scenes vary (the default scene, and it with 5 and 1 µm rms roughness: ``studies/preset_pareto.py``).
_PHYSICS_SECTIONS = ("fingerpad", "ridges", "roughness", "skin", "screen", "ridge_area")
_MEASURED_RMS_HEIGHT = (1e-6, 5e-6)


def applicability(scene: Scene) -> str:
    """For the report beside :func:`describe`: nothing where ``scene``'s physics lies within the measured scenes'
    (the default scene with a roughness rms height of 1–5 µm), otherwise a sentence naming the keys by which it
    differs."""
    default = load_scene()
    differing = [f"{section}.{f.name}" for section in _PHYSICS_SECTIONS
                 for f in dataclasses.fields(getattr(scene, section))
                 if not (section == "roughness" and f.name == "rms_height")
                 and getattr(getattr(scene, section), f.name) != getattr(getattr(default, section), f.name)]
    rms = scene.roughness.rms_height
    if not _MEASURED_RMS_HEIGHT[0] <= rms <= _MEASURED_RMS_HEIGHT[1]:
        differing.append(f"roughness.rms_height = {rms:g} m (measured: 1–5 µm)")
    if not differing:
        return ""
    return (" These errors were measured on the default scene with 1, 3 and 5 µm rms roughness; this scene differs "
            f"in {', '.join(differing)}, so its errors may differ and are not known.")


def _discretisation_sentence(entry: Measurement) -> str:
    """The discretisation error of the preset's pixel against the reference pixel, where measured."""
    error = entry.discretisation
    if not error or all(math.isnan(error[column]) for column in RESOLUTION_COLUMNS):
        return ""
    return (f" Discretisation error of its pixel (1-D profiles of the default scene against 0.11 µm pixels, beyond "
            f"which the layered F_el with air breakdown at its contact lines changes by less than 0.1 %; "
            f"`docs/guide/presets.md`, 'Discretisation error of F_el and d_eq'): the layered field's F_el "
            f"±{100 * error['fel_error']:.2g} %, d_eq (Eq. 25) ±{100 * error['deq_error']:.2g} %, the "
            f"field-equivalent gap ±{100 * error['field_deq_error']:.2g} %.")


def scene_at_preset(path=None, preset: str | None = None, target_error=None, table=None) -> Scene:
    """The scene of ``roughcontact run``: the scene file ``path`` (None: the default scene) at ``preset``, or,
    with ``preset`` "auto", at the cheapest measured setting whose error meets ``target_error`` (a fraction or
    a percentage such as ``"2%"``); ``target_error`` goes with "auto" only."""
    if (preset == AUTO) != (target_error is not None):
        raise ValueError(f"--preset auto and --target-error go together (got preset {preset!r}, target error "
                         f"{target_error!r})")
    if preset != AUTO:
        return load_scene(path, preset=preset)
    return auto_scene(load_scene(path), parse_target(target_error), table)
