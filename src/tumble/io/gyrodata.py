"""Gyroscope records in: a phone's phyphox export or a plain ``t, wx, wy, wz`` CSV; and the
``tumble fit`` command (fit the record, write ``fit.json`` and optionally ``fit.png``).

Formats read by :func:`read_gyro_csv`:

- **phyphox** (the free phone app of RWTH Aachen, experiment "Gyroscope (rotation rate)",
  export "CSV"): a header line naming the columns ``"Time (s)"``, ``"Gyroscope x (rad/s)"``,
  ``"Gyroscope y (rad/s)"``, ``"Gyroscope z (rad/s)"`` (the names of phyphox's experiment
  definition, ``<set name="Gyroscope">``; quoted or not, any letter case; further columns such as
  ``"Absolute (rad/s)"`` are ignored). The three CSV flavours phyphox offers are accepted:
  comma-separated, tab-separated, and semicolon-separated with a decimal comma.
- **plain**: four numeric columns ``t (s), wx, wy, wz (rad/s)``, with or without one header
  line, separated by commas, semicolons, tabs or spaces.

Lines starting with ``#`` and blank lines are skipped. Every error is one line naming the file
and the line: a missing column, a value that is not a number, a row of the wrong length, fewer
than two rows. The checks of the data themselves (finite, increasing times, enough samples)
are :func:`tumble.analysis.fit.fit_rotation`'s, reported with the file's name.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

import numpy as np

from ..analysis.fit import fit_rotation
from ..mass._checks import read_input_file
from .output import FIGURE_DPI, check_output_dir, output_dir
from .provenance import file_sha256, provenance

__all__ = ["MAX_GYRO_FILE_BYTES", "read_gyro_csv", "run_fit_command"]

#: The largest gyroscope file read, bytes (a day at 100 Hz is about 35 MB of text).
MAX_GYRO_FILE_BYTES = 64 << 20

_PHYPHOX = ("time (s)", "gyroscope x (rad/s)", "gyroscope y (rad/s)", "gyroscope z (rad/s)")
_NUMBER = re.compile(r"^[+-]?(\d+([.,]\d*)?|[.,]\d+)([eE][+-]?\d+)?$|^[+-]?(nan|inf|infinity)$", re.IGNORECASE)


def _split(line: str, sep: str | None) -> list[str]:
    cells = line.split(sep) if sep else line.split()
    return [c.strip().strip('"').strip("'").strip() for c in cells]


def _separator(line: str) -> str | None:
    for sep in ("\t", ";", ","):
        if sep in line:
            return sep
    return None


def read_gyro_csv(path) -> tuple[np.ndarray, np.ndarray]:
    """Read a gyroscope record: times and angular velocity along the sensor's axes.

    Parameters
    ----------
    path : str or Path
        A phyphox CSV export or a plain ``t, wx, wy, wz`` CSV (module docstring).

    Returns
    -------
    t : ndarray, shape (n,)
        Times, s.
    omega : ndarray, shape (n, 3)
        Angular velocity, sensor axes, rad/s.

    Raises
    ------
    ValueError
        One line naming the file (and the line): not a readable regular file, larger than
        :data:`MAX_GYRO_FILE_BYTES`, not text, a missing column, a value that is not a number.
    """
    label = os.fspath(path)
    raw = read_input_file(path, limit=MAX_GYRO_FILE_BYTES, what="a gyroscope record (CSV)")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise ValueError(f"{label}: not a text file (UTF-8): byte {err.start} cannot be decoded") from None
    lines = [(i + 1, line) for i, line in enumerate(text.splitlines())
             if line.strip() and not line.lstrip().startswith("#")]
    if not lines:
        raise ValueError(f"{label}: no data; expected a phyphox gyroscope export or columns t, wx, wy, wz")
    first_no, first = lines[0]
    sep = _separator(first)
    decimal_comma = sep == ";"
    head = _split(first, sep)
    columns = [0, 1, 2, 3]
    width = 4
    if not all(_NUMBER.match(c) for c in head):  # a header line
        names = [h.lower() for h in head]
        if "time (s)" in names or any(n.startswith("gyroscope") for n in names):
            missing = [n for n in _PHYPHOX if n not in names]
            if missing:
                raise ValueError(f"{label}, line {first_no}: a phyphox header without the column \"{missing[0]}\"; "
                                 f"expected \"Time (s)\", \"Gyroscope x (rad/s)\", \"Gyroscope y (rad/s)\", "
                                 f"\"Gyroscope z (rad/s)\"")
            columns = [names.index(n) for n in _PHYPHOX]
            width = len(head)
        elif len(head) != 4:
            raise ValueError(f"{label}, line {first_no}: a header of {len(head)} columns; expected 4 (t, wx, wy, wz) "
                             "or a phyphox gyroscope export")
        lines = lines[1:]
    elif len(head) != 4:
        raise ValueError(f"{label}, line {first_no}: {len(head)} columns; expected 4 (t, wx, wy, wz)")
    rows = np.empty((len(lines), 4))
    for k, (no, line) in enumerate(lines):
        cells = _split(line, sep)
        if len(cells) != width:
            raise ValueError(f"{label}, line {no}: {len(cells)} columns; expected {width}")
        for j, c in enumerate(columns):
            cell = cells[c]
            if not _NUMBER.match(cell):
                raise ValueError(f"{label}, line {no}, column {c + 1}: {cell[:40]!r} is not a number")
            rows[k, j] = float(cell.replace(",", ".") if decimal_comma else cell)
    if len(rows) < 2:
        raise ValueError(f"{label}: {len(rows)} data rows; a record needs many samples")
    return rows[:, 0].copy(), rows[:, 1:].copy()


def run_fit_command(path, out, *, argv=None, figure=None, start: float | None = None, end: float | None = None,
                    **options) -> int:
    """``tumble fit DATA.csv --out DIR``: fit a gyroscope record and write the result.

    Writes ``DIR/fit.json`` (the fitted values and uncertainties of
    :meth:`tumble.analysis.fit.RotationFit.summary`, the input file and the provenance) and,
    when ``figure`` is given, ``DIR/fit.png``, all or nothing (:func:`tumble.io.output.output_dir`);
    prints one line.

    Parameters
    ----------
    path : str or Path
        The gyroscope record (:func:`read_gyro_csv`).
    out : str or Path
        The output folder.
    argv : list of str, optional
        The command line after ``tumble``, for the provenance.
    figure : callable, optional
        ``figure(fit, omega_measured)`` returning the figure (a matplotlib Figure:
        :func:`tumble.viz.figure_fit`; io cannot import viz), saved as ``fit.png``.
    start, end : float, optional
        Fit only the samples with ``start <= t <= end``, s (the free flight of a toss: the
        record of a phone thrown and caught holds the throw and the catch too).
    **options
        Passed to :func:`tumble.analysis.fit.fit_rotation` (``sensor_rotation``, ``bias``).

    Returns
    -------
    int
        0 on success (errors raise ``ValueError`` with one line).
    """
    check_output_dir(out)
    t, omega = read_gyro_csv(path)
    if start is not None or end is not None:
        lo = -np.inf if start is None else float(start)
        hi = np.inf if end is None else float(end)
        if not lo < hi:
            raise ValueError(f"--start {start} must be before --end {end} (s)")
        keep = (t >= lo) & (t <= hi)
        t, omega = t[keep], omega[keep]
    digest = file_sha256(path)
    try:
        fit = fit_rotation(t, omega, **options)
    except ValueError as err:
        raise ValueError(f"{os.fspath(path)}: {err}") from None
    record = {"input": os.fspath(path), "start": start, "end": end, **fit.summary(),
              "method": "least squares on the exact torque-free solution (Landau & Lifshitz sec. 37), "
                        "uncertainties sqrt(diag((J^T J)^-1) s^2) (Numerical Recipes sec. 15.5)",
              "provenance": provenance(argv, [(path, digest)])}
    owns = ("fit.json", "fit.png")
    with output_dir(out, owns=owns) as stage:
        (Path(stage) / "fit.json").write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")
        if figure is not None:  # drawn by the caller's layer, written here into the staged folder
            figure(fit, omega).savefig(Path(stage) / "fit.png", dpi=FIGURE_DPI)
    written = "fit.json" + (" and fit.png" if figure is not None else "")
    print(f"fit {os.fspath(path)}: I1/I3 = {fit.ratios[0]:.5f} +- {fit.ratios_std[0]:.1g}, "
          f"I2/I3 = {fit.ratios[1]:.5f} +- {fit.ratios_std[1]:.1g}, residual {fit.residual_rms:.3g} rad/s "
          f"({fit.samples} samples); wrote {written} in {os.fspath(out)}")
    return 0
