"""The files of a phyphox export beside the gyroscope's: the START/PAUSE events
(``meta/time.csv``), the raw accelerometer (``Accelerometer.csv``), and which CSV holds the
gyroscope's data.

phyphox is the free phone app of RWTH Aachen (https://phyphox.org); its "CSV" export of an
experiment is a folder or a zip of one CSV per sensor and ``meta/``.
"""

from __future__ import annotations

import os

import numpy as np

from ..analysis.fit.freefall import MAX_ACCEL
from ._delimited import _NUMBER, _check_order, _first_lines, _refuse_cell, _rows, _separator, _split
from .gyrocolumns import match_accel

__all__ = ["ACCEL_CSV", "ACCEL_SPAN_SLACK", "TIME_CSV", "accel_gap", "parse_accel_csv", "parse_time_csv"]


#: phyphox's raw accelerometer in an export with several sensors, beside ``Gyroscope.csv``.
ACCEL_CSV = "Accelerometer.csv"
#: How far a gyroscope sample may lie from the nearest accelerometer sample, s: the sensors of
#: one phyphox experiment start within tens of milliseconds of each other and sample at tens to
#: hundreds of Hz; beyond this, an interpolated or held value would stand in for samples that
#: were never taken (a late start, an early end, samples dropped in between).
ACCEL_SPAN_SLACK = 0.1


def parse_accel_csv(raw: bytes, label: str, t: np.ndarray) -> tuple[np.ndarray, tuple, tuple, np.ndarray]:
    """phyphox's ``Accelerometer.csv`` (experiment "Acceleration (with g)": ``"Time (s)"``,
    ``"Acceleration x (m/s^2)"``, ...), interpolated linearly onto the gyroscope's times ``t``
    (``numpy.interp`` per axis; held at its first and last value just outside its own span): the
    specific force, m/s^2, sensor axes; its columns' names and units; and its own sample times,
    s (:func:`accel_gap` tells whether they cover the gyroscope's).

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.io.phyphox import parse_accel_csv
    >>> raw = b'"Time (s)","Acceleration x (m/s^2)","Acceleration y (m/s^2)","Acceleration z (m/s^2)"\\n0,0,0,9.8\\n0.02,0,0,0\\n'
    >>> f, names, units, times = parse_accel_csv(raw, "Accelerometer.csv", np.array([0.0, 0.01, 0.02]))
    >>> f[:, 2].round(6).tolist(), names[0], units, times.tolist()
    ([9.8, 4.9, 0.0], 'Accelerometer.csv: Acceleration x (m/s^2)', ('m/s^2', 'm/s^2', 'm/s^2'), [0.0, 0.02])
    """
    lines, sep, head = _first_lines(raw, label, "phyphox's accelerometer export: Time (s), Acceleration x, y, z")
    times = [j for j, cell in enumerate(head) if cell.lower() in ("time (s)", "t (s)", "time", "t")]
    columns, scale, units = match_accel(head, times[:1], label, lines[0][0])
    if len(times) != 1 or not columns:
        raise ValueError(f"{label}, line {lines[0][0]}: expected the columns \"Time (s)\", \"Acceleration x (m/s^2)\", "
                         f"\"Acceleration y (m/s^2)\", \"Acceleration z (m/s^2)\" (phyphox's raw accelerometer)")
    rows = _rows(lines[1:], sep, [times[0], *columns], len(head), label) * np.array([1.0, *scale])
    if len(rows) < 2:
        raise ValueError(f"{label}: {len(rows)} data rows; an accelerometer record needs many samples")
    _check_values(rows, lines[1:], head, [times[0], *columns], label)
    _check_order(rows[:, 0], lines[1:], label)
    f = np.stack([np.interp(t, rows[:, 0], rows[:, k]) for k in (1, 2, 3)], axis=1)
    base = os.path.basename(label)
    return f, tuple(f"{base}: {head[j]}" for j in columns), tuple(units), rows[:, 0].copy()


def _check_values(rows: np.ndarray, lines: list, head: list, columns: list, label: str) -> None:
    """Refuse, in one line naming the file, the line and the column, a time or a specific force
    that is not finite, a time beyond ``MAX_TIME`` or a force beyond :data:`MAX_ACCEL`, as the
    gyroscope's reader refuses them (:func:`tumble.analysis.fit.single.fit_rotation`): one such cell
    would be interpolated over half the record."""
    from ..analysis.fit.single import MAX_TIME

    limit = np.r_[MAX_TIME, np.full(rows.shape[1] - 1, MAX_ACCEL)]

    def rule(k: int, j: int) -> str:
        what, unit = ("a time", "s") if j == 0 else ("an accelerometer's reading", "m/s^2")
        return "is not a finite number" if not np.isfinite(rows[k, j]) else f"is beyond {what} (at most {limit[j]:.0e} {unit})"

    _refuse_cell(~np.isfinite(rows) | (np.abs(rows) > limit), rows, lines, columns, [head[c] for c in columns], label, rule)


