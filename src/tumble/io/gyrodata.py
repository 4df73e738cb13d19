"""Gyroscope records in: a phone's phyphox export or a plain ``t, wx, wy, wz`` CSV.

Formats read by :func:`read_gyro_csv`:

- **phyphox** (the free phone app of RWTH Aachen, experiment "Gyroscope (rotation rate)",
  export "CSV"): a header line naming the columns ``"Time (s)"``, ``"Gyroscope x (rad/s)"``,
  ``"Gyroscope y (rad/s)"``, ``"Gyroscope z (rad/s)"`` (the names of phyphox's experiment
  definition, ``<set name="Gyroscope">``; quoted or not, any letter case; further columns such as
  ``"Absolute (rad/s)"`` are ignored). The three CSV flavours phyphox offers are accepted:
  comma-separated, tab-separated, and semicolon-separated with a decimal comma.
- **plain**: four numeric columns ``t (s), wx, wy, wz (rad/s)``, with or without one header
  line, separated by commas, semicolons, tabs or spaces. A header may name each column's unit
  in brackets, ``t (ms)``, ``wx [deg/s]``: times in s, ms, us or ns and rates in rad/s, deg/s
  (or dps), rpm, rev/s or Hz are converted to s and rad/s; any other unit is refused, naming
  the column.

Lines starting with ``#`` and blank lines are skipped. Every error is one line naming the file
and the line: a missing column, a value that is not a number, a row of the wrong length, fewer
than two rows. The checks of the data themselves (finite, increasing times, enough samples)
are :func:`tumble.analysis.fit.fit_rotation`'s, reported with the file's name.
"""

from __future__ import annotations

import os
import re

import numpy as np

from ..validation import read_input_file

__all__ = ["MAX_GYRO_FILE_BYTES", "TIME_CSV", "parse_gyro_csv", "parse_time_csv", "read_gyro_csv", "read_recording"]

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


def read_gyro_csv(path: str | os.PathLike[str]) -> tuple[np.ndarray, np.ndarray]:
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

    Examples
    --------
    >>> from importlib import resources
    >>> t, omega = read_gyro_csv(resources.files("tumble") / "examples/data/phone_toss.csv")  # 15 s at 100 Hz
    >>> t.shape, omega.shape, round(float(omega[0, 0]), 1)  # spun at 12 rad/s about the sensor's x
    ((1500,), (1500, 3), 12.0)
    """
    raw = read_input_file(path, limit=MAX_GYRO_FILE_BYTES, what="a gyroscope record (CSV)")
    return parse_gyro_csv(raw, os.fspath(path))


def parse_gyro_csv(raw: bytes, label: str) -> tuple[np.ndarray, np.ndarray]:
    """:func:`read_gyro_csv` on the bytes of a file already read (``label`` names it).

    Examples
    --------
    >>> t, omega = parse_gyro_csv(b"t (ms), wx [deg/s], wy [deg/s], wz [deg/s]\\n0, 180, 0, 0\\n10, 180, 0, 90\\n", "toss.csv")
    >>> t.tolist(), omega.round(6).tolist()  # converted to s and rad/s
    ([0.0, 0.01], [[3.141593, 0.0, 0.0], [3.141593, 0.0, 1.570796]])
    >>> parse_gyro_csv(b"t, wx, wy\\n0, 1, 2\\n", "toss.csv")
    Traceback (most recent call last):
    ...
    ValueError: toss.csv, line 1: a header of 3 columns; expected 4 (t, wx, wy, wz) or a phyphox gyroscope export
    """
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
    scale = [1.0, 1.0, 1.0, 1.0]
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
        else:
            scale = [_unit(head[0], _TIME_UNITS, label, first_no, 1)] + \
                [_unit(h, _RATE_UNITS, label, first_no, j + 2) for j, h in enumerate(head[1:])]
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
    rows *= np.array(scale)
    return rows[:, 0].copy(), rows[:, 1:].copy()


#: Units a plain header may name for the time, and their factor to s.
_TIME_UNITS = {"s": 1.0, "sec": 1.0, "ms": 1e-3, "us": 1e-6, "\u00b5s": 1e-6, "\u03bcs": 1e-6, "ns": 1e-9}
#: Units a plain header may name for a rate, and their factor to rad/s.
_RATE_UNITS = {"rad/s": 1.0, "deg/s": np.pi / 180, "\u00b0/s": np.pi / 180, "dps": np.pi / 180,
               "rpm": 2 * np.pi / 60, "rev/s": 2 * np.pi, "hz": 2 * np.pi}
_UNIT = re.compile(r"[(\[]\s*([^()\[\]]+?)\s*[)\]]\s*$")


def _unit(name: str, table: dict, label: str, line: int, column: int) -> float:
    """The factor to SI of the unit a header cell names in brackets, ``"t (ms)"`` or
    ``"wx [deg/s]"``; 1 when it names none (the documented s and rad/s). An unknown unit is
    refused, naming the column: read as SI it would give wrong numbers with no error."""
    match = _UNIT.search(name)
    if match is None:
        return 1.0
    unit = match.group(1).strip().lower().replace(" ", "")
    if unit not in table:
        raise ValueError(f"{label}, line {line}, column {column}: unknown unit {match.group(1)!r} in header "
                         f"{name!r}; use one of {', '.join(k for k in table if k.isascii())}")
    return float(table[unit])


#: The phyphox export's file of START/PAUSE events, inside the folder or the zip.
TIME_CSV = "meta/time.csv"


def parse_time_csv(raw: bytes, label: str) -> list[tuple[str, float]]:
    """phyphox's ``meta/time.csv``: ``[(event, experiment time in s), ...]``.

    Its header is ``"event","experiment time","system time","system time text"``; the events
    are ``START`` and ``PAUSE`` (after a pause the experiment time carries on from the pause).

    Examples
    --------
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


