"""Gyroscope records in: a phone's phyphox export or a plain ``t, wx, wy, wz`` CSV.

Formats read by :func:`read_gyro_csv`:

- **phyphox** (the free phone app of RWTH Aachen, experiment "Gyroscope (rotation rate)",
  export "CSV"): a header line naming the columns ``"Time (s)"``, ``"Gyroscope x (rad/s)"``,
  ``"Gyroscope y (rad/s)"``, ``"Gyroscope z (rad/s)"`` (the names of phyphox's experiment
  definition, ``<set name="Gyroscope">``; quoted or not, any letter case; further columns such as
  ``"Absolute (rad/s)"`` are ignored). The three CSV flavours phyphox offers are accepted:
  comma-separated, tab-separated, and semicolon-separated with a decimal comma.
- **any delimited text with a header line** (a logger's export): the time column and the three
  rate columns found by their names, a raw accelerometer's three columns (the specific force,
  m/s^2 or g) kept when the header names them, the other columns (``|omega|``, a phone's
  linear acceleration, other sensors) ignored by theirs; units in brackets, ``t (ms)``, ``wx [deg/s]``: times in s, ms, us
  or ns and rates in rad/s, deg/s (or dps), rpm, rev/s or Hz are converted to s and rad/s; any
  other unit is refused, naming the column. The names allowed: :mod:`tumble.io.gyrocolumns`.
- **plain, without a header**: four numeric columns ``t (s), wx, wy, wz (rad/s)``; or five,
  when the fifth is ``|omega|`` of columns 2-4 to the precision written (it is then ignored).

Separated by commas, semicolons, tabs or spaces; a trailing separator is allowed. Lines starting
with ``#`` (anywhere) and blank lines are skipped. Sampling may be irregular; the times must
increase. Every error is one line naming the file and the line: a header without a time column
or the three rates (or with two candidates), a value that is not a number, a row of the wrong
length, a time that repeats or goes back, fewer than two rows. :func:`load_recording` also says
what was read (:class:`~tumble.io.gyrocolumns.ColumnsRead`: the columns taken and their units,
those ignored, the rows and the median sample rate). The other checks of the data (finite,
enough samples) are :func:`tumble.analysis.fit.fit_rotation`'s, reported with the file's name.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field, replace

import numpy as np

from .._html import fmt, plural, result_html, result_repr, short_name
from .examples import _read_input
from ._delimited import _NUMBER, _check_order, _first_lines, _refuse_cell, _rows, _split
from .gyrocolumns import ColumnsRead, match_accel, match_header
from .phyphox import ACCEL_CSV, TIME_CSV, _pick_csv, accel_gap, parse_accel_csv, parse_time_csv

__all__ = ["MAX_GYRO_FILE_BYTES", "MAX_SAMPLE_INTERVAL", "GyroRecording", "load_recording", "parse_gyro_csv", "parse_gyro_table",
           "parse_recording_table", "read_gyro_csv", "read_recording"]

#: The largest gyroscope file read, bytes (a day at 100 Hz is about 35 MB of text).
MAX_GYRO_FILE_BYTES = 64 << 20




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
    >>> from tumble.io.gyrodata import read_gyro_csv
    >>> t, omega = read_gyro_csv(resources.files("tumble") / "examples/data/phone_toss.csv")  # 15 s at 100 Hz
    >>> t.shape, omega.shape, round(float(omega[0, 0]), 1)  # spun at 12 rad/s about the sensor's x
    ((1500,), (1500, 3), 12.0)
    """
    raw = _read_input(path, limit=MAX_GYRO_FILE_BYTES, what="a gyroscope record (CSV)")
    return parse_gyro_csv(raw, os.fspath(path))


