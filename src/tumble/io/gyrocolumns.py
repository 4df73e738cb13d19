"""Which columns of a gyroscope table are the time and the three rates: by their header names.

A header cell is a name and, in brackets or parentheses at its end, a unit: ``"Time (s)"``,
``"gyro_x [deg/s]"``. The name is compared in lower case with spaces, ``_``, ``-`` and ``.``
alike (``gyro_x``, ``Gyro X`` and ``gyro-x`` are one name):

- **time**: ``t``, ``time``, ``timestamp``, ``time stamp``, ``elapsed``, ``elapsed time``,
  ``seconds elapsed``; its unit s (default), ms, us or ns. Beside a clock's column the elapsed
  one is taken, the clock ignored: Sensor Logger's ``Gyroscope.csv`` (iOS and Android) is
  ``time,seconds_elapsed,z,y,x``, the time in ns since 1970 and the rates in rad/s;
- **rate** about axis ``x`` (``y``, ``z`` alike): ``x``, ``wx``, ``gx``, ``omega x``, ``gyro x``,
  ``gyroscope x``, ``rate x``, ``rotation rate x``, ``angular velocity x`` (a space, or none,
  before the axis; ``x axis`` too); unit rad/s (default), deg/s, dps, rpm, rev/s or Hz. tumble's own
  ``trajectory.csv`` names them ``omega_1``, ``omega_2``, ``omega_3`` (the principal axes), read as
  x, y and z: a simulated run is fitted as a recording;
- **specific force** (a raw accelerometer, optional; all three axes or none) along ``x`` (``y``,
  ``z`` alike): ``ax``, ``acc x``, ``accel x``, ``accelerometer x``, ``acceleration x``,
  ``specific force x``, ``f x``; in m/s^2 (default), g (standard gravity, 9.80665 m/s^2) or mg
  (:func:`match_accel`, which the throw files' reader uses too). A phone's **linear acceleration**
  (``linear acceleration x``, phyphox's "acceleration without g") is **not** the specific force:
  the phone's sensor fusion subtracts a gravity estimate that a tumbling phone cannot track, so it
  is ignored, and the summary of what was read says so;
- **ignored**, and named as such: the other sensors' axes (``linear acceleration x``,
  ``gravity x``, ``mag x``, ``magnetic field x``), magnitudes (``|omega|``, ``abs``,
  ``absolute``, ``norm``, ``magnitude``) and any other name.

A header with no time column, two, or not one rate column for each axis is refused in one line
naming the file, the header and the names allowed.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from ..dynamics.environment.earth import STANDARD_GRAVITY
from .keys import FileFormat, Key, Table

__all__ = ["ACCEL_UNITS", "RATE_PREFIXES", "RATE_UNITS", "RECORDING_FORMAT", "TIME_NAMES", "TIME_UNITS", "ColumnsRead", "match_accel",
           "match_header"]

#: Units a header may name for the time, and their factor to s.
TIME_UNITS = {"s": 1.0, "sec": 1.0, "ms": 1e-3, "us": 1e-6, "\u00b5s": 1e-6, "\u03bcs": 1e-6, "ns": 1e-9}
#: Units a header may name for a rate, and their factor to rad/s.
RATE_UNITS = {"rad/s": 1.0, "deg/s": np.pi / 180, "\u00b0/s": np.pi / 180, "dps": np.pi / 180,
              "rpm": 2 * np.pi / 60, "rev/s": 2 * np.pi, "hz": 2 * np.pi}
#: Units a header may name for the specific force, and their factor to m/s^2 (g: standard gravity,
#: :data:`tumble.dynamics.environment.earth.STANDARD_GRAVITY`).
ACCEL_UNITS = {"m/s^2": 1.0, "m/s2": 1.0, "m/s\u00b2": 1.0, "ms^-2": 1.0, "g": STANDARD_GRAVITY,
               "mg": 1e-3 * STANDARD_GRAVITY}

#: The names a header may give the time column (compared in lower case, ``_ - .`` as spaces).
TIME_NAMES = ("t", "time", "timestamp", "time stamp", "elapsed", "elapsed time", "seconds elapsed")
#: The words before the axis (``x``, ``y``, ``z``) in the name of a rate column; the axis alone too.
RATE_PREFIXES = ("w", "g", "omega", "gyro", "gyroscope", "rate", "rotation rate", "angular velocity", "angular rate")
#: The columns of a gyroscope table, as the page on recordings lists them.
RECORDING_FORMAT = FileFormat("recording", (
    Table("header columns", (
        Key("time", "numbers, increasing", ", ".join(TIME_UNITS), "s", choices=TIME_NAMES, example='"Time (s)"',
            doc="the sample times; the unit in brackets after the name; beside a clock's column (time, timestamp) "
                "an elapsed one is taken and the clock ignored (Sensor Logger's time,seconds_elapsed)"),
        *(Key(axis, "numbers", ", ".join(u for u in RATE_UNITS if u.isascii()), "rad/s",
              allowed=f"{axis} alone or after {', '.join(RATE_PREFIXES)}; then ' axis' optionally; or "
                      f"omega_{'xyz'.index(axis) + 1} (tumble's trajectory.csv)",
              example=f'"gyro_{axis} [deg/s]"', doc=f"the angular velocity about the sensor's {axis} axis")
          for axis in "xyz"),
        *(Key(f"a{axis}", "numbers", ", ".join(u for u in ACCEL_UNITS if u.isascii()), "m/s^2",
              allowed=f"a{axis}, acc {axis}, accel {axis}, accelerometer {axis}, acceleration {axis}, specific force "
                      f"{axis}, f {axis}", example=f'"Acceleration {axis} (m/s^2)"',
              doc=f"optional (all three or none): a raw accelerometer's specific force along the sensor's {axis} "
                  "axis; a phone's linear acceleration (gravity removed) is not it and is ignored")
          for axis in "xyz"),
        Key("other", "anything", allowed="linear acceleration, the other sensors' axes (gravity x, mag x, ...), "
            "magnitudes (|omega|, norm, ...), any other name", example='"Absolute (rad/s)"',
            doc="ignored, and reported as such"),
    ), "A header line names the columns: a name and, in brackets or parentheses at its end, a unit. "
       "Names are compared in lower case with spaces, ``_``, ``-`` and ``.`` alike; a header needs "
       "one time column and one rate column for each axis."),
    Table("without a header", (
        Key("column 1", "numbers, increasing", "s", required=True, example="0.01", doc="the time"),
        Key("columns 2-4", "numbers", "rad/s", required=True, example="12.0, 0.1, 0.3", doc="wx, wy, wz"),
        Key("column 5", "numbers", "rad/s", allowed="|omega| of columns 2-4 to the precision written",
            example="12.004", doc="ignored"),
    ), "Four or five numeric columns, separated by commas, semicolons, tabs or spaces."),
), "A gyroscope recording: delimited text (a phyphox export, a logger's CSV), a phyphox export's folder "
   "or zip; ``tumble fit`` and :func:`tumble.io.gyrodata.load_recording` read it.")

_UNIT = re.compile(r"[(\[]\s*([^()\[\]]+?)\s*[)\]]\s*$")
_TIME = set(TIME_NAMES)
#: The time names that count from the recording's start (taken beside a clock's column).
_ELAPSED = {"elapsed", "elapsed time", "seconds elapsed"}
_RATE = re.compile(r"^(?:(?:" + "|".join(re.escape(p) for p in RATE_PREFIXES) + r") ?)?([xyz])(?: axis)?$")
#: tumble's trajectory.csv: omega about the principal axes 1, 2, 3, read as x, y, z.
_PRINCIPAL = re.compile(r"^omega ?([123])$")
_OTHER = re.compile(r"^(?:a|acc|accel|accelerometer|acceleration|linear acceleration|lin acc|gravity|m|mag|"
                    r"magnetometer|magnetic field|b) ?[xyz](?: axis)?$")
_ACCEL = re.compile(r"^(?:a|acc|accel|accelerometer|acceleration|specific force|f) ?([xyz])(?: axis)?$")
_LINEAR = re.compile(r"^(?:linear acceleration|lin acc|acceleration without g|user acceleration) ?[xyz](?: axis)?$")
_MAGNITUDE = re.compile(r"^(?:\|.*\||abs|absolute|norm|magnitude|total)$")
_ALLOWED = ("time: t, time, timestamp (s, ms, us, ns); rates: x, wx, gx, omega_x, gyro_x, gyroscope x "
            "(rad/s, deg/s, rpm, rev/s, Hz), y and z alike, or omega_1, omega_2, omega_3")


@dataclass(frozen=True)
class ColumnsRead:
    """What was read from a gyroscope table: which columns, in which units, how many rows.

    Attributes
    ----------
    file : str
        The file (a zip's member as ``archive.zip/member``).
    time : str
        The time column as its header names it (``"column 1"`` without a header).
    time_unit : str
        Its unit, converted to s.
    rates : tuple of str
        The x, y, z rate columns as named.
    rate_units : tuple of str
        Their units, converted to rad/s.
    ignored : tuple of str
        The columns left out (``"column 5 (|omega|)"`` without a header).
    rows : int
        Data rows read.
    sample_rate : float
        The median of ``1 / (t[k+1] - t[k])``, Hz.
    accel : tuple of str
        The x, y, z specific-force columns as named (a phyphox export's accelerometer as
        ``"Accelerometer.csv: Acceleration x"``, interpolated onto the gyroscope's times); empty
        without an accelerometer.
    accel_units : tuple of str
        Their units, converted to m/s^2.
    accel_left_out : str
        Why an accelerometer that was there is not used (a phyphox export's ``Accelerometer.csv``
        with no sample near some of the gyroscope's: a late start, an early end, a gap between);
        empty otherwise.

    Examples
    --------
    >>> from tumble.io.gyrocolumns import ColumnsRead
    >>> read = ColumnsRead("toss.csv", "t", "s", ("wx", "wy", "wz"), ("rad/s",) * 3, ("|omega|",), 1500, 100.0)
    >>> read.summary()["rates"], read.brief()
    (['wx', 'wy', 'wz'], 't (s), wx, wy, wz (rad/s), 1 ignored, 1500 rows at 100 Hz')
    """

    file: str
    time: str
    time_unit: str
    rates: tuple
    rate_units: tuple
    ignored: tuple
    rows: int
    sample_rate: float
    accel: tuple = ()
    accel_units: tuple = ()
    accel_left_out: str = ""

    def summary(self) -> dict:
        """JSON-ready (fit.json's ``"read"``).

        Examples
        --------
        >>> from tumble.io.gyrocolumns import ColumnsRead
        >>> ColumnsRead("a.csv", "column 1", "s", ("column 2", "column 3", "column 4"), ("rad/s",) * 3, (), 2, 50.0).summary()["time"]
        {'column': 'column 1', 'unit': 's'}
        """
        out = {"file": self.file, "time": {"column": self.time, "unit": self.time_unit},
               "rates": list(self.rates), "rate_units": list(self.rate_units),
               "accel": list(self.accel) or None, "accel_units": list(self.accel_units) or None,
               "ignored": list(self.ignored), "rows": int(self.rows), "sample_rate_median_hz": float(self.sample_rate)
               if np.isfinite(self.sample_rate) else None}
        linear = [c for c in self.ignored if _LINEAR.match(_name(c)[0])]
        if linear:
            out["not_specific_force"] = (f"{', '.join(linear)}: a phone's linear acceleration (its fusion's gravity "
                                         "estimate taken out, which a tumbling phone cannot track) is not the "
                                         "specific force; ignored")
        if self.accel_left_out:
            out["accel_left_out"] = self.accel_left_out
        return out

    def brief(self) -> str:
        """A few words for the command's one line.

        Examples
        --------
        >>> from tumble.io.gyrocolumns import ColumnsRead
        >>> ColumnsRead("a.csv", "Time", "ms", ("gx", "gy", "gz"), ("deg/s",) * 3, (), 900, 400.0).brief()
        'Time (ms), gx, gy, gz (deg/s), 900 rows at 400 Hz'
        >>> ColumnsRead("a.csv", "t", "s", ("wx", "wy", "wz"), ("rad/s",) * 3, ("linear_acceleration_x",), 9, 100.0).brief()
        "t (s), wx, wy, wz (rad/s), 1 ignored (1 a phone's linear acceleration, not the specific force), 9 rows at 100 Hz"
        """
        def bare(cell):
            match = _UNIT.search(cell)
            return cell[:match.start()].strip() if match else cell

        units = self.rate_units[0] if len(set(self.rate_units)) == 1 else "/".join(self.rate_units)
        linear = [c for c in self.ignored if _LINEAR.match(_name(c)[0])]  # fit.json says why (summary)
        ignored = f", {len(self.ignored)} ignored" if self.ignored else ""
        ignored += f" ({len(linear)} a phone's linear acceleration, not the specific force)" if linear else ""
        ignored += ", the accelerometer left out" if self.accel_left_out else ""
        accel = f", {', '.join(bare(a) for a in self.accel)} ({'/'.join(dict.fromkeys(self.accel_units))})" \
            if self.accel else ""
        return (f"{bare(self.time)} ({self.time_unit}), {', '.join(bare(r) for r in self.rates)} ({units}){accel}"
                f"{ignored}, {self.rows} rows at {self.sample_rate:.3g} Hz")


def _name(cell: str) -> tuple[str, str | None]:
    """A header cell's name (lower case, separators as one space) and its unit (or None)."""
    match = _UNIT.search(cell)
    unit = match.group(1).strip() if match else None
    name = cell[:match.start()] if match else cell
    return re.sub(r"[\s_\-.:]+", " ", name.strip().lower()).strip(), unit


def _factor(cell: str, unit: str | None, table: dict, label: str, line: int, column: int) -> tuple[float, str]:
    if unit is None:
        return 1.0, next(iter(table))
    key = unit.lower().replace(" ", "")
    if key not in table:
        raise ValueError(f"{label}, line {line}, column {column}: unknown unit {unit!r} in header "
                         f"{cell!r}; use one of {', '.join(k for k in table if k.isascii())}")
    return float(table[key]), unit


def match_accel(head: list[str], taken: list[int], label: str, line: int,
                allowed: str = "") -> tuple[list[int], list[float], list[str]]:
    """The specific-force columns ``x, y, z`` of a header (module docstring), not among ``taken``:
    their indices, factors to m/s^2 and units; three empty lists when the header has none.

    Raises
    ------
    ValueError
        One line naming the file, the line and the header: one axis without the others, two
        columns for an axis, an unknown unit.

    Examples
    --------
    >>> from tumble.io.gyrocolumns import match_accel
    >>> match_accel(["t", "gx", "gy", "gz", "acc_x (g)", "acc_y (g)", "acc_z (g)"], [0, 1, 2, 3], "a.csv", 1)[0]
    [4, 5, 6]
    >>> match_accel(["t", "gx", "gy", "gz", "linear acceleration x"], [0, 1, 2, 3], "a.csv", 1)   # not the specific force
    ([], [], [])
    """
    parsed = [_name(cell) for cell in head]
    shown = ", ".join(head)
    shown = shown if len(shown) <= 160 else shown[:157] + "..."
    axes: dict[str, list[int]] = {"x": [], "y": [], "z": []}
    for j, (n, _) in enumerate(parsed):
        m = _ACCEL.match(n)
        if m and j not in taken:
            axes[m.group(1)].append(j)
    found = [a for a, js in axes.items() if js]
    columns: list[int] = []
    scale: list[float] = []
    units: list[str] = []
    if not found:
        return columns, scale, units
    allowed = allowed or "ax, acc_x, accel x, accelerometer x, acceleration x, specific force x (m/s^2, g, mg), y and z alike"
    for axis, js in axes.items():
        if len(js) != 1:
            what = f"no specific-force column for {axis} (but one for {', '.join(found)})" if not js else \
                f"{len(js)} specific-force columns for {axis} ({', '.join(repr(head[j]) for j in js)})"
            raise ValueError(f"{label}, line {line}: header {shown!r} has {what}; allowed: {allowed}")
        f, u = _factor(head[js[0]], parsed[js[0]][1], ACCEL_UNITS, label, line, js[0] + 1)
        columns.append(js[0]), scale.append(f), units.append(u)
    return columns, scale, units


def match_header(head: list[str], label: str, line: int) -> tuple[list[int], list[float], dict]:
    """The columns of the time and the x, y, z rates in a header line, their factors to SI and
    what they are (module docstring).

    Returns
    -------
    columns : list of int
        Indices of the time, x, y, z columns.
    scale : list of float
        Their factors to s and rad/s.
    names : dict
        ``time``, ``time_unit``, ``rates``, ``rate_units``, ``ignored``: as :class:`ColumnsRead`.

    Raises
    ------
    ValueError
        One line naming the file, the line, the header and what is allowed.

    Examples
    --------
    >>> from tumble.io.gyrocolumns import match_header
    >>> columns, scale, names = match_header(["time (ms)", "acc_x", "gyro_x [deg/s]", "gyro_y [deg/s]", "gyro_z [deg/s]", "|omega|"], "a.csv", 1)
    >>> columns, names["ignored"]
    ([0, 2, 3, 4], ['acc_x', '|omega|'])
    >>> columns, scale, names = match_header(["time", "seconds_elapsed", "z", "y", "x"], "Gyroscope.csv", 1)
    >>> columns, names["time"], names["ignored"]   # Sensor Logger's: the seconds elapsed, not the clock
    ([1, 4, 3, 2], 'seconds_elapsed', ['time'])
    >>> match_header(["t", "ax", "ay", "az"], "a.csv", 1)
    Traceback (most recent call last):
    ...
    ValueError: a.csv, line 1: header 't, ax, ay, az' has no rate column for x; allowed: time: t, time, timestamp (s, ms, us, ns); rates: x, wx, gx, omega_x, gyro_x, gyroscope x (rad/s, deg/s, rpm, rev/s, Hz), y and z alike, or omega_1, omega_2, omega_3
    """
    parsed = [_name(cell) for cell in head]
    shown = ", ".join(head)
    if len(shown) > 160:
        shown = shown[:157] + "..."
    times = [j for j, (n, _) in enumerate(parsed) if n in _TIME]
    elapsed = [j for j in times if parsed[j][0] in _ELAPSED]
    if len(times) == 2 and len(elapsed) == 1:  # a clock and the seconds since the start (Sensor Logger): the latter
        times = elapsed
    axes: dict[str, list[int]] = {"x": [], "y": [], "z": []}
    for j, (n, _) in enumerate(parsed):
        m = _RATE.match(n)
        if m and not _OTHER.match(n):
            axes[m.group(1)].append(j)
        elif p := _PRINCIPAL.match(n):
            axes["xyz"[int(p.group(1)) - 1]].append(j)
    if len(times) != 1:
        what = "no time column" if not times else \
            f"{len(times)} time columns ({', '.join(repr(head[j]) for j in times)}); keep one"
        raise ValueError(f"{label}, line {line}: header {shown!r} has {what}; allowed: {_ALLOWED}")
    for axis, found in axes.items():
        if len(found) != 1:
            what = f"no rate column for {axis}" if not found else \
                f"{len(found)} rate columns for {axis} ({', '.join(repr(head[j]) for j in found)})"
            raise ValueError(f"{label}, line {line}: header {shown!r} has {what}; allowed: {_ALLOWED}")
    columns = [times[0], axes["x"][0], axes["y"][0], axes["z"][0]]
    scale, units = [], []
    for k, j in enumerate(columns):
        f, u = _factor(head[j], parsed[j][1], TIME_UNITS if k == 0 else RATE_UNITS, label, line, j + 1)
        scale.append(f), units.append(u)
    names = {"time": head[columns[0]], "time_unit": units[0], "rates": [head[j] for j in columns[1:]],
             "rate_units": units[1:], "ignored": [h for j, h in enumerate(head) if j not in columns]}
    return columns, scale, names
