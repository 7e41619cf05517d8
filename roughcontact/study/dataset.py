"""A fingerpad study as an ``xarray.Dataset``, written as ``results.nc`` (xarray + h5netcdf): every field per
load, voltage (frequency) and realisation in SI units, the friction variables, and the scene, preset, seed and
version in the attributes. xarray is imported where a dataset is built, not with :mod:`roughcontact.study`."""
from __future__ import annotations

import numpy as np

from .._version import __version__
from .friction import friction_computed
from .records import CONFIDENCE
from .run import StudyResult
from .tables import FIELDS, FLAG_DESCRIPTIONS, friction_rows, input_value, point_flags


def dataset(result: StudyResult, friction: bool = True):
    """The study as an ``xarray.Dataset`` (SI units in every variable's ``units``; scene, preset, seed and
    version in the attributes); a frequency sweep with a ``frequency`` dimension [Hz] after ``voltage`` (and no
    friction variables); ``friction`` False leaves the friction variables out."""
    import xarray as xr
    if result.frequencies:
        frequency = xr.DataArray(np.array(result.frequencies), dims="frequency", name="frequency",
                                 attrs={"units": "Hz"})
        parts = [dataset(result.at_frequency(k), friction=False) for k in range(len(result.frequencies))]
        data = xr.concat(parts, dim=frequency)
        data["apparent_area"] = parts[0]["apparent_area"]                 # one per load
        return data.transpose("normal_force", "voltage", "frequency", ...)
    scene = result.scene
    coords = {"normal_force": ("normal_force", result.normal_forces, {"units": "N"}),
              "voltage": ("voltage", result.voltages, {"units": "V"}),
              "realisation": ("realisation", np.arange(result.array("equivalent_gap").shape[-1])),
              "coarse_graining": ("coarse_graining", np.array(result.coarse_graining), {"units": "m"})}
    dims = ("normal_force", "voltage", "realisation")
    units = {"equivalent_gap": "m", "field_equivalent_gap": "m", "ridge_equivalent_gap": "m", "mean_gap": "m",
             "contact_fraction": "1", "electrostatic_attraction": "Pa", "pixel_law_attraction": "Pa",
             "field_ratio": "1", "gap_slope": "1", "iterations": "1", "unstable_steps": "1"}
    descriptions = {name: text for name, _, _, _, text in FIELDS}
    variables = {name: (dims, result.array(name), {"units": unit, "long_name": descriptions.get(name, name)})
                 for name, unit in units.items()}
    variables["converged"] = (dims, result.array("converged").astype(np.int8), {"units": "1"})
    variables["ridge_area_fraction"] = (("normal_force", "voltage", "coarse_graining", "realisation"),
                                        result.array("ridge_area_fractions"),
                                        {"units": "1", "long_name": "A_R / A0 after closing at coarse_graining"})
    variables["apparent_area"] = (("normal_force",), result.array("apparent_area")[:, 0], {"units": "m2"})
    variables["solve_seconds"] = (("normal_force", "voltage"), result.array("seconds"), {"units": "s"})
    for name, values in point_flags(result).items():     # points that say nothing about the topography
        variables[name] = (("normal_force", "voltage"), values.astype(np.int8) if values.dtype == bool else values,
                           {"units": "1", "long_name": FLAG_DESCRIPTIONS[name]})
    friction = friction_rows(result) if friction and friction_computed(result) else []
    for key, unit in (("bottom_up_tangential_force_N", "N"), ("bottom_up_tangential_force_ci95_N", "N"),
                      ("seed_tangential_force_N", "N"), ("bottom_up_friction_coefficient", "1"),
                      ("bottom_up_friction_coefficient_ci95", "1"), ("seed_friction_coefficient", "1")):
        if friction:
            values = np.array([row[key] for row in friction]).reshape(len(result.normal_forces), -1)
            variables[key.removesuffix("_N")] = (("normal_force", "voltage"), values, {"units": unit})
    attrs = {"title": "roughcontact multiscale fingerpad study", "roughcontact_version": __version__,
             "preset": scene.study.preset, "field": scene.screen.field, "seed": scene.study.seed,
             "scene_toml": scene.to_toml(), "short_cutoff_in_use": result.short_cutoff, "confidence": CONFIDENCE}
    for key, value in scene.flat().items():
        attrs[f"scene.{key}"] = int(value) if isinstance(value, bool) else value
    if result.plan.topography is not None:             # a measured scan's missing points (report.md words them)
        record = result.plan.topography.metadata
        attrs.update({f"scan_{key}": record[key] for key in ("missing_points", "filled_fraction", "kept_fraction")
                      if key in record})
    return xr.Dataset(variables, coords=coords, attrs=attrs)


def write_dataset(result: StudyResult, out, provenance):
    """Write ``results.nc`` of ``result`` into the directory ``out`` with its provenance; its path."""
    data = dataset(result)
    data.attrs["provenance"] = provenance.line
    data.to_netcdf(out / "results.nc", engine="h5netcdf")
    return out / "results.nc"


def variant_dataset(result):
    """A parameter study (a :class:`VariantStudyResult`) as an ``xarray.Dataset``: each variant's study
    (:func:`dataset`, at its drive frequency) along a ``variant`` dimension, the varied inputs as coordinates on
    it (their names, e.g. ``skin.layer_E_star``; a topography's file name; NaN for an absent drive frequency),
    the outputs' sensitivity measures as ``sensitivity_<measure>`` (dimensions output, input, load, voltage);
    the base scene with its ``[vary]`` table and the design in the attributes."""
    import xarray as xr
    parts = [dataset(study.at_frequency(0) if study.frequencies else study) for study in result.results]
    data = xr.concat([part.drop_vars("apparent_area") for part in parts], dim="variant", combine_attrs="drop")
    data["apparent_area"] = xr.concat([part["apparent_area"] for part in parts], dim="variant")
    names = result.study.variation.names
    coords = {"variant": np.arange(len(result.variants)),
              "label": ("variant", [variant.label for variant in result.variants])}
    for n, name in enumerate(names):
        coords[name] = ("variant", [input_value(variant.values[n]) for variant in result.variants])
    data = data.assign_coords(coords)
    sensitivity = result.sensitivity
    for measure, values in sensitivity.measures.items():
        data[f"sensitivity_{measure}"] = (("output", "input", "normal_force", "voltage"), values,
                                          {"long_name": f"{sensitivity.design} sensitivity measure {measure}"})
    data = data.assign_coords(output=list(sensitivity.outputs), input=list(names))
    attrs = dict(parts[0].attrs)
    attrs.update({"title": "roughcontact parameter study of the multiscale fingerpad", "design": result.design,
                  "scene_toml": result.study.to_toml(), "ranked_by": sensitivity.ranked_by})
    data.attrs = {key: value for key, value in attrs.items() if not key.startswith("scene.")}
    return data


def write_variant_dataset(result, out, provenance):
    """Write ``results.nc`` of a parameter study into ``out`` with its provenance; its path."""
    data = variant_dataset(result)
    data.attrs["provenance"] = provenance.line
    data.to_netcdf(out / "results.nc", engine="h5netcdf")
    return out / "results.nc"