def parse_gyro_csv(raw: bytes, label: str) -> tuple[np.ndarray, np.ndarray]:
    """:func:`read_gyro_csv` on the bytes of a file already read (``label`` names it).

    Examples
    --------
    >>> from tumble.io.gyrodata import parse_gyro_csv
    >>> t, omega = parse_gyro_csv(b"t (ms), wx [deg/s], wy [deg/s], wz [deg/s]\\n0, 180, 0, 0\\n10, 180, 0, 90\\n", "toss.csv")
    >>> t.tolist(), omega.round(6).tolist()  # converted to s and rad/s
    ([0.0, 0.01], [[3.141593, 0.0, 0.0], [3.141593, 0.0, 1.570796]])
    >>> parse_gyro_csv(b"t, wx, wy\\n0, 1, 2\\n", "toss.csv")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: toss.csv, line 1: header 't, wx, wy' has no rate column for z; allowed: ...
    """
    t, omega, _ = parse_gyro_table(raw, label)
    return t, omega


def parse_gyro_table(raw: bytes, label: str) -> tuple[np.ndarray, np.ndarray, ColumnsRead]:
    """:func:`parse_gyro_csv`, and what was read (:class:`~tumble.io.gyrocolumns.ColumnsRead`).

    Examples
    --------
    >>> from tumble.io.gyrodata import parse_gyro_table
    >>> text = b"# exported by a logger\\ntime (s)\\tgx\\tgy\\tgz\\t|omega|\\n0.0\\t1\\t0\\t0\\t1\\n0.002\\t1\\t0\\t0\\t1\\n"
    >>> t, omega, read = parse_gyro_table(text, "log.txt")
    >>> read.rates, read.ignored, read.rows, read.sample_rate
    (('gx', 'gy', 'gz'), ('|omega|',), 2, 500.0)
    """
    t, omega, _, read = parse_recording_table(raw, label)
    return t, omega, read


def parse_recording_table(raw: bytes, label: str) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, ColumnsRead]:
    """:func:`parse_gyro_table`, and the accelerometer's specific force when the header names
    its three columns (:func:`~tumble.io.gyrocolumns.match_accel`; m/s^2, sensor axes; None
    otherwise).

    Examples
    --------
    >>> from tumble.io.gyrodata import parse_recording_table
    >>> text = b"t (ms), gx, gy, gz, acc_x (g), acc_y (g), acc_z (g), linear acceleration x\\n0, 1, 0, 0, 0, 0, 1, 0\\n" \\
    ...        b"10, 1, 0, 0, 0, 0, 0, -9.8\\n"
    >>> t, omega, accel, read = parse_recording_table(text, "log.csv")
    >>> accel[:, 2].tolist(), read.accel, read.ignored   # 1 g at rest, then falling
    ([9.80665, 0.0], ('acc_x (g)', 'acc_y (g)', 'acc_z (g)'), ('linear acceleration x',))
    """
    lines, sep, head = _first_lines(raw, label, "a phyphox gyroscope export or columns t, wx, wy, wz")
    first_no = lines[0][0]
    columns = [0, 1, 2, 3]
    scale = [1.0, 1.0, 1.0, 1.0]
    names = {"time": "column 1", "time_unit": "s", "rates": ["column 2", "column 3", "column 4"],
             "rate_units": ["rad/s"] * 3, "ignored": []}
    magnitude = False
    header = not all(_NUMBER.match(c) for c in head)
    if header:  # a header line
        # phyphox's "Time (s)", "Gyroscope x (rad/s)" ... are names of the table like any (its deg/s too; a
        # column missing is refused naming the names allowed)
        columns, scale, names = match_header(head, label, first_no)
        more, factors, accel_units = match_accel(head, columns, label, first_no)
        columns, scale = columns + more, scale + factors
        names.update(accel=[head[j] for j in more], accel_units=accel_units,
                     ignored=[h for j, h in enumerate(head) if j not in columns])
        width = len(head)
        lines = lines[1:]
    elif len(head) == 5:  # a fifth column without a header: read when it is |omega| of columns 2-4
        width, magnitude = 5, True
        names["ignored"] = ["column 5 (|omega|)"]
    elif len(head) != 4:
        raise ValueError(f"{label}, line {first_no}: {len(head)} columns; expected 4 (t, wx, wy, wz), a fifth "
                         "|omega|, or a header line naming the columns")
    else:
        width = 4
    read_columns = columns + ([4] if magnitude else [])
    rows = _rows(lines, sep, read_columns, width, label)
    # a nan, an inf or a number past double (1e400) named by its line and column, before anything else: the
    # fit's own check named an array and a 0-based sample (omega_measured[399]; a walkthrough, issue 40)
    labels = [head[c] if header else f"column {c + 1}" for c in read_columns]
    _refuse_cell(~np.isfinite(rows), rows, lines, read_columns, labels, label, lambda k, j: "is not a finite number")
    if len(rows) < 2:
        raise ValueError(f"{label}: {len(rows)} data rows; a record needs many samples")
    if magnitude:
        ulp = np.array([[_last_digit(cells[4]), max(_last_digit(c) for c in cells[1:4])]
                        for cells in (_split(line, sep) for _, line in lines)])
        fifth, rows = rows[:, 4], rows[:, :4]
    rows *= np.array(scale)
    t, omega = rows[:, 0].copy(), rows[:, 1:4].copy()
    accel = rows[:, 4:7].copy() if len(columns) == 7 else None
    if magnitude:
        _check_magnitude(omega, fifth, ulp, lines, label)
    _check_order(t, lines, label)
    _check_sample_interval(t, names["time"], names["time_unit"], label)
    read = ColumnsRead(label, names["time"], names["time_unit"], tuple(names["rates"]), tuple(names["rate_units"]),
                       tuple(names["ignored"]), len(t), float(1.0 / np.median(np.diff(t))),
                       tuple(names.get("accel", ())), tuple(names.get("accel_units", ())))
    return t, omega, accel, read


