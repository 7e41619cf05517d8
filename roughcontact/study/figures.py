"""The figures of a fingerpad study (PNG with their provenance): d_eq against load, the voltage dependence of
d_eq and the contact fractions, Eq. 25 against the field-equivalent gap, the friction recipe beside the seed's
model; for a drive-frequency sweep, F_el, d_eq and A_R/A0 against frequency. Every bar is the interval of
:func:`~.records.positive_interval` over the realisations."""
from __future__ import annotations

import numpy as np

from ..fe.feed import fe_friction_columns
from ..io.provenance import save_figure
from ..macro import LinearGap, PowerLawGap, SlidingFrictionModel
from .friction import bottom_up_friction, friction_computed, friction_realisations
from .records import confidence_interval, positive_interval
from .sensitivity import OUTPUTS
from .run import StudyResult
from .tables import MICRO, MM2, bars_note, point_flags, realisation_samples, sweep_crossover, sweep_samples

#: Fields bounded by 1 (fractions of A0): their intervals are taken on the log-odds scale.
FRACTIONS = ("ridge_area_fractions", "contact_fraction")


def _bars(result: StudyResult, name: str, scale: float = 1.0) -> tuple:
    """``(mean, [below, above])`` of field ``name`` for ``errorbar``: the realisation mean and the distances to
    the bounds of :func:`positive_interval` (each ≥ 0), both × ``scale``."""
    samples = realisation_samples(result, name)
    mean = confidence_interval(samples)[0]
    low, high = positive_interval(samples, 1.0 if name in FRACTIONS else np.inf)
    below, above = (np.nan_to_num(np.maximum(d, 0.0)) for d in (mean - low, high - mean))
    return mean * scale, np.stack([below, above]) * scale


def _ring(axis, x, y, flagged) -> None:
    """Open rings around the points ``(x, y)`` that ``flagged`` marks: in full contact or with F_el ≥ 10 F_N
    (:func:`~.tables.point_flags`), whose numbers say nothing about the topography."""
    x, y = np.broadcast_to(x, np.shape(flagged)), np.asarray(y)
    axis.plot(x[flagged], y[flagged], "o", ms=13, mfc="none", mec="k", ls="none")