def read_recording(path: str | os.PathLike[str]) -> tuple[np.ndarray, np.ndarray, list]:
    """A whole recording: a CSV file, or a phyphox export (its folder or its ``.zip``).

    Parameters
    ----------
    path : str or Path
        A gyroscope CSV (:func:`read_gyro_csv`), or phyphox's export: a folder or a zip holding
        ``Raw Data.csv`` and ``meta/time.csv`` (the START/PAUSE events; optional).

    Returns
    -------
    t : ndarray, shape (n,)
        Times (phyphox's experiment time), s.
    omega : ndarray, shape (n, 3)
        rad/s, sensor axes.
    events : list of (str, float)
        START/PAUSE events (empty for a plain CSV).

    Raises
    ------
    ValueError
        One line naming the file: as :func:`read_gyro_csv`, a zip that is not one or whose
        members are too large, an export without its gyroscope CSV.

    Examples
    --------
    >>> import tempfile, zipfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     export = Path(folder) / "toss.zip"  # a phyphox export, as the app writes it
    ...     with zipfile.ZipFile(export, "w") as z:
    ...         z.writestr("Raw Data.csv", '"Time (s)","Gyroscope x (rad/s)","Gyroscope y (rad/s)",'
    ...                    '"Gyroscope z (rad/s)"\\n0,1,0,0\\n0.01,1,0,0\\n0.02,1,0,0\\n')
    ...         z.writestr("meta/time.csv", '"event","experiment time"\\nSTART,0\\nPAUSE,0.02\\n')
    ...     t, omega, events = read_recording(export)
    >>> t.tolist(), omega.shape, events
    ([0.0, 0.01, 0.02], (3, 3), [('START', 0.0), ('PAUSE', 0.02)])
    """
    import zipfile
    import zlib

    label = os.fspath(path)
    if os.path.isdir(path):
        names = [e for e in os.listdir(path) if os.path.isfile(os.path.join(path, e))]
        name = _pick_csv(names, label)
        t, omega = read_gyro_csv(os.path.join(path, name))
        meta = os.path.join(path, *TIME_CSV.split("/"))
        events = []
        if os.path.isfile(meta):
            events = parse_time_csv(read_input_file(meta, limit=1 << 20, what="phyphox's meta/time.csv"), meta)
        return t, omega, events
    if label.lower().endswith(".zip"):
        raw = read_input_file(path, limit=MAX_GYRO_FILE_BYTES, what="a phyphox export (zip)")
        import io

        try:
            archive = zipfile.ZipFile(io.BytesIO(raw))
        except zipfile.BadZipFile:
            raise ValueError(f"{label}: not a zip archive (a phyphox export is a .zip of CSV files)") from None
        with archive:
            infos = {i.filename: i for i in archive.infolist() if not i.is_dir()}
            name = _pick_csv(list(infos), label)

            def member(n, limit):
                if infos[n].file_size > limit:
                    raise ValueError(f"{label}: {n} unpacks to {infos[n].file_size} bytes; at most {limit} are read")
                try:
                    return archive.read(n)
                except (zipfile.BadZipFile, zlib.error, EOFError, NotImplementedError) as exc:
                    # a damaged archive (bad deflate data, a bad CRC, cut short) is bad input, not a failed computation
                    raise ValueError(f"{label}: {n} cannot be unpacked, the archive is damaged ({exc})") from None

            t, omega = parse_gyro_csv(member(name, MAX_GYRO_FILE_BYTES), f"{label}/{name}")
            events = []
            if TIME_CSV in infos:
                events = parse_time_csv(member(TIME_CSV, 1 << 20), f"{label}/{TIME_CSV}")
        return t, omega, events
    t, omega = read_gyro_csv(path)
    return t, omega, []
