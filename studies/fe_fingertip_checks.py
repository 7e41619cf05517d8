"""The FE fingertip's validation and sensitivity runs (a script; needs roughcontact[fe]; see
docs/guide/fe_fingertip.md and docs/findings/fe_fingertip.md).

    python studies/fe_fingertip_checks.py hertz --output out          # 2-D Hertz check, mesh series
    python studies/fe_fingertip_checks.py convergence --output out    # mesh, travel step, penalty
    python studies/fe_fingertip_checks.py sensitivity --output out    # L0, ξ and the exponent vs parameters

``hertz``: a round section (R = 10 mm, concentric rigid core of 3 mm) of one neo-Hookean solid (μ = 10 kPa,
ν = 0.3) pressed frictionlessly by the load P of a Hertz half-width a = R/20; the contact length L against
2a = 2√(4PR/(πE*)) on three meshes refined by 1, 2 and 3 in every direction, and the half-width from the
second moment of the contact force, 2√⟨x²⟩ (a for the Hertz pressure), independent of the edge estimate.

``convergence``: press-and-slide at f_N = 200 N/m, μ = 0.26 and at 50 N/m, μ = 2 on each candidate mesh and
its ×1.5 refinement, and on the default mesh with half the travel step and the contact penalty ×0.3 and ×3;
L0, L at full slip, ξ (runs on a pool of two processes).

``sensitivity``: a sweep over the finger's 0.5, 1 and 2 N (f_N = F_N/w = 53, 92, 163 N/m) at μ0 = 0.26 on the
coarse mesh (``SENSITIVITY_MESH``) for the default parameters and one parameter changed at a time (tissue moduli
×½ and ×2, the subcutaneous exponent α, the skin thickness, the seed's μ = 0.35); L0 and ξ at 1 N, the
reductions at full slip and their growth from 1 to 2 N (Sirin et al. 2019b: 8 % → 15 %), the exponent of ξ(f_N).

Each writes ``fe_fingertip_<check>.csv`` with its provenance.
"""
from __future__ import annotations

import argparse
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import replace

import numpy as np

from roughcontact.fe.analysis import fit_eq34
from roughcontact.fe.feed import line_load
from roughcontact.fe.geometry import FingerSection, MeshResolution
from roughcontact.fe.materials import FingerMaterials, OgdenMaterial
from roughcontact.fe.model import FingertipModel, default_travel_step
from roughcontact.fe.study import run_fingertip_study
from roughcontact.io.provenance import output_directory, parse_arguments, write_csv

#: The Hertz press's approach step (/ R): 0.1 mm, a few times the indentation; the finger's default (0.05, i.e.
#: 0.5 mm here) overshoots the small Hertz load some hundredfold, and on the 200-ray mesh the press then comes
#: back to a contact 9 % too long.
HERTZ_APPROACH_STEP = 0.01
#: Processes of the checks' pools (the machine's two cores).
WORKERS = 2
#: The friction law's μ0: the FE's contact at 0 V.
MU0 = 0.26
#: The sensitivity runs' mesh: the coarse one (a fifth of the default's cost); the convergence check measures
#: its error.
SENSITIVITY_MESH = MeshResolution.coarse()


def hertz_rows():
    radius, shear, poisson = 10e-3, 10e3, 0.3
    materials = FingerMaterials.homogeneous(shear, poisson)
    e_star = materials.skin.plane_strain_modulus
    half_width = radius / 20
    load = np.pi * e_star * half_width ** 2 / (4 * radius)          # a = √(4PR/(πE*)) inverted [N/m]
    rows = []
    for around, refinement, subcutaneous, skin in ((100, 0.05, 5, 2), (200, 0.05, 10, 4), (300, 0.05, 15, 6)):
        resolution = MeshResolution(around=around, subcutaneous=subcutaneous, skin=skin,
                                    contact_refinement=refinement, grading=2.0)
        model = FingertipModel(section=FingerSection.circular(radius, 3e-3, 0.3e-3), materials=materials,
                               resolution=resolution, approach_step=HERTZ_APPROACH_STEP)
        pressed = model.press(load)
        snapshot = pressed.snapshot
        spacing = np.diff(snapshot.x)[np.argmin(np.abs(snapshot.x[:-1]))]
        weight = snapshot.normal / snapshot.normal.sum()
        centre = np.sum(weight * snapshot.x)
        moment_half_width = 2 * np.sqrt(np.sum(weight * (snapshot.x - centre) ** 2))   # Hertz: <x²> = a²/4
        rows.append({"around": around, "half_width_per_spacing": half_width / spacing,
                     "moment_half_width_over_hertz": moment_half_width / half_width,
                     "length_over_hertz": snapshot.length() / (2 * half_width),
                     "gap_length_over_hertz": snapshot.length("gap") / (2 * half_width),
                     "carried_over_load": snapshot.normal.sum() / load})
    return rows


