"""The study planned once: :class:`StudyPlan`, what every task of a study shares, computed from the scene before
any task runs, and :class:`Task`, one realisation at one voltage (and drive frequency) with the content key of
its inputs.

The plan holds the patch grid, the A_R closing lengths, the micro-roughness cut-off in use, the realisation
count, the loads, voltages and drive frequencies, a measured scan's patch (read, levelled and given its boundary
once) and the task list. The tasks run from it (:func:`~.resolved.solve_chain`, :func:`~.coupled.coupled_chain`),
so nothing of the patch is worked out again per task, and a measured patch travels to the workers with the plan
(they need not see the scan's file).

**Content keys.** A task's key (:attr:`Task.key`) is the SHA-256 of :meth:`StudyPlan.inputs`, exactly the inputs
its records depend on: the library version; the voltage U_j and drive frequency f_k (and under a drive σ_sc and
the keys of a leak across the interface that are set; without a drive the layered law's model of the contact
line); every normal force (a task solves them in order, each warm-started from the last); the apparent scale's keys of
the fingerpad model in use (and the rings of a fingertip); the skin; the dielectric stack and its field model;
the patch — its grid, the ridges (pores only where there are any), the micro-roughness with its cut-off in use and
the rng stream seed + r where the patch is random, or, for a measured topography, the SHA-256 of the patch as
solved (grid and heights: the scan's bytes read with its options) instead of the scan's path; the closing
lengths; the solver settings of the preset (tolerance, dtype, warm start, scales, and the periods that size the
coupled path's ridge grid). Left out because no record depends on them: the scene's other voltages and
frequencies, the realisation count, the preset's name, the keys of an unused fingerpad model, a disabled
section's keys, a measured scan's path. So two scenes whose tasks have equal inputs give those tasks equal keys,
and a task directory keyed by them is shared by any set of scenes (:class:`~.execution.TaskStore`); a changed
input, a replaced scan included, is a new key, solved again, never a stored task reused.
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import warnings
from dataclasses import dataclass

import numpy as np

from surfaces import Grid, HeightField

from .._version import __version__
from .apparent import ring_count
from .patch import (PatchScaleWarning, check_patch, closing_lengths, patch_body, patch_grid, patch_scale_message,
                    patch_surface, realisation_count, resolved_short_cutoff)
from .scene import LEAK_KEYS, Scene, measured_topography


@dataclass(frozen=True)
class Task:
    """One task of a study: the patch of ``realisation`` r at voltage index ``voltage_index`` j (and drive
    frequency index ``frequency_index`` k of a frequency sweep, else None) under every load; ``key``, the
    SHA-256 (hex) of its inputs (:meth:`StudyPlan.inputs`)."""

    realisation: int
    voltage_index: int
    frequency_index: int | None
    key: str

    @property
    def index(self) -> tuple:
        """``(r, j)``, or ``(r, j, k)`` in a frequency sweep: the task's place in the study."""
        if self.frequency_index is None:
            return self.realisation, self.voltage_index
        return self.realisation, self.voltage_index, self.frequency_index


