"""The experiment scripts' result tables: one CSV writer and one echo format for all of them."""
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