def _figures(result: StudyResult, out, provenance) -> list:
    """The figures of a loads × voltages study: ``equivalent_gap.png``, ``voltage_dependence.png``,
    ``field_ratio.png`` and, where the friction law is computed, ``friction.png``."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    forces, voltages = result.normal_forces, result.voltages
    d_mean, d_bars = _bars(result, "equivalent_gap", MICRO)
    a_mean, a_bars = _bars(result, "ridge_area_fractions", 100.0)
    c_mean, c_bars = _bars(result, "contact_fraction", 100.0)
    gap_mean = result.summary("mean_gap")[0]
    note = bars_note(result)
    flags = point_flags(result)
    flagged = flags["full_contact"] | flags["attraction_dominates"]
    if flagged.any():
        note += "; ringed: full contact or F_el ≥ 10 F_N, the numbers say nothing about the topography (report.md)"
    written = []
    line = np.linspace(forces[0], forces[-1], 50)

    def finish(figure, name):
        figure.text(0.5, 0.005, note, ha="center", va="bottom", fontsize=7, style="italic")
        figure.tight_layout(rect=(0, 0.04, 1, 1))
        written.append(save_figure(figure, out / name, provenance))
        plt.close(figure)

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for j, voltage in enumerate(voltages):
        left.errorbar(forces, d_mean[:, j], yerr=d_bars[:, :, j], marker="o", capsize=3,
                      label=f"Eq. 25, {voltage:g} V")
    left.plot(line, LinearGap.paper_table1()(line, 0.0) * MICRO, "k--", label="seed Eq. 46 (fit, any voltage)")
    guo = PowerLawGap.guo2019()
    span = np.linspace(max(forces[0], 0.5), min(forces[-1], 4.5), 50)     # its measured 0.5-4.5 N, our loads
    if span[0] < span[-1]:
        left.plot(span, guo(span, 0.0) * MICRO, "k:", label="Guo et al. 2019, measured at 150 V")
    left.set(xlabel="normal force F_N [N]", ylabel="equivalent air gap [µm]", title="d_eq vs load")
    left.legend(fontsize=7)
    right.plot(forces, gap_mean[:, 0] * MICRO, "s-", label=f"arithmetic mean gap, {voltages[0]:g} V")
    right.plot(forces, d_mean[:, 0], "o-", label=f"Eq. 25, {voltages[0]:g} V")
    right.set(xlabel="normal force F_N [N]", ylabel="gap [µm]", title="mean gap vs Eq. 25 (realisation means)")
    right.legend(fontsize=7)
    finish(figure, "equivalent_gap.png")

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for i, force in enumerate(forces):
        left.errorbar(voltages, d_mean[i], yerr=d_bars[:, i], marker="o", capsize=3, label=f"{force:g} N")
        right.errorbar(voltages, a_mean[i], yerr=a_bars[:, i], marker="o", capsize=3, color=f"C{i}",
                       label=f"A_R/A0, {force:g} N")
        right.errorbar(voltages, c_mean[i], yerr=c_bars[:, i], marker="s", ls="--", capsize=3, color=f"C{i}",
                       label=f"real contact, {force:g} N")
        _ring(left, voltages, d_mean[i], flagged[i])
    left.set(xlabel="voltage U [V]", ylabel="d_eq (Eq. 25) [µm]", title="voltage dependence of d_eq")
    right.set(xlabel="voltage U [V]", ylabel="fraction of A0 [%]",
              title="ridge (solid) and real (dashed) contact vs voltage")
    left.legend(fontsize=7)
    right.legend(fontsize=6)
    finish(figure, "voltage_dependence.png")

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    field_mean, field_bars = _bars(result, "field_equivalent_gap", MICRO)
    ratio_mean, ratio_bars = _bars(result, "field_ratio")
    for j, voltage in enumerate(voltages):
        colour = f"C{j}"
        left.errorbar(forces, d_mean[:, j], yerr=d_bars[:, :, j], marker="o", capsize=3, color=colour,
                      label=f"Eq. 25, {voltage:g} V")
        left.errorbar(forces, field_mean[:, j], yerr=field_bars[:, :, j], marker="s", capsize=3,
                      ls="--", color=colour, label=f"field-equivalent, {voltage:g} V")
    for i, force in enumerate(forces):
        right.errorbar(voltages, ratio_mean[i], yerr=ratio_bars[:, i], marker="o", capsize=3, label=f"{force:g} N")
    right.axhline(1.0, color="k", lw=0.8)
    left.set(xlabel="normal force F_N [N]", ylabel="gap [µm]", title="Eq. 25 (solid) vs field-equivalent (dashed)")
    right.set(xlabel="voltage U [V]", ylabel="F_el(field) / F_el(Eq. 21 per pixel)",
              title=f"{result.scene.screen.field} field against the per-pixel law")
    left.legend(fontsize=6)
    right.legend(fontsize=7)
    finish(figure, "field_ratio.png")

    if friction_computed(result):
        model, seed = bottom_up_friction(result), SlidingFrictionModel.paper_table1()
        ours = model.state(forces[:, None], voltages[None, :])
        samples = friction_realisations(result)
        fed = np.array([[fe_friction_columns(model, f, u)["bottom_up_fe_friction_coefficient"] for u in voltages]
                        for f in forces])                     # the FE fingertip's reduction at μ_eff (roughcontact.fe)
        figure, axes = plt.subplots(1, 3, figsize=(14, 4))
        for j, voltage in enumerate(voltages):
            theirs = seed.state(line, voltage)
            colour = f"C{j}"
            axes[0].plot(forces, ours.initial_area[:, j] * MM2, "o-", color=colour, label=f"bottom-up {voltage:g} V")
            axes[0].plot(line, theirs.initial_area * MM2, "--", color=colour)
            for axis, name in ((axes[1], "tangential_force"), (axes[2], "friction_coefficient")):
                value = getattr(ours, name)[:, j]
                low, high = positive_interval(samples[name][:, j])
                bars = np.nan_to_num(np.maximum(np.stack([value - low, high - value]), 0.0))
                axis.errorbar(forces, value, yerr=bars, marker="o", capsize=3, color=colour, label=f"{voltage:g} V")
                _ring(axis, forces, value, flagged[:, j])
                axis.plot(line, getattr(theirs, name), "--", color=colour)
            axes[2].plot(forces, fed[:, j], "^:", color=colour, mfc="none")
        axes[0].set(xlabel="F_N [N]", ylabel="ridge area A_R0 [mm²]", title="A_R (solid) vs seed Eq. 9 (dashed)")
        axes[1].set(xlabel="F_N [N]", ylabel="F_T [N]", title="friction force (dashed: seed Table 1)")
        axes[2].set(xlabel="F_N [N]", ylabel="μ = F_T/F_N", title="μ (dashed: seed; dotted △: FE-fed reduction)")
        for axis in axes:
            axis.legend(fontsize=7)
        finish(figure, "friction.png")
    return written


def _sweep_figure(result: StudyResult, out, provenance) -> list:
    """``frequency_sweep.png``: F_el, its paired ratio to the highest frequency's, d_eq and A_R/A0 against
    frequency (log axis) per load, a row per voltage
    above 0 V, DC as a dotted line, the circuit's crossover (:func:`sweep_crossover`) as a dashed line."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    voltages = [j for j, voltage in enumerate(result.voltages) if voltage > 0]
    frequencies = np.array(result.frequencies)
    ac = frequencies > 0
    if not voltages or not ac.any():
        return []
    crossover = sweep_crossover(result)[0]
    samples = sweep_samples(result)
    figure, axes = plt.subplots(len(voltages), 4, figsize=(18, 3.6 * len(voltages)), squeeze=False)
    for row, j in zip(axes, voltages):
        for (label, values), axis in zip(samples.items(), row):
            upper = 100.0 if label.startswith("A_R") else np.inf
            for i, force in enumerate(result.normal_forces):
                mean = confidence_interval(values[i, j])[0]
                low, high = positive_interval(values[i, j], upper)
                bars = np.nan_to_num(np.maximum(np.stack([mean - low, high - mean]), 0.0))
                colour = f"C{i}"
                axis.errorbar(frequencies[ac], mean[ac], yerr=bars[:, ac], marker="o", capsize=3,
                              color=colour, label=f"{force:g} N")
                if not ac.all():
                    axis.axhline(mean[0], color=colour, ls=":", lw=1, label=f"{force:g} N, DC")
                axis.axvline(crossover[i, j], color=colour, ls="--", lw=0.8)
            axis.set(xscale="log", xlabel="drive frequency f [Hz]", ylabel=label,
                     title=f"{label.split(' [')[0]} at {result.voltages[j]:g} V RMS")
            axis.legend(fontsize=6)
    figure.text(0.5, 0.005, "dashed: crossover f_c of the series circuit, h_rest = field-equivalent gap at the "
                "highest frequency + d_i/ε_i; dotted: DC; " + bars_note(result), ha="center", va="bottom",
                fontsize=7, style="italic")
    figure.tight_layout(rect=(0, 0.03, 1, 1))
    written = [save_figure(figure, out / "frequency_sweep.png", provenance)]
    plt.close(figure)
    return written


