"""Results on disk: savable result dataclasses (``.npz`` with their parameters) and the provenance line of every
file the library writes. Layer 1: imports nothing of roughcontact above it."""
from __future__ import annotations

from .provenance import (OutputPathError, Provenance, output_directory, parse_arguments, read_csv, save_figure,
                         write_atomic, write_columns, write_csv)
from .results import ConvergenceWarning, SavableResult, savable_field

__all__ = ["ConvergenceWarning", "OutputPathError", "Provenance", "SavableResult", "output_directory",
           "parse_arguments", "read_csv", "savable_field", "save_figure", "write_atomic", "write_columns", "write_csv"]
