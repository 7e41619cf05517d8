"""Output files that say where they came from: the one writer of ``roughcontact figures``, ``roughcontact run``
and the scripts in ``studies/``.

Every CSV written here starts with one comment line, and every PNG carries the same line in its metadata
(PNG text chunks ``Comment`` and ``Software``)::

    # roughcontact 0.1.0, 2026-01-31T12:00:00+00:00, command: roughcontact figures --output out, parameters: {...}

Absolute paths in the command and the parameters are recorded relative to the working directory, or by their
name where they lie outside it (:func:`portable`): a file made on one machine does not carry its directories.

Readers skip it: ``pandas.read_csv(path, comment="#")``, ``numpy.loadtxt(path, delimiter=",", skiprows=2)``
(numpy counts the comment among the skipped lines; comment lines after it are skipped anyway), or
:func:`read_csv` here. ``PIL.Image.open(path).text["Comment"]`` returns a PNG's line.

:func:`output_directory` validates an output directory before anything is computed: it creates only the
last level of the path (a missing parent is a typo more often than a wish) and raises
:class:`OutputPathError`, a ``ValueError`` with a one-line message, for a path that cannot hold the outputs.
"""
from __future__ import annotations

import csv
import json
import os
import shlex
import sys
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path

from .._version import __version__

#: Resolution of the PNG figures [dots per inch].
FIGURE_DPI = 120


class OutputPathError(ValueError):
    """An output path that cannot hold the outputs (a file, a missing parent, no write permission)."""


def _now() -> str:
    return datetime.now(timezone.utc).isoformat(timespec="seconds")


@dataclass(frozen=True)
class Provenance:
    """Library version, date (UTC, ISO 8601), command line and parameters of one run."""

    command: str
    parameters: dict
    version: str = __version__
    date: str = field(default_factory=_now)

    def __post_init__(self):
        object.__setattr__(self, "parameters", portable(dict(self.parameters)))

    @classmethod
    def of_command(cls, program: str, argv, parameters: dict) -> Provenance:
        """The provenance of ``program`` (a command line, e.g. ``python studies/x.py``) run with the
        arguments ``argv`` (a list, shell-quoted here); absolute paths in them are recorded by :func:`portable`."""
        return cls(command=" ".join([program, shlex.join(map(str, portable(list(argv))))]).strip(),
                   parameters=dict(parameters))

    @property
    def line(self) -> str:
        """``roughcontact <version>, <date>, command: <command>, parameters: <JSON>`` (no comment sign)."""
        parameters = json.dumps(self.parameters, default=str, ensure_ascii=False)
        return f"roughcontact {self.version}, {self.date}, command: {self.command}, parameters: {parameters}"

    @property
    def png_metadata(self) -> dict:
        """PNG text chunks for matplotlib's ``savefig(..., metadata=...)``."""
        return {"Software": f"roughcontact {self.version}", "Comment": self.line}


