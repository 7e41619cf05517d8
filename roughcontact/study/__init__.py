"""The multiscale fingerpad study: d_eq(F_N, U) and A_R(F_N, U) bottom-up from a scene (``docs/findings/equivalent_gap.md``).
Layer 4: imports the solvers, the body, the interaction laws, the macroscopic model and io below it.

Inside, imports run one way: :mod:`.scene` (the scene file) ← :mod:`.presets` (the measured preset table) ←
:mod:`.variants` (a parameter study's ``[vary]`` table and its variants); :mod:`.fingertip` (the cap on the layered skin) ← :mod:`.apparent` (apparent area and nominal pressures) and
:mod:`.patch` (the periodic patch and what is measured on its gap) ← :mod:`.plan` (the study planned once: the
patch grid, closing lengths, cut-off, a measured patch, the tasks with their content keys) and :mod:`.records` (a
task's records, a point's intervals) ← :mod:`.resolved` (ridges and roughness in one grid) and :mod:`.coupled`
(the roughness as an interface law on the ridges) ← :mod:`.execution` (task store, results directory, pool,
dask) ← :mod:`.run` (:func:`run_study`) ← :mod:`.friction` (the seed's friction law fed bottom-up) ←
:mod:`.sensitivity` (the outputs' sensitivity to a study's inputs) ← :mod:`.variant_run` (:func:`run_variants`) ←
:mod:`.tables` (the CSV tables and the samples they share) ← :mod:`.dataset` (``results.nc``) and
:mod:`.figures` (the PNG figures) ← :mod:`.report` (``report.md``, and :func:`write_results`, all of it on
disk).

The names below load their module on first use (PEP 562), so ``roughcontact.study.scene`` stays light.
"""
from __future__ import annotations

from surfaces.lazy import lazy_attributes

# public name -> submodule that defines it
_LAZY = {
    "DEFAULT_SCENE_TOML": "scene",
    "Scene": "scene",
    "load_scene": "scene",
    "scene_at_preset": "presets",
    "fingertip_contact": "fingertip",
    "apparent_contact": "apparent",
    "apparent_scale": "apparent",
    "patch_body": "patch",
    "patch_grid": "patch",
    "patch_surface": "patch",
    "ridge_area_fraction": "patch",
    "PatchScaleWarning": "patch",
    "PatchRecord": "records",
    "PointResult": "records",
    "confidence_interval": "records",
    "StudyPlan": "plan",
    "Task": "plan",
    "plan_study": "plan",
    "solve_chain": "resolved",
    "InterfaceLaw": "coupled",
    "coupled_chain": "coupled",
    "interface_law": "coupled",
    "TaskStore": "execution",
    "ResultsDirectory": "execution",
    "StaleTaskWarning": "execution",
    "StudyResult": "run",
    "run_study": "run",
    "checked_plan": "run",
    "open_results": "variant_run",
    "bottom_up_friction": "friction",
    "friction_recipe": "friction",
    "friction_realisations": "friction",
    "write_results": "report",
    "load_variant_study": "variants",
    "has_variation": "variants",
    "literature_ranges": "variants",
    "VariantStudy": "variants",
    "run_variants": "variant_run",
    "plan_variants": "variant_run",
    "open_variant_results": "variant_run",
    "VariantStudyResult": "variant_run",
    "Sensitivity": "sensitivity",
}

__getattr__, __dir__, __all__ = lazy_attributes(__name__, _LAZY, [])
