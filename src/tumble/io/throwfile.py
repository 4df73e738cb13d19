"""Throw files (CSV): one throw of the device of ``tumble calibrate`` and ``tumble tensor``.

A throw is delimited text with the columns ``t (s), wx, wy, wz (rad/s), rotor (rad/s), ax, ay,
az (m/s^2)``, in the device's sensor frame: the gyroscope's rates, the rotor's speed relative
to the device (positive about the device's ``rotor_axis``) and the accelerometer's specific
force, at the logger's real timestamps (irregular before the release, ~250 us in flight).

The columns are found by the names in a header line, as :mod:`tumble.io.gyrocolumns` finds a
gyroscope's, compared in lower case with spaces, ``_``, ``-`` and ``.`` alike, each with its
unit in brackets or parentheses at its end:

- **time** and the **rates** ``wx, wy, wz``: the names and units of :mod:`tumble.io.gyrocolumns`
  (time in s, ms, us or ns; rates in rad/s, deg/s, rpm, rev/s or Hz);
- **rotor**: ``rotor``, ``rotor speed``, ``rotor rate``, ``flywheel``, ``wheel``, ``wheel speed``,
  ``motor``, ``motor speed``; in rad/s (default), deg/s, rpm, rev/s or Hz;
- **specific force** along ``x`` (``y``, ``z`` alike): ``ax``, ``acc x``, ``accel x``,
  ``accelerometer x``, ``acceleration x``, ``specific force x``, ``f x``; in m/s^2 (default) or
  g (standard gravity, 9.80665 m/s^2), mg. A phone's "linear acceleration" (gravity taken out
  by a filter) is not the specific force and is not read. The three are optional together: a
  throw without them has no accelerometer (``accel`` None);
- other columns are ignored.

A file without a header has eight numeric columns in the order above. Separated by commas,
semicolons (with a decimal comma), tabs or spaces; lines starting with ``#`` and blank lines are
skipped; the times must increase. Every error is one line naming the file and the line.
:func:`write_throw` writes a throw back in this format.

A flight controller's own log, a Betaflight blackbox CSV (``blackbox_decode``, Blackbox
Explorer), is recognised by its ``gyroADC[0]`` column and read by :mod:`tumble.io.blackbox` from
the same entry points (:func:`load_throw`, :func:`read_throw`, :func:`parse_throw_csv`), in the
log's integer units turned into SI and into the sensor frame with the device's motor, gyroscope
and mounting keys (:class:`~tumble.analysis.tensor.Device`).
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..analysis.tensor import Device, Throw
from .atomic import atomic_write_text
from .examples import _read_input
from .gyrocolumns import (ACCEL_UNITS, RATE_PREFIXES, RATE_UNITS, TIME_NAMES, TIME_UNITS, _factor, _name, match_accel,
                          match_header)
from .keys import FileFormat, Key, Table
from ._delimited import _NUMBER, CutLogWarning, _check_order, _first_lines, _refuse_cell, _rows, _split, _without_a_cut_last_line
from .throwread import ThrowRead

__all__ = ["ACCEL_UNITS", "COMPACT_HEADER", "COMPACT_PLACES", "CutLogWarning", "MAX_THROW_FILE_BYTES", "THROW_FORMAT", "THROW_HEADER",
           "ThrowRead", "is_rotor_column", "load_throw", "parse_throw_csv", "read_throw", "throw_csv", "write_throw"]

#: The largest throw file read, bytes (a minute at 4 kHz is about 25 MB of text).
MAX_THROW_FILE_BYTES = 64 << 20


#: The header :func:`write_throw` writes.
THROW_HEADER = ("t (s)", "wx (rad/s)", "wy (rad/s)", "wz (rad/s)", "rotor (rad/s)", "ax (m/s^2)", "ay (m/s^2)",
                "az (m/s^2)")

#: The header of the compact form (:func:`throw_csv` with ``compact=True``): the time in whole microseconds.
COMPACT_HEADER = ("t (us)", *THROW_HEADER[1:])
#: The compact form's decimal places of the rates and the rotor (rad/s) and of the specific force
#: (m/s^2): finer than a 16-bit logger's steps (1.1e-3 rad/s at 2000 deg/s full scale, 4.8e-3
#: m/s^2 at 16 g), so that rounding to them changes a logged sample by less than a tenth of a step.
COMPACT_PLACES = {"rate": 4, "rotor": 2, "accel": 3}

_ACCEL_NAMES = "a{0}, acc {0}, accel {0}, accelerometer {0}, acceleration {0}, specific force {0}, f {0}"
#: The columns of a throw file, as the page docs/formats/throw.md lists them.
THROW_FORMAT = FileFormat("throw", (
    Table("header columns", (
        Key("t", "numbers, increasing", ", ".join(TIME_UNITS), "s", required=True, choices=TIME_NAMES,
            example='"t (s)"', doc="the logger's sample times; the unit in brackets after the name"),
        *(Key(f"w{axis}", "numbers", ", ".join(u for u in RATE_UNITS if u.isascii()), "rad/s", required=True,
              allowed=f"{axis} alone or after {', '.join(RATE_PREFIXES)}; then ' axis' optionally",
              example=f'"w{axis} (rad/s)"',
              doc=f"the gyroscope's angular velocity about the sensor frame's {axis} axis")
          for axis in "xyz"),
        Key("rotor", "numbers", ", ".join(u for u in RATE_UNITS if u.isascii()), "rad/s", required=True,
            allowed="rotor, flywheel, wheel or motor; then speed, rate, omega or angular velocity optionally",
            example='"rotor (rpm)"',
            doc="the rotor's speed relative to the device, positive about the device file's rotor_axis"),
        *(Key(f"a{axis}", "numbers", ", ".join(u for u in ACCEL_UNITS if u.isascii()), "m/s^2",
              allowed=_ACCEL_NAMES.format(axis) + "; all three or none", example=f'"a{axis} (m/s^2)"',
              doc=f"the accelerometer's specific force along the sensor frame's {axis} axis (gravity included); "
                  "without the three, no centre of mass")
          for axis in "xyz"),
        Key("other", "anything", allowed="any other name (a phone's linear acceleration, a temperature, ...)",
            example='"temperature (C)"', doc="ignored, and listed in tensor.json's \"read\""),
    ), "A header line names the columns: a name and, in brackets or parentheses at its end, a unit. "
       "Names are compared in lower case with spaces, ``_``, ``-`` and ``.`` alike; the columns may come "
       "in any order."),
    Table("without a header", (
        Key("column 1", "numbers, increasing", "s", required=True, example="0.000212", doc="the time"),
        Key("columns 2-4", "numbers", "rad/s", required=True, example="0.0053, -0.0085, 0.0032", doc="wx, wy, wz"),
        Key("column 5", "numbers", "rad/s", required=True, example="1301.25", doc="the rotor's speed"),
        Key("columns 6-8", "numbers", "m/s^2", required=True, example="-8.61, -9.96, 11.305", doc="ax, ay, az"),
    ), "Eight numeric columns in this order, in SI, separated by commas, semicolons, tabs or spaces."),
), "A throw of the device of ``tumble calibrate`` and ``tumble tensor``: delimited text, one row a sample, "
   "in the device's sensor frame; :func:`tumble.io.throwfile.read_throw` reads it and "
   ":func:`tumble.io.throwfile.write_throw` writes it.")

_ROTOR = re.compile(r"^(?:rotor|flywheel|wheel|motor)(?: (?:speed|rate|omega|angular velocity))?$")


def is_rotor_column(cell: str) -> bool:
    """Whether a header cell names a throw's rotor column (its unit aside): what a throw of the
    flywheel device has and a phone's gyroscope recording has not.

    Examples
    --------
    >>> from tumble.io.throwfile import is_rotor_column
    >>> is_rotor_column("Rotor speed (rpm)"), is_rotor_column("flywheel"), is_rotor_column("wx (rad/s)")
    (True, True, False)
    """
    return bool(_ROTOR.match(_name(cell)[0]))


_ALLOWED = ("rotor: rotor, rotor speed, flywheel, wheel, motor (rad/s, deg/s, rpm, rev/s, Hz); specific force: "
            "ax, acc_x, accel x, accelerometer x, specific force x (m/s^2, g, mg), y and z alike")


def _match(head: list[str], label: str, line: int) -> tuple[list[int], list[float], list[str]]:
    """The columns of time, rates, rotor (and specific force), their factors to SI and units."""
    columns, scale, names = match_header(head, label, line)
    units = [names["time_unit"], *names["rate_units"]]
    shown = ", ".join(head)
    shown = shown if len(shown) <= 160 else shown[:157] + "..."
    parsed = [_name(cell) for cell in head]
    rotor = [j for j, (n, _) in enumerate(parsed) if j not in columns and _ROTOR.match(n)]
    if len(rotor) != 1:
        what = "no rotor column" if not rotor else \
            f"{len(rotor)} rotor columns ({', '.join(repr(head[j]) for j in rotor)}); keep one"
        hint = " (a gyroscope recording without a flywheel is fitted with 'tumble fit')" if not rotor else ""
        raise ValueError(f"{label}, line {line}: header {shown!r} has {what}{hint}; allowed: {_ALLOWED}")
    f, u = _factor(head[rotor[0]], parsed[rotor[0]][1], RATE_UNITS, label, line, rotor[0] + 1)
    columns.append(rotor[0]), scale.append(f), units.append(u)
    more, factors, accel_units = match_accel(head, columns, label, line, _ALLOWED)
    return columns + more, scale + factors, units + accel_units


def parse_throw_csv(raw: bytes, label: str, device: Device | None = None
                    ) -> tuple[dict[str, np.ndarray | None], ThrowRead]:
    """The samples of a throw file already read (``label`` names it), in SI, and what was read.

    Parameters
    ----------
    raw : bytes
        The file's contents.
    label : str
        The file, for messages.
    device : Device, optional
        How a blackbox CSV is read (:func:`tumble.io.blackbox.parse_blackbox_csv`, which takes
        a file with a ``gyroADC[0]`` column): its motor, gyroscope and mounting; a throw file
        in the sensor frame does not need it.

    Returns
    -------
    samples : dict
        ``t`` (n,) s, ``omega`` (n, 3) rad/s, ``rotor`` (n,) rad/s, ``accel`` (n, 3) m/s^2 or None.
    read : ThrowRead

    Raises
    ------
    ValueError
        One line naming the file and the line (module docstring).

    Examples
    --------
    >>> from tumble.io.throwfile import parse_throw_csv
    >>> raw = b"time (ms), gyro x [deg/s], gyro y [deg/s], gyro z [deg/s], rotor (rpm), ax (g), ay (g), az (g)\\n" \\
    ...       b"0, 180, 0, 0, 0, 0, 0, 1\\n0.25, 180, 0, 90, 60, 0, 0, 0\\n"
    >>> samples, read = parse_throw_csv(raw, "a1.csv")
    >>> samples["t"].tolist(), samples["omega"][1].round(6).tolist(), samples["rotor"].round(6).tolist()
    ([0.0, 0.00025], [3.141593, 0.0, 1.570796], [0.0, 6.283185])
    >>> samples["accel"][0].tolist()   # 1 g on z, in m/s^2
    [0.0, 0.0, 9.80665]
    >>> parse_throw_csv(b"t, wx, wy, wz, ax, ay, az\\n0, 1, 2, 3, 0, 0, 0\\n", "a1.csv")   # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: a1.csv, line 1: header 't, wx, wy, wz, ax, ay, az' has no rotor column (a gyroscope recording without a flywheel is fitted with 'tumble fit'); allowed: rotor: rotor, rotor speed, ...
    """
    from .blackbox import looks_like_blackbox, parse_blackbox_csv  # it builds a ThrowRead: imported here

    if looks_like_blackbox(raw):
        return parse_blackbox_csv(raw, label, device)
    lines, sep, head = _first_lines(raw, label, "columns t, wx, wy, wz, rotor, ax, ay, az")
    first_no = lines[0][0]
    if not all(_NUMBER.match(c) for c in head):  # a header line
        columns, scale, units = _match(head, label, first_no)
        names = [head[j] for j in columns]
        ignored = tuple(h for j, h in enumerate(head) if j not in columns)
        width = len(head)
        lines = lines[1:]
    elif len(head) == 8:
        columns, scale = list(range(8)), [1.0] * 8
        names = [f"column {j + 1}" for j in range(8)]
        units = ["s", "rad/s", "rad/s", "rad/s", "rad/s", "m/s^2", "m/s^2", "m/s^2"]
        ignored, width = (), 8
    else:
        raise ValueError(f"{label}, line {first_no}: {len(head)} columns; expected 8 (t, wx, wy, wz, rotor, ax, ay, "
                         "az) or a header line naming the columns")
    lines = _without_a_cut_last_line(lines, sep, width, label)
    rows = _rows(lines, sep, columns, width, label)
    if len(rows) < 2:
        raise ValueError(f"{label}: {len(rows)} data rows; a throw needs many samples")
    # a logger's nan or inf, said where the file has it (not as a sample index); a header's cell names its unit
    _refuse_cell(~np.isfinite(rows), rows, lines, columns, names, label,
                 lambda k, j: "is not a finite number" + ("" if units[j] in names[j] else f" ({units[j]})"))
    rows *= np.array(scale)
    t = rows[:, 0].copy()
    _check_order(t, lines, label)
    samples = {"t": t, "omega": rows[:, 1:4].copy(), "rotor": rows[:, 4].copy(),
               "accel": rows[:, 5:8].copy() if len(columns) == 8 else None, "line": [no for no, _ in lines]}
    return samples, ThrowRead(label, tuple(names), tuple(units), ignored, len(t))


def load_throw(path: str | os.PathLike[str], device: Device | None = None) -> tuple[Throw, ThrowRead]:
    """:func:`read_throw`, and what was read (:class:`ThrowRead`).

    Parameters
    ----------
    path : str or os.PathLike
        A throw file, or a Betaflight blackbox CSV (:mod:`tumble.io.blackbox`).
    device : Device, optional
        The device whose log it is: how a blackbox CSV is read (its ``motor_poles``,
        ``motor_index``, ``gyro_full_scale``, ``gyro_resolution``, ``sensor_axes``; their
        defaults without it). A throw file in the sensor frame does not need it.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from tumble.io.throwfile import load_throw
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "a1.csv")
    ...     rows = "".join(f"{k * 2.5e-4:.4f},1,2,3,{100 * k},0,0,0,21.5\\n" for k in range(50))
    ...     _ = path.write_text("t (s),wx,wy,wz,rotor,ax,ay,az,temperature\\n" + rows)
    ...     throw, read = load_throw(path)
    >>> throw.omega.shape, read.brief()
    ((50, 3), 't (s), wx, wy, wz (rad/s), rotor (rad/s), ax, ay, az (m/s^2), 1 ignored, 50 rows')
    """
    label = os.fspath(path)
    if label.lower().endswith(".toml"):  # it read "header 'body, =, t-handle' has no time column" (a QA walkthrough)
        raise ValueError(f"{label}: a TOML file (a scenario, body or device file), not a throw's log: 'tumble tensor' "
                         "and 'tumble calibrate' read each throw's CSV; the device file goes with --device")
    raw = _read_input(path, limit=MAX_THROW_FILE_BYTES, what="a throw file (CSV)")  # "no such file" hints at examples/
    samples, read = parse_throw_csv(raw, label, device)
    try:
        throw = Throw(t=samples["t"], omega=samples["omega"], rotor=samples["rotor"], accel=samples["accel"],
                      input=label)
    except ValueError as exc:  # "throw A1.csv omega ...": said as the file's, a sample's index with its line
        message = str(exc).removeprefix(f"throw {label} ").removeprefix("throw ")
        at = re.match(r"(t|omega|rotor|accel)\[(\d+)\]", message)
        where = f", line {samples['line'][int(at.group(2))]}" if at and samples.get("line") is not None else ""
        raise ValueError(f"{label}{where}: {message}") from None
    return throw, read


def read_throw(path: str | os.PathLike[str], device: Device | None = None) -> Throw:
    """A throw file (module docstring) as a :class:`~tumble.analysis.tensor.Throw` whose ``input``
    is the path as given.

    Parameters
    ----------
    path : str or os.PathLike
        The file: a throw file, or a Betaflight blackbox CSV (:mod:`tumble.io.blackbox`).
    device : Device, optional
        How a blackbox CSV is read (:func:`load_throw`).

    Raises
    ------
    ValueError
        One line naming the file and the line: not a readable regular file, larger than
        :data:`MAX_THROW_FILE_BYTES`, not text, a header without a column needed (or with two),
        an unknown unit, a value that is not a number, a time that repeats or goes back; or what
        :class:`~tumble.analysis.tensor.Throw` refuses, after the file's name.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from tumble.io.throwfile import read_throw
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "a1.csv")   # no header: t, wx, wy, wz, rotor, ax, ay, az in SI
    ...     _ = path.write_text("".join(f"{k * 2.5e-4:.5f} 1 2 3 {100 * k} 0 0 9.8\\n" for k in range(40)))
    ...     throw = read_throw(path)
    >>> float(throw.t[-1]), float(throw.rotor[-1]), throw.input.endswith("a1.csv")
    (0.00975, 3900.0, True)
    """
    return load_throw(path, device)[0]


def _fixed(x: float, places: int) -> str:
    """``x`` with ``places`` decimals, trailing zeros dropped (``"-0"`` written ``"0"``)."""
    text = f"{x:.{places}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def throw_csv(throw: Throw, *, header: str = "", compact: bool = False) -> str:
    """The text of a throw file: :data:`THROW_HEADER` and a row a sample, in SI.

    Times with 12 significant digits (10 ns at 1000 s, 1 us after a day), the rest with 7 (a
    logger's 16-bit samples have fewer). Without an accelerometer the last three columns are left
    out.

    The **compact** form (``compact=True``, about a third smaller) writes what a logger records
    and no more: the time in whole microseconds (:data:`COMPACT_HEADER`, as a flight controller
    stamps its samples) and the values to fixed decimals (:data:`COMPACT_PLACES`: 1e-4 rad/s,
    0.01 rad/s for the rotor, 1e-3 m/s^2), trailing zeros dropped. Every reader of a throw file
    reads it, by its header.

    Parameters
    ----------
    throw : Throw
    header : str
        Comment lines put first (each prefixed with ``#`` and a space).
    compact : bool
        Write the compact form.

    Examples
    --------
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Throw
    >>> from tumble.io.throwfile import throw_csv
    >>> t = np.arange(20) * 2.5e-4
    >>> throw = Throw(t=t, omega=np.tile([1.0, -2.0, 3.0], (20, 1)), rotor=10 * np.arange(20.0), accel=None)
    >>> print("\\n".join(throw_csv(throw, header="no accelerometer").splitlines()[:5]))
    # no accelerometer
    t (s),wx (rad/s),wy (rad/s),wz (rad/s),rotor (rad/s)
    0,1,-2,3,0
    0.00025,1,-2,3,10
    0.0005,1,-2,3,20

    The compact form of a sample of a tumbling device:

    >>> throw = Throw(t=0.5 + t, omega=np.tile([0.00532632, -12.3456789, 3.0], (20, 1)), rotor=np.full(20, 1301.25731),
    ...               accel=np.tile([-8.6095493, 0.0, 9.80665], (20, 1)))
    >>> throw_csv(throw, compact=True).splitlines()[:3]
    ['t (us),wx (rad/s),wy (rad/s),wz (rad/s),rotor (rad/s),ax (m/s^2),ay (m/s^2),az (m/s^2)', '500000,0.0053,-12.3457,3,1301.26,-8.61,0,9.807', '500250,0.0053,-12.3457,3,1301.26,-8.61,0,9.807']
    """
    columns = [throw.t[:, None], throw.omega, throw.rotor[:, None]]
    names = COMPACT_HEADER if compact else THROW_HEADER
    if throw.accel is not None:
        columns.append(throw.accel)
    else:
        names = names[:5]
    data = np.hstack([np.asarray(c, float) for c in columns])
    lines = [f"# {line}".rstrip() for line in header.splitlines()] + [",".join(names)]
    if compact:
        places = [COMPACT_PLACES["rate"]] * 3 + [COMPACT_PLACES["rotor"]] + [COMPACT_PLACES["accel"]] * 3
        micro = np.rint(data[:, 0] * 1e6)
        lines += [f"{us:.0f}," + ",".join(_fixed(x, k) for x, k in zip(row[1:], places))
                  for us, row in zip(micro, data)]
    else:
        lines += [f"{row[0]:.12g}," + ",".join(f"{x:.7g}" for x in row[1:]) for row in data]
    return "\n".join(lines) + "\n"


def write_throw(path: str | os.PathLike[str], throw: Throw, *, header: str = "", compact: bool = False) -> Path:
    """Write a throw file (:func:`throw_csv`) whole or not at all (:mod:`tumble.io.atomic`).

    Parameters
    ----------
    path : str or os.PathLike
        The file to write (its folder is created).
    throw : Throw
        The samples: a logger's, or a synthetic throw's
        (:func:`tumble.analysis.tensor.synthetic.synthetic_throw`).
    header : str
        Comment lines put first (each prefixed with ``#`` and a space): what the throw is.
    compact : bool
        The compact form (:func:`throw_csv`): whole microseconds and fixed decimals.

    Returns
    -------
    pathlib.Path
        ``path``.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> from tumble.analysis.tensor import Throw
    >>> from tumble.io.throwfile import read_throw, write_throw
    >>> t = np.arange(40) * 2.5e-4
    >>> throw = Throw(t=t, omega=np.tile([1.0, -2.0, 3.0], (40, 1)), rotor=100 * np.arange(40.0),
    ...               accel=np.zeros((40, 3)))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     again = read_throw(write_throw(pathlib.Path(folder, "a1.csv"), throw))
    >>> float(np.max(np.abs(again.t - throw.t))) < 1e-15, bool(np.array_equal(again.rotor, throw.rotor))   # to 12 digits
    (True, True)

    A synthetic throw of the example device with a box strapped to it, made to try ``tumble
    tensor`` (docs/tensor.md), in the compact form:

    >>> from tumble.analysis.tensor.synthetic import box, combine, synthetic_throw, true_device
    >>> bracket = box(0.482, (0.16, 0.09, 0.04), center=(0.012, -0.008, 0.035), rotvec=(0.2, -0.1, 0.35))
    >>> throw = synthetic_throw(21, combine(true_device(), bracket))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_throw(pathlib.Path(folder, "o1.csv"), throw, header="synthetic", compact=True)
    ...     again = read_throw(path)
    >>> bool(np.abs(again.t - throw.t).max() <= 0.5e-6), bool(np.abs(again.omega - throw.omega).max() <= 0.5e-4)
    (True, True)
    """
    return atomic_write_text(path, throw_csv(throw, header=header, compact=compact))
