"""Gallery of synthetic surfaces: the five fingerprint classes and self-affine roughness at several Hurst
exponents, each with its PSD (PNG), plus their measured statistics (CSV).

    python studies/surface_gallery.py [--fast] [--output DIR]   # after pip install -e .

Writes ``fingerprint_classes.png`` (height maps with cores ● and deltas ▲, and PSDs with the requested
ridge wavenumber), ``fingerprint_detail.png`` (a 3 mm zoom: minutiae, pores, a cross-section),
``roughness_hurst.png`` (maps and PSDs against the slope −2(1+H)) and ``gallery_statistics.csv``. Full mode:
20 mm fingerprints at 1024², 1 mm roughness at 512² (≈ 20 s); ``--fast``: 10 mm at 256², 128² (≈ 3 s).
The pictures in ``docs/img`` are the full-mode output (``--output docs/img``); every PNG carries its
provenance in its metadata.
"""
from __future__ import annotations

import argparse

import numpy as np

import surfaces
from roughcontact.io import output_directory, parse_arguments, save_figure, write_csv
from surfaces.plotting import plot_map, plot_profile, plot_psd
from surfaces.ridges import PATTERNS, PORE_DENSITY, RIDGE_PERIOD

HURST_EXPONENTS = (0.3, 0.5, 0.8)
SHORT_CUTOFF_PIXELS = 4         # short-wavelength cutoff of the roughness, in pixels
_MM = 1e3
#: PNG palette size and resolution of the gallery pictures (they go into docs/img: < 200 kB each).
PALETTE_COLOURS, GALLERY_DPI = 128, 80


def fingerprint_fields(n: int, length: float, rng: int = 1) -> dict:
    grid = surfaces.Grid((n, n), (length, length), periodic=False)
    return {pattern: surfaces.fingerprint(grid, pattern, rng=rng) for pattern in PATTERNS}


def roughness_fields(n: int, length: float, rng: int = 2) -> dict:
    """Self-affine fields (rms height 1 µm, short cutoff 4 pixels), one per Hurst exponent."""
    grid = surfaces.Grid((n, n), (length, length), periodic=True)
    return {hurst: surfaces.self_affine(grid, hurst=hurst, rms_height=1e-6,
                                        short_cutoff=SHORT_CUTOFF_PIXELS * length / n, rng=rng)
            for hurst in HURST_EXPONENTS}


def save_small(fig, path, provenance):
    """Save ``fig`` as a small palette PNG with its provenance, and close it."""
    import matplotlib.pyplot as plt
    save_figure(fig, path, provenance, dpi=GALLERY_DPI, colors=PALETTE_COLOURS)
    plt.close(fig)


def draw_fingerprints(prints: dict, path, provenance):
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, len(prints), figsize=(3.1 * len(prints), 6.0), constrained_layout=True)
    for column, (pattern, field) in enumerate(prints.items()):
        ax = axes[0, column]
        plot_map(field, ax=ax, cmap="gray", colorbar=False)
        for points, marker, colour in ((field.metadata["cores"], "o", "tab:red"),
                                       (field.metadata["deltas"], "^", "tab:blue")):
            for x, y in points:
                ax.plot(x * _MM, y * _MM, marker, color=colour, ms=6, mec="white")
        ax.set_xlim(0, field.grid.lengths[0] * _MM)
        ax.set_ylim(0, field.grid.lengths[1] * _MM)
        ax.set_title(pattern.replace("_", " "))
        ax = axes[1, column]
        plot_psd(field, ax=ax, color="k", lw=0.8)
        ax.axvline(2 * np.pi / RIDGE_PERIOD, color="tab:red", lw=0.8, ls="--", label="2π / ridge_period")
        measured = surfaces.dominant_wavelength(field)
        ax.set_title(f"dominant λ = {measured * _MM:.3f} mm", fontsize=9)
        ax.set_xlim(1e3, 1e6)
        if column == 0:
            ax.legend(fontsize=8, loc="lower left")
    save_small(fig, path, provenance)