def portable(value):
    """``value`` with its absolute paths made independent of the machine: one under the working directory
    relative to it, any other by its last component alone (where a machine keeps its outputs is no part of their
    provenance, and a shipped file should not carry it). Applies to strings and ``os.PathLike`` (an option's
    ``--name=path`` form included), and item by item to lists, tuples and dicts; anything else is returned as
    it is."""
    if isinstance(value, dict):
        return {key: portable(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return type(value)(portable(item) for item in value)
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if not isinstance(value, str):
        return value
    option, equals, path = value.partition("=") if value.startswith("-") else ("", "", value)
    if not os.path.isabs(path):
        return value
    path = Path(os.path.normpath(path))
    try:
        relative = str(path.relative_to(Path.cwd()))
    except ValueError:
        relative = path.name or str(path)
    return option + equals + relative


def parse_arguments(parser, argv, program: str) -> tuple:
    """``(args, provenance)``: ``parser``'s arguments from ``argv`` (default: the command line) and the
    provenance of running ``program`` with them (the parameters: the parsed arguments, callables left out)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    args = parser.parse_args(argv)
    parameters = {key: value for key, value in vars(args).items() if not callable(value)}
    return args, Provenance.of_command(program, argv, parameters)


def output_directory(path, name: str = "output") -> Path:
    """``path`` as a writable directory, created if missing (only its last level). Raises
    :class:`OutputPathError` for an empty path, a file, a missing parent or a directory without write access,
    naming the directory by ``name`` (the parameter or flag it came from, e.g. "tasks" or "--tasks")."""
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"the {name} path must be a str or os.PathLike, got {type(path).__name__}")
    if not str(path).strip():
        raise OutputPathError(f"the {name} path is empty")
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise OutputPathError(f"{name} path {path} is a file, not a directory")
    if not path.exists():
        if path.parent.exists() and not path.parent.is_dir():
            raise OutputPathError(f"the parent of the {name} directory, {path.parent}, is a file, not a directory")
        if not path.parent.is_dir():
            raise OutputPathError(f"the parent of the {name} directory, {path.parent}, does not exist "
                                  "(only the last level of the path is created)")
        try:
            path.mkdir()
        except OSError as error:
            raise OutputPathError(f"cannot create the {name} directory {path}: {error.strerror}") from None
    if not os.access(path, os.W_OK | os.X_OK):
        raise OutputPathError(f"the {name} directory {path} is not writable")
    return path


def write_csv(path, rows, provenance: Provenance | None, columns=None, echo=False) -> Path:
    """Write ``rows`` (dicts) to the CSV file ``path`` after the provenance comment, with ``columns`` as header
    (default: the first row's keys; other keys are ignored, missing ones left empty); ``echo`` also prints
    each row as ``key=value, …``. ``provenance=None`` writes no comment line, for a reader that cannot skip one."""
    rows = list(rows)
    with open(path, "w", newline="", encoding="utf-8") as stream:
        if provenance is not None:
            stream.write(f"# {provenance.line}\n")
        writer = csv.DictWriter(stream, fieldnames=columns or list(rows[0]), extrasaction="ignore", restval="")
        writer.writeheader()
        writer.writerows(rows)
    if echo:
        for row in rows:
            print(", ".join(f"{key}={value:.4g}" if isinstance(value, float) else f"{key}={value}"
                            for key, value in row.items()))
    return Path(path)


def write_atomic(path, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` through a sibling ``.part`` file, synced to disk and renamed over it
    (the directory synced after): a reader, or a run resumed after a crash or a power cut, sees the old file or
    the whole new one, never a half-written or empty one."""
    path = Path(path)
    temporary = path.with_name(path.name + ".part")
    with open(temporary, "w", encoding="utf-8") as stream:
        stream.write(text)
        stream.flush()
        os.fsync(stream.fileno())
    os.replace(temporary, path)
    if hasattr(os, "O_DIRECTORY"):                   # (POSIX: the rename itself reaches the disk)
        directory = os.open(path.parent, os.O_RDONLY | os.O_DIRECTORY)
        try:
            os.fsync(directory)
        finally:
            os.close(directory)
    return path


def write_columns(path, header, columns, provenance: Provenance) -> Path:
    """Write equal-length numeric ``columns`` under the names ``header`` to the CSV file ``path`` (full
    precision), after the provenance comment."""
    import numpy as np

    np.savetxt(path, np.column_stack(columns), delimiter=",", comments="",
               header=f"# {provenance.line}\n{','.join(header)}")
    return Path(path)


def read_csv(path) -> list:
    """The rows of a CSV file written here, as dicts of strings (comment lines skipped)."""
    try:
        with open(path, newline="", encoding="utf-8") as stream:
            return list(csv.DictReader(line for line in stream if not line.startswith("#")))
    except UnicodeDecodeError as error:
        raise ValueError(f"{path} is not UTF-8 text (byte {error.start}); the CSV files written here are") from None


def save_figure(figure, path, provenance: Provenance, dpi=FIGURE_DPI, colors=None) -> Path:
    """Save the matplotlib ``figure`` as a PNG at ``path`` with the provenance in its metadata; ``colors``:
    quantise to a palette of that many colours (small files for the docs)."""
    if colors is None:
        figure.savefig(path, dpi=dpi, metadata=provenance.png_metadata)
        return Path(path)
    import io

    from PIL import Image, PngImagePlugin

    buffer = io.BytesIO()
    figure.savefig(buffer, dpi=dpi, format="png")
    buffer.seek(0)
    text = PngImagePlugin.PngInfo()
    for key, value in provenance.png_metadata.items():
        text.add_text(key, value)
    with Image.open(buffer) as image:
        image.convert("RGB").quantize(colors=colors).save(path, optimize=True, pnginfo=text)
    return Path(path)
