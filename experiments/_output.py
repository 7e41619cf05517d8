"""The experiment scripts' outputs: one CSV writer with one echo format, and one line-plot writer."""
from __future__ import annotations

import csv


def write_csv(path, rows, columns=None, echo=False):
    """Write ``rows`` (dicts) to the CSV file ``path`` with ``columns`` as header (default: the first row's keys;
    keys outside ``columns`` are ignored, missing ones left empty); ``echo`` also prints each row as
    ``key=value, …``."""
    rows = list(rows)
    with open(path, "w", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=columns or list(rows[0]), extrasaction="ignore", restval="")
        writer.writeheader()
        writer.writerows(rows)
    if echo:
        for row in rows:
            print(", ".join(f"{key}={value:.4g}" if isinstance(value, float) else f"{key}={value}"
                            for key, value in row.items()))


def save_semilogy(path, curves, *, xlabel, ylabel, title, marker=None):
    """PNG at ``path`` of ``curves`` ({label: (x, y)}) on a logarithmic y axis, one legend entry each."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(5, 3.5))
    for label, (x, y) in curves.items():
        axes.semilogy(x, y, marker=marker, label=label)
    axes.set(xlabel=xlabel, ylabel=ylabel, title=title)
    axes.legend()
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)