def accel_gap(times: np.ndarray, t: np.ndarray, label: str) -> str:
    """Why an accelerometer sampled at ``times`` (s, ascending) cannot stand for the gyroscope's
    record at the times ``t``: a gyroscope sample farther than :data:`ACCEL_SPAN_SLACK` from every
    accelerometer sample (a late start, an early end, a gap between); ``""`` when there is none.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.io.phyphox import accel_gap
    >>> t = np.linspace(0.0, 10.0, 1001)
    >>> accel_gap(np.arange(0.03, 9.99, 0.02), t, "Accelerometer.csv")   # within the slack: used
    ''
    >>> accel_gap(np.arange(2.0, 10.01, 0.02), t, "Accelerometer.csv")   # starts 2 s late
    "Accelerometer.csv has no sample within 0.1 s of the gyroscope's at 0 s (its samples: 2 to 10 s, 401 of them): not used; the flights are found from the gyroscope alone"
    >>> dropped = np.r_[np.arange(0.0, 4.0, 0.02), np.arange(4.5, 10.01, 0.02)]   # half a second dropped
    >>> accel_gap(dropped, t, "Accelerometer.csv")   # the gyroscope's sample farthest from any
    "Accelerometer.csv has no sample within 0.1 s of the gyroscope's at 4.24 s (its samples: 0 to 10 s, 476 of them): not used; the flights are found from the gyroscope alone"
    """
    k = np.clip(np.searchsorted(times, t), 1, len(times) - 1)
    distance = np.minimum(np.abs(t - times[k - 1]), np.abs(times[k] - t))
    worst = int(np.argmax(distance))
    if distance[worst] <= ACCEL_SPAN_SLACK:
        return ""
    return (f"{os.path.basename(label)} has no sample within {ACCEL_SPAN_SLACK:g} s of the gyroscope's at "
            f"{t[worst]:.6g} s (its samples: {times[0]:.6g} to {times[-1]:.6g} s, {len(times)} of them): not used; "
            "the flights are found from the gyroscope alone")


#: The phyphox export's file of START/PAUSE events, inside the folder or the zip.
TIME_CSV = "meta/time.csv"


def parse_time_csv(raw: bytes, label: str) -> list[tuple[str, float]]:
    """phyphox's ``meta/time.csv``: ``[(event, experiment time in s), ...]``.

    Its header is ``"event","experiment time","system time","system time text"``; the events
    are ``START`` and ``PAUSE`` (after a pause the experiment time carries on from the pause).

    Examples
    --------
    >>> from tumble.io.phyphox import parse_time_csv
    >>> raw = b'"event","experiment time","system time","system time text"\\nSTART,0.0,1.7e9,a\\nPAUSE,12.5,1.7e9,b\\n'
    >>> parse_time_csv(raw, "meta/time.csv")
    [('START', 0.0), ('PAUSE', 12.5)]
    """
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise ValueError(f"{label}: not a text file (UTF-8): byte {err.start} cannot be decoded") from None
    lines = [(i + 1, line) for i, line in enumerate(text.splitlines()) if line.strip()]
    if not lines:
        return []
    sep = _separator(lines[0][1]) or ","
    head = [h.lower() for h in _split(lines[0][1], sep)]
    if "event" not in head or "experiment time" not in head:
        raise ValueError(f"{label}, line {lines[0][0]}: expected the columns \"event\" and \"experiment time\" "
                         "(phyphox's meta/time.csv)")
    ie, it = head.index("event"), head.index("experiment time")
    events = []
    for no, line in lines[1:]:
        cells = _split(line, sep)
        if len(cells) <= max(ie, it):
            raise ValueError(f"{label}, line {no}: {len(cells)} columns; expected {len(head)}")
        name, value = cells[ie].upper(), cells[it]
        if name not in ("START", "PAUSE"):
            raise ValueError(f"{label}, line {no}: event {cells[ie][:20]!r}; expected START or PAUSE")
        if not _NUMBER.match(value):
            raise ValueError(f"{label}, line {no}: experiment time {value[:40]!r} is not a number")
        events.append((name, float(value.replace(",", ".") if sep == ";" else value)))
    return events


def _pick_csv(names, label) -> str:
    """The gyroscope CSV of a phyphox export: ``Raw Data.csv``, else the only CSV at the top."""
    top = [n for n in names if n.lower().endswith(".csv") and "/" not in n.strip("/")]
    for n in top:
        if n.lower() in ("raw data.csv", "gyroscope.csv"):
            return n
    if len(top) == 1:
        return top[0]
    raise ValueError(f"{label}: a phyphox export holds \"Raw Data.csv\" (the gyroscope's data) at its top; found "
                     f"{len(top)} CSV files ({', '.join(sorted(top)[:4]) or 'none'})")