#: The longest median interval between a gyroscope's samples, s: phones sample at 50-500 Hz and
#: loggers faster; a time in ms or us read as s is 1000 or 10^6 times longer (ms at 1 kHz or
#: faster, read as s, is not caught).
MAX_SAMPLE_INTERVAL = 1.0


def _check_sample_interval(t: FloatArray, name: str, unit: str, label: str) -> None:
    """Refuse times whose samples lie more than :data:`MAX_SAMPLE_INTERVAL` apart, naming the unit that
    would put them 0.1 ms to 0.1 s apart: ``timestamp,gx,gy,gz`` in ms read as s found "357 flights,
    357 too short" (a walkthrough of docs/fitting.md, 2026-12-03)."""
    dt = float(np.median(np.diff(t)))
    if dt <= MAX_SAMPLE_INTERVAL:
        return
    likely = next((u for u, f in (("ms", 1e-3), ("us", 1e-6), ("ns", 1e-9)) if 1e-4 <= dt * f <= 0.1), None)
    bare = name.split("(")[0].split("[")[0].strip() or "t"
    hint = f"; is it in {likely}? Name its unit in the header: '{bare} ({likely})'" if likely else ""
    raise ValueError(f"{label}: the time column {name!r}, read in {unit}, puts the samples {dt:.3g} s apart "
                     f"({1.0 / dt:.2g} Hz); a gyroscope samples tens to thousands of times a second{hint}")


def _last_digit(cell: str) -> float:
    """The value of one unit in the last digit a number is written with (``"1.25"``: 0.01)."""
    mantissa, _, exponent = cell.lower().partition("e")
    decimals = len(mantissa.replace(",", ".").partition(".")[2])
    return float(10.0 ** ((int(exponent) if exponent else 0) - decimals))