@dataclass(frozen=True, eq=False)
class StudyPlan:
    """What the tasks of ``scene``'s study share, worked out once (:func:`plan_study`): the patch ``grid``; the A_R
    ``closing_lengths`` [m] (the coarse-graining length, then its sensitivity factors on it); the micro-roughness
    ``short_cutoff`` in use [m] (NaN without synthetic roughness); the distinct patches, ``realisations``; the
    ``normal_forces`` [N], ``voltages`` [V] and drive ``frequencies`` [Hz] (empty without a drive); the measured
    patch ``topography`` (a HeightField, None for a synthetic patch) and its SHA-256 ``topography_digest``
    (:func:`field_digest`); the ``tasks`` in order (voltage, then frequency, then realisation). Two plans are
    equal when their scenes and their tasks (keys included) are."""

    scene: Scene
    grid: Grid
    closing_lengths: tuple
    short_cutoff: float
    realisations: int
    normal_forces: tuple
    voltages: tuple
    frequencies: tuple
    topography: HeightField | None
    topography_digest: str | None
    tasks: tuple = ()

    def __eq__(self, other):
        if not isinstance(other, StudyPlan):
            return NotImplemented
        return self.scene == other.scene and self.tasks == other.tasks

    __hash__ = None

    def task(self, realisation: int, voltage_index: int, frequency_index: int | None = None) -> Task:
        """The task at ``(r, j[, k])``."""
        index = (realisation, voltage_index) if frequency_index is None else (realisation, voltage_index,
                                                                              frequency_index)
        found = next((task for task in self.tasks if task.index == index), None)
        if found is None:
            raise ValueError(f"task {index} is not one of the study's ({self.realisations} realisation(s), "
                             f"{len(self.voltages)} voltage(s)"
                             + (f", {len(self.frequencies)} frequencies)" if self.frequencies else ")"))
        return found

    def describe(self, task: Task) -> str:
        """The task in words, for messages: "realisation 1 at 150 V" (", 100 Hz" under a drive)."""
        drive = "" if task.frequency_index is None else f", {self.frequencies[task.frequency_index]:g} Hz"
        return f"realisation {task.realisation} at {self.voltages[task.voltage_index]:g} V{drive}"

    def surface(self, realisation: int) -> np.ndarray:
        """Heights [m] of the patch of ``realisation``: the measured patch, or ridges plus micro-roughness."""
        if self.topography is not None:
            return self.topography.heights
        return patch_surface(self.scene, realisation, self.grid, self.short_cutoff)

    def body(self, threads: int | None = None):
        """The skin under the patch (:func:`~.patch.patch_body` on the plan's grid), ``threads`` FFT threads."""
        return patch_body(self.scene, self.grid, threads=threads)

    def inputs(self, realisation: int, voltage_index: int, frequency_index: int | None = None) -> dict:
        """Everything the records of task ``(r, j[, k])`` depend on, as plain JSON values (module docstring):
        its key is :func:`task_key` of this."""
        scene, preset = self.scene, self.scene.preset
        frequency = None if frequency_index is None else self.frequencies[frequency_index]
        screen = {key: getattr(scene.screen, key) for key in ("d_sc", "eps_sc", "d_i", "eps_i", "eps_a", "field")}
        if scene.screen.field == "layered" and frequency is None:     # the layered law's model of the contact line
            screen["contact_line"] = scene.screen.contact_line
        if frequency is not None:
            screen["sigma_sc"] = scene.screen.sigma_sc
            screen.update({key: getattr(scene.screen, key) for key, absent in LEAK_KEYS.items()
                           if getattr(scene.screen, key) != absent})          # the leak's keys that are set
        solver = {"tolerance": preset.tolerance, "dtype": preset.dtype, "warm_start": preset.warm_start,
                  "scales": preset.scales}
        if preset.scales == "coupled":
            solver["periods"] = preset.periods
        return {"roughcontact": __version__, "voltage": self.voltages[voltage_index], "frequency": frequency,
                "normal_forces": list(self.normal_forces), "apparent": _apparent_inputs(scene),
                "skin": _skin_inputs(scene.skin), "screen": screen, "patch": self._patch_inputs(realisation),
                "closing_lengths": list(self.closing_lengths), "solver": solver}

    def _patch_inputs(self, realisation: int) -> dict:
        grid = self.grid.to_dict()
        if self.topography is not None:
            return {"grid": grid, "measured": self.topography_digest}
        ridges, roughness = self.scene.ridges, self.scene.roughness
        pores = ridges.enabled and ridges.pore_density > 0
        return {"grid": grid,
                "ridges": None if not ridges.enabled else {
                    "period": ridges.period, "height": ridges.height, "width_ratio": ridges.width_ratio,
                    **({"pore_density": ridges.pore_density, "pore_diameter": ridges.pore_diameter,
                        "pore_depth": ridges.pore_depth} if pores else {})},
                "roughness": None if not roughness.enabled else {
                    "hurst": roughness.hurst, "rms_height": roughness.rms_height,
                    "long_cutoff": roughness.long_cutoff, "short_cutoff": self.short_cutoff},
                "stream": self.scene.study.seed + realisation if roughness.enabled or pores else None}