def write_figures(result: StudyResult, out, provenance) -> list:
    """Write the figures of ``result`` into the directory ``out`` (the sweep's for a frequency sweep); returns
    their paths."""
    return _sweep_figure(result, out, provenance) if result.frequencies else _figures(result, out, provenance)


def write_sensitivity_figure(result, out, provenance) -> list:
    """``sensitivity.png`` of a parameter study (a :class:`VariantStudyResult`) at its report point (F_N, U), one
    panel per output: one at a time, a tornado of the output's relative change at each input's lowest and
    highest level; Morris, μ* against σ; Sobol', S1 and ST with their 95 % intervals."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sensitivity, (force, voltage) = result.sensitivity, result.point
    outputs = [name for name in sensitivity.outputs
               if np.any(np.isfinite(sensitivity.measure(sensitivity.ranked_by, name, force, voltage)))]
    columns = min(max(len(outputs), 1), 3)
    rows = -(-max(len(outputs), 1) // columns)
    figure, axes = plt.subplots(rows, columns, figsize=(4.2 * columns, 3.2 * rows), squeeze=False)
    for axis, output in zip(axes.flat, outputs):
        _sensitivity_panel(axis, sensitivity, output, force, voltage)
    for axis in list(axes.flat)[len(outputs):]:
        axis.set_axis_off()
    if not outputs:
        axes[0, 0].text(0.5, 0.5, "no output varies at this point", ha="center", va="center")
    figure.suptitle(f"sensitivity ({sensitivity.design}) at F_N = {force:g} N, U = {voltage:g} V", fontsize=9)
    figure.tight_layout()
    written = [save_figure(figure, out / "sensitivity.png", provenance)]
    plt.close(figure)
    return written


def _sensitivity_panel(axis, sensitivity, output: str, force: float, voltage: float) -> None:
    """One output's panel of ``sensitivity.png``."""
    symbol = OUTPUTS[output][0]
    names = list(sensitivity.ranking(output, force, voltage))[::-1]           # the largest on top
    order = [sensitivity.inputs.index(name) for name in names]
    rows = np.arange(len(names))

    def values(name):
        return sensitivity.measure(name, output, force, voltage)[order]

    if sensitivity.design == "one-at-a-time":
        axis.barh(rows - 0.2, 100 * values("low"), height=0.4, color="C0", label="lowest level")
        axis.barh(rows + 0.2, 100 * values("high"), height=0.4, color="C3", label="highest level")
        axis.axvline(0.0, color="k", lw=0.8)
        axis.set(xlabel=f"{symbol}: change from the baseline [%]")
    elif sensitivity.design == "morris":
        axis.errorbar(values("mu_star"), values("sigma"), xerr=values("mu_star_conf"), fmt="o", capsize=3)
        for name, x, y in zip(names, values("mu_star"), values("sigma")):
            axis.annotate(name, (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points")
        axis.set(xlabel=f"μ* of {symbol}", ylabel="σ")
        return
    else:
        axis.barh(rows - 0.2, values("S1"), height=0.4, xerr=values("S1_conf"), color="C0", label="S1")
        axis.barh(rows + 0.2, values("ST"), height=0.4, xerr=values("ST_conf"), color="C3", label="ST")
        axis.set(xlabel=f"Sobol' index of {symbol}")
    axis.set_yticks(rows, names, fontsize=7)
    axis.legend(fontsize=6)