def _check_magnitude(omega, fifth, ulp, lines, label) -> None:
    """A header-less fifth column must be |omega| of columns 2-4 to the precision written."""
    norm = np.linalg.norm(omega, axis=1)
    tol = 0.5 * ulp[:, 0] + 0.9 * ulp[:, 1] + 1e-9 * norm
    off = np.flatnonzero(~(np.abs(fifth - norm) <= tol))
    if off.size:
        k = int(off[0])
        raise ValueError(f"{label}, line {lines[k][0]}: 5 columns without a header, and the fifth ({fifth[k]:.6g}) "
                         f"is not |omega| of columns 2-4 ({norm[k]:.6g}); name the columns in a header line "
                         "(t, wx, wy, wz and others)")


@dataclass(frozen=True)
class GyroRecording:
    """A recording as read: its samples, phyphox's events and what was read (:func:`load_recording`).

    Attributes
    ----------
    t : ndarray, shape (n,)
        Times, s.
    omega : ndarray, shape (n, 3)
        rad/s, sensor axes.
    events : tuple of (str, float)
        START/PAUSE events (empty for a plain file).
    read : ColumnsRead
        Which columns were taken, in which units, how many rows (:mod:`tumble.io.gyrocolumns`).
    accel : ndarray, shape (n, 3), or None
        The accelerometer's specific force at the times ``t``, m/s^2, sensor axes: the file's
        own columns, or a phyphox export's ``Accelerometer.csv`` interpolated onto the
        gyroscope's times (:func:`parse_accel_csv`); None without one, or when the export's does
        not cover the gyroscope's record (``read.accel_left_out`` says so).

    Examples
    --------
    >>> from importlib import resources
    >>> from tumble.io.gyrodata import load_recording
    >>> rec = load_recording(resources.files("tumble") / "examples/data/phone_toss.csv")
    >>> rec.read.brief()   # phyphox's names; the phone's clock a little irregular
    'Time (s), Gyroscope x, Gyroscope y, Gyroscope z (rad/s), 1500 rows at 99.9 Hz'
    """

    t: np.ndarray = field(repr=False)
    omega: np.ndarray = field(repr=False)
    events: tuple
    read: ColumnsRead
    accel: np.ndarray | None = field(default=None, repr=False)

    def _rows(self) -> list[tuple[str, str]]:
        """(what, value): the recording's size, speed, events and accelerometer."""
        n = len(self.t)
        rows = [("samples", plural(n, "sample") + (f" over {fmt(self.t[-1] - self.t[0], 3)} s" if n > 1 else "")),
                ("sample rate", f"{fmt(self.read.sample_rate, 3)} Hz")]
        if n:
            rows.append(("largest |omega|", f"{fmt(np.linalg.norm(self.omega, axis=1).max(), 3)} rad/s"))
        rows.append(("events", plural(len(self.events), "event")))
        accel = "with the accelerometer" if self.accel is not None else "no accelerometer"
        rows.append(("accelerometer", f"{accel}: {self.read.accel_left_out}" if self.read.accel_left_out else accel))
        return rows

    def __repr__(self) -> str:
        """``GyroRecording('phone_toss.csv', 1500 samples over 15 s, 99.9 Hz, ...)``: one short line.

        Examples
        --------
        >>> from importlib import resources
        >>> from tumble.io.gyrodata import load_recording
        >>> load_recording(resources.files("tumble") / "examples/data/phone_toss.csv")
        GyroRecording('phone_toss.csv', 1500 samples over 15 s, 99.9 Hz, largest |omega| 15.1 rad/s, 0 events, no accelerometer)
        """
        rows = dict(self._rows())
        parts = [short_name(os.path.basename(self.read.file)), rows["samples"], rows["sample rate"]]
        if "largest |omega|" in rows:
            parts.append(f"largest |omega| {rows['largest |omega|']}")
        return result_repr("GyroRecording", [*parts, rows["events"], rows["accelerometer"]])

    def _repr_html_(self) -> str:
        """The recording's file, columns, size and speed as an HTML table (Jupyter).

        Examples
        --------
        >>> from importlib import resources
        >>> from tumble.io.gyrodata import load_recording
        >>> page = load_recording(resources.files("tumble") / "examples/data/phone_toss.csv")._repr_html_()
        >>> "Gyroscope x" in page, "1500 samples" in page
        (True, True)
        """
        return result_html("GyroRecording", [("file", str(self.read.file)), ("columns", self.read.brief()), *self._rows()])