def _apparent_inputs(scene: Scene) -> dict:
    """The fingerpad keys of the apparent scale in use (:func:`~.apparent.apparent_scale`)."""
    fingerpad = scene.fingerpad
    if fingerpad.model == "power_law":
        return {"model": fingerpad.model, "area_prefactor": fingerpad.area_prefactor,
                "area_exponent": fingerpad.area_exponent}
    return {"model": fingerpad.model, "radius": fingerpad.radius, "E_star": fingerpad.E_star,
            "layer": fingerpad.layer, "rings": ring_count(scene),
            **({"layer_grid": fingerpad.layer_grid} if fingerpad.layer else {})}


def _skin_inputs(skin) -> dict:
    """The skin's keys that its body uses (:func:`~.fingertip.skin_body`): E_star alone for a half-space."""
    if skin.layer_thickness == 0:
        return {"E_star": skin.E_star, "layer_thickness": 0.0}
    return dataclasses.asdict(skin)


def task_key(inputs: dict) -> str:
    """The SHA-256 (hex) of ``inputs`` as canonical JSON (sorted keys, exact floats)."""
    text = json.dumps(inputs, sort_keys=True, separators=(",", ":"), allow_nan=False)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def field_digest(field: HeightField) -> str:
    """The SHA-256 (hex) of a height field's grid and heights (float64, little-endian): equal for equal fields."""
    digest = hashlib.sha256(json.dumps(field.grid.to_dict(), sort_keys=True).encode("utf-8"))
    digest.update(np.ascontiguousarray(field.heights, dtype="<f8").tobytes())
    return digest.hexdigest()


def plan_study(scene: Scene, topography: HeightField | None = None) -> StudyPlan:
    """The :class:`StudyPlan` of ``scene``: a measured topography read once (or ``topography``, the patch stored
    with a study's results, used instead of the scan), the patch (:func:`~.patch.check_patch`) and the cut-offs
    checked, every task keyed."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene (roughcontact.study.load_scene reads one from a TOML file), got "
                        f"{type(scene).__name__}")
    if topography is not None and not scene.roughness.topography:
        raise ValueError("topography given for a scene without a measured topography (roughness.topography)")
    if scene.roughness.topography:
        topography = measured_topography(scene.roughness) if topography is None else topography
        grid, cutoff = topography.grid, float("nan")
    else:
        grid = patch_grid(scene)
        check_patch(scene, grid)
        cutoff = resolved_short_cutoff(scene, grid) if scene.roughness.enabled else float("nan")
    if message := patch_scale_message(scene, grid):
        warnings.warn(message, PatchScaleWarning, stacklevel=2)
    plan = StudyPlan(scene=scene, grid=grid, closing_lengths=closing_lengths(scene), short_cutoff=cutoff,
                     realisations=realisation_count(scene), normal_forces=tuple(scene.loads.normal_forces),
                     voltages=tuple(scene.loads.voltages), frequencies=tuple(scene.screen.frequency or ()),
                     topography=topography, topography_digest=None if topography is None else field_digest(topography))
    drives = [None] if not plan.frequencies else range(len(plan.frequencies))
    tasks = tuple(Task(r, j, k, task_key(plan.inputs(r, j, k)))
                  for j in range(len(plan.voltages)) for k in drives for r in range(plan.realisations))
    return dataclasses.replace(plan, tasks=tasks)


def as_plan(scene) -> StudyPlan:
    """``scene`` if it is a :class:`StudyPlan`, else the plan of the Scene ``scene``."""
    return scene if isinstance(scene, StudyPlan) else plan_study(scene)