def draw_detail(field, path, provenance, zoom: float = 3e-3):
    """A ``zoom`` × ``zoom`` corner of a print at full resolution, its detected pores, and a cross-section."""
    import matplotlib.pyplot as plt
    grid = field.grid
    n = int(round(zoom / grid.spacing[0]))
    i0, j0 = (grid.shape[0] - n) // 2, (grid.shape[1] - n) // 2 - n
    crop = surfaces.HeightField.from_array(field.heights[i0:i0 + n, j0:j0 + n], (n * grid.spacing[0],) * 2)
    pores = surfaces.detect_pores(crop)
    fig, (left, right) = plt.subplots(1, 2, figsize=(9.5, 4.0), constrained_layout=True,
                                      gridspec_kw={"width_ratios": (1.0, 1.2), "wspace": 0.1})
    plot_map(crop, ax=left, cmap="gray")
    left.plot(pores.centres[:, 0] * _MM, pores.centres[:, 1] * _MM, "o", mfc="none", mec="tab:orange", ms=7)
    left.axhline(crop.grid.lengths[1] / 2 * _MM, color="tab:blue", lw=0.8)
    left.set_title(f"{field.metadata['pattern']}: {pores.count} pores found ({pores.density / 1e4:.0f} cm⁻²)")
    plot_profile(crop, ax=right, axis=0, color="tab:blue")
    right.set_title("cross-section along the blue line")
    save_small(fig, path, provenance)


def draw_roughness(rough: dict, path, provenance):
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(rough) + 1, figsize=(3.3 * (len(rough) + 1), 3.4), constrained_layout=True)
    for ax, (hurst, field) in zip(axes, rough.items()):
        plot_map(field, ax=ax, cmap="viridis", colorbar=False)
        ax.set_title(f"H = {hurst}")
    ax = axes[-1]
    q_short = 2 * np.pi / (SHORT_CUTOFF_PIXELS * next(iter(rough.values())).grid.spacing[0])
    floor = np.inf
    for hurst, field in rough.items():
        line = plot_psd(field, ax=ax, lw=0.8, label=f"H = {hurst}")
        q, spectrum = surfaces.psd(field)
        band = q < 0.95 * q_short
        slope = -2 * (1 + hurst)                    # reference power law through the band (log-mean prefactor)
        prefactor = np.exp(np.mean(np.log(spectrum[band]) - slope * np.log(q[band])))
        ax.loglog(q[band], prefactor * q[band] ** slope, ls=":", color=line.get_color())
        floor = min(floor, spectrum[band].min())
    ax.set_xlim(right=q_short)                      # beyond the cutoff there is only round-off
    ax.set_ylim(bottom=0.1 * floor)
    ax.set_title("PSD, dotted: q^−2(1+H)")
    ax.legend(fontsize=8)
    save_small(fig, path, provenance)


def statistics_rows(prints: dict, rough: dict) -> list:
    def measured(label, field, **extra):
        return {"field": label, "window_mm": field.grid.lengths[0] * _MM, "pixels": field.grid.shape[0],
                "rms_height_um": surfaces.rms_height(field) * 1e6, "rms_slope": surfaces.rms_slope(field), **extra}

    return ([measured(f"fingerprint {pattern}", field,
                      dominant_wavelength_mm=surfaces.dominant_wavelength(field) * _MM,
                      requested_period_mm=RIDGE_PERIOD * _MM,
                      pore_density_cm2=surfaces.detect_pores(field).density / 1e4,
                      requested_pore_density_cm2=PORE_DENSITY / 1e4) for pattern, field in prints.items()]
            + [measured(f"self_affine H={hurst}", field) for hurst, field in rough.items()])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="small grids (seconds)")
    parser.add_argument("--output", default="out", help="output directory (its parent must exist)")
    args, provenance = parse_arguments(parser, argv, "python studies/surface_gallery.py")
    output = output_directory(args.output)
    import matplotlib
    matplotlib.use("Agg")
    prints = fingerprint_fields(256, 10e-3) if args.fast else fingerprint_fields(1024, 20e-3)
    rough = roughness_fields(128, 1e-3) if args.fast else roughness_fields(512, 1e-3)
    draw_fingerprints(prints, output / "fingerprint_classes.png", provenance)
    draw_detail(prints["whorl"], output / "fingerprint_detail.png", provenance)
    draw_roughness(rough, output / "roughness_hurst.png", provenance)
    rows = statistics_rows(prints, rough)
    write_csv(output / "gallery_statistics.csv", rows, provenance, echo=True)
    print(f"written to {output}/")
    return rows


if __name__ == "__main__":
    main()