def _run_row(label, model, force=200.0, travel_step=None):
    start = time.process_time()
    run = model.slide(force, travel_step=travel_step)
    fit = fit_eq34(run.tangential_force, run.length)
    return {"case": label, "normal_force_N_per_m": force, "friction": model.friction,
            "initial_length_m": run.initial_length,
            "sliding_length_m": run.sliding_length, "relative_reduction": run.relative_reduction,
            "xi_m3_per_N2": -fit.slope, "xi_error_m3_per_N2": fit.slope_error,
            "coulomb_ratio_minus_1": run.tangential_force[-1] / (run.friction * force) - 1,
            "full_slip": run.full_slip, "increments": len(run.travel) - 1, "seconds": round(run.seconds, 1),
            "cpu_seconds": round(time.process_time() - start, 1)}


def _in_parallel(cases):
    """The rows of ``cases`` (argument tuples of :func:`_run_row`, the travel step optional) on a process pool,
    in their order."""
    cases = [(*case, *(None,) * (4 - len(case))) for case in cases]
    with ProcessPoolExecutor(WORKERS) as pool:
        return list(pool.map(_run_row, *zip(*cases)))


#: The meshes of the convergence check, each against its x1.5 refinement.
CANDIDATE_MESHES = {"medium": MeshResolution(around=112, subcutaneous=7, skin=2, contact_refinement=0.2),
                    "default": MeshResolution()}


def convergence_rows():
    default = FingertipModel(friction=MU0)
    cases = []
    for name, mesh in CANDIDATE_MESHES.items():
        for label, resolution in ((name, mesh), (f"{name} x1.5", mesh.refined(1.5))):
            cases += [(f"mesh {label}", replace(default, resolution=resolution), 200.0),
                      (f"mesh {label}", replace(default, resolution=resolution, friction=2.0), 50.0)]
    cases += [("travel step x0.5", default, 200.0, default_travel_step(200.0, MU0) / 2),
              ("penalty x0.3", replace(default, penalty=300.0), 200.0),
              ("penalty x3", replace(default, penalty=3000.0), 200.0)]
    return _in_parallel(cases)


def _scaled(material: OgdenMaterial, factor: float) -> OgdenMaterial:
    return OgdenMaterial(mu=tuple(m * factor for m in material.mu), alpha=material.alpha, bulk=material.bulk * factor)


def _tissue(model: FingertipModel, **materials) -> FingertipModel:
    return replace(model, materials=replace(model.materials, **materials))


#: The finger's 0.5, 1 and 2 N as forces per unit width of the section, F_N/w (``roughcontact.fe.feed``) [N/m].
SENSITIVITY_FORCES = tuple(float(line_load(f)) for f in (0.5, 1.0, 2.0))


def sensitivity_rows():
    base = FingertipModel(resolution=SENSITIVITY_MESH, friction=MU0)
    skin, pulp = base.materials.skin, base.materials.subcutaneous
    cases = {"default": base,
             "skin mu x0.5": _tissue(base, skin=_scaled(skin, 0.5)),
             "skin mu x2": _tissue(base, skin=_scaled(skin, 2.0)),
             "subcutaneous mu x0.5": _tissue(base, subcutaneous=_scaled(pulp, 0.5)),
             "subcutaneous mu x2": _tissue(base, subcutaneous=_scaled(pulp, 2.0)),
             "subcutaneous alpha 4": _tissue(base, subcutaneous=replace(pulp, alpha=(4.0,))),
             "skin 0.7 mm": replace(base, section=replace(base.section, skin_thickness=0.7e-3)),
             "skin 1.3 mm": replace(base, section=replace(base.section, skin_thickness=1.3e-3)),
             "friction 0.35 (the seed's FE)": replace(base, friction=0.35)}
    rows = []
    for label, model in cases.items():
        study = run_fingertip_study(model, SENSITIVITY_FORCES, workers=WORKERS)
        fits = study.eq34_fits()
        exponent = study.exponent()
        low, one, two = study.runs
        rows.append({"case": label, "initial_length_1N_m": one.initial_length,
                     "reduction_0.5N": low.relative_reduction, "reduction_1N": one.relative_reduction,
                     "reduction_2N": two.relative_reduction,
                     "reduction_ratio_2N_over_1N": two.relative_reduction / one.relative_reduction,
                     "xi_1N_m3_per_N2": -fits[1].slope, "exponent_xi": exponent.slope,
                     "exponent_xi_error": exponent.slope_error,
                     "full_slip": all(run.full_slip for run in study.runs),
                     "cpu_seconds": round(sum(run.cpu_seconds for run in study.runs))})
        print(rows[-1], flush=True)
    return rows


CHECKS = {"hertz": hertz_rows, "convergence": convergence_rows, "sensitivity": sensitivity_rows}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("check", choices=sorted(CHECKS))
    parser.add_argument("--output", default="out")
    args, provenance = parse_arguments(parser, argv, "python studies/fe_fingertip_checks.py")
    output = output_directory(args.output)
    write_csv(output / f"fe_fingertip_{args.check}.csv", CHECKS[args.check](), provenance, echo=True)


if __name__ == "__main__":
    main()