def read_recording(path: str | os.PathLike[str]) -> tuple[np.ndarray, np.ndarray, list]:
    """A whole recording: a CSV file, or a phyphox export (its folder or its ``.zip``); its
    accelerometer, when it has one, is :func:`load_recording`'s.

    Parameters
    ----------
    path : str or Path
        A gyroscope CSV (:func:`read_gyro_csv`), or phyphox's export: a folder or a zip holding
        ``Raw Data.csv`` (or ``Gyroscope.csv``), ``meta/time.csv`` (the START/PAUSE events;
        optional) and ``Accelerometer.csv`` (the raw accelerometer; optional).

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
    >>> from tumble.io.gyrodata import read_recording
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
    rec = load_recording(path)
    return rec.t, rec.omega, list(rec.events)


def load_recording(path: str | os.PathLike[str]) -> GyroRecording:
    """:func:`read_recording`, and what was read: a :class:`GyroRecording`.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from tumble.io.gyrodata import load_recording
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     log = Path(folder) / "log.txt"   # a logger's export: comments, a header, |omega| and the accelerometer
    ...     _ = log.write_text("# phone 1\\ntimestamp (ms) gyro_x gyro_y gyro_z acc_x acc_y acc_z |omega|\\n"
    ...                        "0 1 0 0 0 0 9.8 1\\n2 1 0 0 0 0 9.8 1\\n4.5 1 0 0 0 0 9.8 1\\n")
    ...     rec = load_recording(log)
    >>> rec.t.round(6).tolist(), rec.read.time, rec.read.ignored, rec.read.accel
    ([0.0, 0.002, 0.0045], 'timestamp (ms)', ('|omega|',), ('acc_x', 'acc_y', 'acc_z'))
    >>> rec.accel[0].tolist()   # the specific force, m/s^2: the phone at rest
    [0.0, 0.0, 9.8]
    """
    import zipfile
    import zlib

    label = os.fspath(path)
    if os.path.isdir(path):
        names = [e for e in os.listdir(path) if os.path.isfile(os.path.join(path, e))]
        name = _pick_csv(names, label)
        csv_path = os.path.join(path, name)
        raw = _read_input(csv_path, limit=MAX_GYRO_FILE_BYTES, what="a gyroscope record (CSV)")
        t, omega, accel, read = parse_recording_table(raw, csv_path)
        meta = os.path.join(path, *TIME_CSV.split("/"))
        events = []
        if os.path.isfile(meta):
            events = parse_time_csv(_read_input(meta, limit=1 << 20, what="phyphox's meta/time.csv"), meta)
        acc, read = _accel_csv(names, read)
        if accel is None and acc is not None:
            p = os.path.join(path, acc)
            accel, read = _with_accel(_read_input(p, limit=MAX_GYRO_FILE_BYTES, what="an accelerometer record (CSV)"),
                                      p, t, read)
        return GyroRecording(t, omega, tuple(events), read, accel)
    if label.lower().endswith(".zip"):
        raw = _read_input(path, limit=MAX_GYRO_FILE_BYTES, what="a phyphox export (zip)")
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

            t, omega, accel, read = parse_recording_table(member(name, MAX_GYRO_FILE_BYTES), f"{label}/{name}")
            events = []
            if TIME_CSV in infos:
                events = parse_time_csv(member(TIME_CSV, 1 << 20), f"{label}/{TIME_CSV}")
            acc, read = _accel_csv(list(infos), read)
            if accel is None and acc is not None:
                accel, read = _with_accel(member(acc, MAX_GYRO_FILE_BYTES), f"{label}/{acc}", t, read)
        return GyroRecording(t, omega, tuple(events), read, accel)
    if label.lower().endswith(".toml"):  # a scenario, body or device file given to 'tumble fit'
        raise ValueError(f"{label}: a TOML file (a scenario, body or device file), not a gyroscope recording: "
                         "'tumble simulate' runs a scenario; 'tumble fit' reads a CSV of the rates, or a phyphox or "
                         "Sensor Logger export")
    raw = _read_input(path, limit=MAX_GYRO_FILE_BYTES, what="a gyroscope record (CSV)")
    t, omega, accel, read = parse_recording_table(raw, label)
    return GyroRecording(t, omega, (), read, accel)


#: Sensor Logger's accelerometer files (iOS and Android), beside ``Gyroscope.csv`` and ``Metadata.csv``.
SENSOR_LOGGER_ACCEL = ("totalacceleration.csv", "metadata.csv")


def _accel_csv(names: list[str], read: ColumnsRead) -> tuple[str | None, ColumnsRead]:
    """The accelerometer file of an export with several sensors (phyphox's ``Accelerometer.csv``),
    or None. Sensor Logger's export (its ``TotalAcceleration.csv`` and ``Metadata.csv``) has an
    ``Accelerometer.csv`` too, with the phone's estimate of gravity taken out: not the specific
    force, which a tumbling phone's estimate cannot give. It is left out, and what was read says
    why. Its ``TotalAcceleration.csv`` (gravity included) is not read either: no export of the
    app's was at hand to check its units and signs on both platforms against, so the flights are
    found from the gyroscope alone rather than from a reading taken on trust."""
    lower = {n.lower().rsplit("/", 1)[-1] for n in names}
    acc = next((n for n in names if n.lower() == ACCEL_CSV.lower()), None)
    # Sensor Logger's by its other files, or by its Gyroscope.csv's own layout (its time column seconds_elapsed:
    # a walkthrough's export without Metadata.csv was read as phyphox's and refused)
    logger = any(k in lower for k in SENSOR_LOGGER_ACCEL) or read.time.strip().lower() == "seconds_elapsed"
    if acc is not None and logger:
        return None, replace(read, accel_left_out="Sensor Logger's Accelerometer.csv has gravity taken out (not the "
                                                  "specific force): not used; the flights are found from the "
                                                  "gyroscope alone")
    if acc is None and "linear acceleration.csv" in lower:  # phyphox's "Acceleration without g", said as documented
        return None, replace(read, accel_left_out="Linear Acceleration.csv has gravity taken out by the phone (not the "
                                                  "specific force): not used; the flights are found from the "
                                                  "gyroscope alone")
    return acc, read


def _with_accel(raw: bytes, label: str, t: np.ndarray, read: ColumnsRead) -> tuple[np.ndarray | None, ColumnsRead]:
    """A phyphox export's accelerometer on the gyroscope's times, and what was read saying so;
    None, and why, when it does not cover the gyroscope's record."""
    head = raw[:2000].decode("utf-8", "replace").lower()
    if "linear acceleration" in head and "acceleration x" not in head.replace("linear acceleration x", ""):
        # phyphox's "Acceleration without g" export: the phone's estimate of gravity taken out, not the
        # specific force; left out as documented (docs/fitting.md), not the whole recording refused
        return None, replace(read, accel_left_out=f"{os.path.basename(label)} holds the linear acceleration (gravity "
                                                  "taken out by the phone, not the specific force): not used; the "
                                                  "flights are found from the gyroscope alone")
    f, names, units, times = parse_accel_csv(raw, label, t)
    gap = accel_gap(times, t, label)
    if gap:
        return None, replace(read, accel_left_out=gap)
    return f, replace(read, accel=names, accel_units=units)
