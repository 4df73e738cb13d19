"""A Betaflight flight controller's own log (its blackbox, as CSV) read as a throw.

The device of ``tumble calibrate`` and ``tumble tensor`` is a flight controller with a motor
spinning a flywheel (Blaha, Kuijper, Pop & Smeur, arXiv:2503.13137). Betaflight logs it to its
blackbox; ``blackbox_decode`` (betaflight/blackbox-tools) and Blackbox Explorer's "Export CSV"
(betaflight/blackbox-log-viewer) turn the log into CSV, which this module reads in the logged
integer units (no ``--unit-rotation`` or ``--unit-acceleration``) and turns into a throw in SI,
in the device's sensor frame (:class:`~tumble.analysis.tensor.Throw`). The columns, by their
names in the header line (``blackbox_decode`` writes it first; Blackbox Explorer after a block of
``"key",value`` lines of the log's header, which are skipped):

- ``time (us)`` (Blackbox Explorer: ``time``, in us; ``blackbox_decode --unit-frame-time``:
  ``time (ms)``, ``time (s)``): the sample times, increasing;
- ``gyroADC[0]``, ``gyroADC[1]``, ``gyroADC[2]``: the gyroscope, in counts of
  :attr:`Device.gyro_lsb <tumble.analysis.tensor.Device.gyro_lsb>` deg/s: by default the sensor's
  16-bit LSB, ``gyro_full_scale / 32768`` (2000 deg/s full scale: 0.061 deg/s), as Cleanflight and
  early Betaflight logged it. **Current Betaflight logs the filtered rate in whole deg/s**
  (``gyroADC = lrintf(gyro.gyroADCf * blackboxHighResolutionScale)``, the scale 10 with
  ``blackbox_high_resolution`` and 1 without, the header's ``gyro_scale`` 1.0;
  betaflight/betaflight, src/main/blackbox/blackbox.c, ``loadMainState``): give
  ``gyro_resolution = 1.0`` (0.1) in the device file for such logs. A count beyond the full scale (``|count| * gyro_lsb >
  gyro_full_scale``) is refused;
- ``accSmooth[0]``, ``accSmooth[1]``, ``accSmooth[2]`` (optional, all three or none): the
  accelerometer's specific force, the log's own ``acc_1G`` counts per g where its header block
  states it (:func:`acc_counts_per_g`), else :data:`ACC_COUNTS_PER_G` (Betaflight's ``acc_1G``
  at +-16 g; g the standard gravity, 9.80665 m/s^2);
- ``eRPM[0]`` (``eRPM[k]`` with ``motor_index = k`` in the device file): the motor's electrical
  speed from its bidirectional DShot telemetry, **logged divided by** :data:`ERPM_PER_COUNT`
  (100): Betaflight's field definition says ``// eRPM / 100`` and logs ``getDshotErpm()``,
  which returns the telemetry's ``eRPM * 100`` period conversion ``(1000000 * 60 / 100) /
  period_us`` (betaflight/betaflight, src/main/blackbox/blackbox.c and
  src/main/drivers/dshot.c, ``ERPM_PER_LSB 100.0f``, where ``erpmToRpm`` is ``erpm *
  ERPM_PER_LSB / (motorPoleCount / 2)``). The rotor's speed, rad/s, is
  ``count * 100 / (motor_poles / 2) * 2 pi / 60``: mechanical rev/min are eRPM over the pole
  pairs. The speed is unsigned: positive about the device's ``rotor_axis``;
- every other column (``loopIteration``, ``axisP[0]``, ``rcCommand[0]``, ``motor[0]``,
  ``debug[0]``, ``gyroUnfilt[0]``, the other motors' ``eRPM`` ...) is ignored.

The gyroscope and accelerometer vectors are turned from the log's axes into the sensor frame
with the device's ``sensor_axes`` (the board's mounting,
:func:`~tumble.analysis.tensor.device.axes_matrix`): ``v = R v_log``.

Bad input is one line naming the file, the line and the column and what is allowed: a header
without the rotor's ``eRPM`` column or the gyroscope's, a value that is not a finite number, a
count that is not whole, beyond its integer range (the gyroscope's full scale, the
accelerometer's 16 bits, the eRPM's unsigned 16 bits), a time that does not increase.
"""

from __future__ import annotations

import math
import re
import warnings
from dataclasses import fields
from typing import Any

import numpy as np

from ..analysis.tensor import Device
from ..dynamics.environment.earth import STANDARD_GRAVITY
from ..typing import BoolArray, Matrix3
from .keys import FileFormat, Key, Table
from ._delimited import _check_order, _data_lines, _rows, _separator, _split, _without_a_cut_last_line
from .throwread import ThrowRead

__all__ = ["ACC_COUNTS_PER_G", "BLACKBOX_FORMAT", "ERPM_PER_COUNT", "GyroResolutionWarning", "SLOWEST_THROW",
           "acc_counts_per_g", "looks_like_blackbox", "parse_blackbox_csv"]

#: Betaflight logs the motor's electrical speed (eRPM) divided by this: a count of ``eRPM[k]``
#: is 100 eRPM (src/main/blackbox/blackbox.c: ``// eRPM / 100``; src/main/drivers/dshot.c:
#: ``#define ERPM_PER_LSB 100.0f``).
ERPM_PER_COUNT = 100.0
#: Counts of ``accSmooth`` per g (standard gravity): Betaflight's ``acc_1G`` with the sensor at
#: +-16 g (2^15 / 16), which its log's header states.
ACC_COUNTS_PER_G = 2048.0
#: The signed 16-bit range of a sensor's count.
_INT16 = 32768.0
#: The unsigned 16-bit range of an eRPM count.
_UINT16 = 65535.0
#: The header's bytes searched for a blackbox column (Blackbox Explorer's header block is ~10 kB).
_SNIFF_BYTES = 1 << 18
_TIME = re.compile(r"^time(?:\s*\(\s*(us|ms|s)\s*\))?$", re.IGNORECASE)
#: Per second, the time units: divided by, so that 1000250 us is the double nearest 1.00025 s.
_PER_SECOND = {"us": 1e6, "ms": 1e3, "s": 1.0}
_UNIT_SUFFIX = re.compile(r"^(gyroadc|accsmooth|erpm)\[\d\]\s*\(.*\)$", re.IGNORECASE)

#: The columns of a blackbox CSV, as the page docs/formats/blackbox.md lists them.
BLACKBOX_FORMAT = FileFormat("blackbox", (
    Table("header columns", (
        Key("time (us)", "whole numbers, increasing", "us", required=True, example="35012345",
            allowed="time (us), time (ms) or time (s) (blackbox_decode); time (Blackbox Explorer, us)",
            doc="the flight controller's clock"),
        *(Key(f"gyroADC[{k}]", "whole numbers", "counts", required=True,
              allowed="|count| * gyro_lsb <= gyro_full_scale", example="1250",
              doc=f"the gyroscope about the log's {axis} axis: counts of gyro_resolution deg/s (default "
                  "gyro_full_scale / 32768)")
          for k, axis in enumerate("xyz")),
        *(Key(f"accSmooth[{k}]", "whole numbers", "counts", allowed="-32768 to 32768; all three or none",
              example="-2048", doc=f"the accelerometer along the log's {axis} axis: 2048 counts per g")
          for k, axis in enumerate("xyz")),
        Key("eRPM[0]", "whole numbers", "100 eRPM", required=True, allowed="0 to 65535", example="1003",
            doc="the rotor's motor's electrical speed / 100; eRPM[motor_index] with motor_index in the device file"),
        Key("other", "anything", example="loopIteration, axisP[0], motor[0], debug[0]", doc="ignored"),
    ), "The header line names the columns (Blackbox Explorer's ``\"key\",value`` lines before it are skipped); "
       "the values are the log's integers, as ``blackbox_decode`` writes them without ``--unit-rotation``."),
), "A Betaflight blackbox log as CSV (``blackbox_decode``, Blackbox Explorer): a throw of the device of "
   "``tumble calibrate`` and ``tumble tensor``, read with the device file's motor, gyroscope and mounting keys.")

_DEFAULTS: dict[str, Any] = {f.name: f.default for f in fields(Device)}


def looks_like_blackbox(raw: bytes) -> bool:
    """Whether a file's bytes are a blackbox CSV: a ``gyroADC[0]`` column in its first 256 kB.

    Examples
    --------
    >>> from tumble.io.blackbox import looks_like_blackbox
    >>> looks_like_blackbox(b"loopIteration, time (us), gyroADC[0], gyroADC[1], gyroADC[2], eRPM[0]\\n")
    True
    >>> looks_like_blackbox(b"t (s), wx, wy, wz, rotor\\n")
    False
    """
    return b"gyroadc[0]" in raw[:_SNIFF_BYTES].lower()


def _reading(device: Device | None) -> tuple[int, int, float, float, Matrix3, tuple[str, ...]]:
    """The device's motor poles, motor index, gyroscope full scale and count (deg/s), rotation and axes
    (the defaults of :class:`~tumble.analysis.tensor.Device` without one)."""
    if device is None:
        d = _DEFAULTS
        full = float(d["gyro_full_scale"])
        return int(d["motor_poles"]), int(d["motor_index"]), full, full / _INT16, np.eye(3), tuple(d["sensor_axes"])
    return (device.motor_poles, device.motor_index, device.gyro_full_scale, device.gyro_lsb, device.sensor_rotation,
            device.sensor_axes)


_ACC_1G = re.compile(r'^\s*"?acc_1G"?\s*,\s*"?\s*([0-9.eE+-]+)\s*"?\s*$', re.IGNORECASE)


def acc_counts_per_g(lines: list[tuple[int, str]], k0: int, label: str) -> float:
    """The accelerometer's counts per g: the log's own ``acc_1G`` (Blackbox Explorer writes the log's
    header fields before the column names, ``"acc_1G",2048``), else :data:`ACC_COUNTS_PER_G`. An
    accelerometer at +-8 g logs 4096 counts per g; read at 2048 its specific force came out twice
    too large and every throw was refused as no body's (a walkthrough, 2026-12-03).

    Examples
    --------
    >>> from tumble.io.blackbox import acc_counts_per_g
    >>> acc_counts_per_g([(1, '"looptime",125'), (2, '"acc_1G",4096'), (3, "time, gyroADC[0]")], 2, "b.csv")
    4096.0
    >>> acc_counts_per_g([(1, "time (us), gyroADC[0]")], 0, "b.csv")
    2048.0
    """
    for no, line in lines[:k0]:
        match = _ACC_1G.match(line)
        if match:
            value = float(match.group(1))
            if not (math.isfinite(value) and 100.0 <= value <= 100_000.0):
                raise ValueError(f"{label}, line {no}: acc_1G = {match.group(1)} is not an accelerometer's counts per g; "
                                 "allowed: 100 to 100000 (Betaflight logs 2048 at +-16 g, 4096 at +-8 g)")
            return value
    return ACC_COUNTS_PER_G


def _header(lines: list[tuple[int, str]], label: str) -> int:
    """The index of the header line: the first naming ``gyroADC[0]``."""
    for k, (_, line) in enumerate(lines):
        if "gyroadc[0]" in line.lower():
            return k
    raise ValueError(f"{label}: no header line naming gyroADC[0]; a blackbox CSV (blackbox_decode, Blackbox Explorer) "
                     "names its columns loopIteration, time (us), ..., gyroADC[0], ...")


def _columns(head: list[str], label: str, line: int, motor: int) -> tuple[list[int], float, str, bool]:
    """The header's time, gyroADC[0..2], eRPM[motor] (and accSmooth[0..2]) columns, the time's unit
    per s and unit, and whether the accelerometer is there."""
    lower = [c.lower() for c in head]
    shown = ", ".join(head)
    shown = shown if len(shown) <= 160 else shown[:157] + "..."
    for j, cell in enumerate(head):
        if _UNIT_SUFFIX.match(cell):
            raise ValueError(f"{label}, line {line}, column {j + 1}: {cell!r} is converted to a unit; a blackbox CSV "
                             "is read in the log's counts (blackbox_decode without --unit-rotation and "
                             "--unit-acceleration), the units from the device file")
    times = [j for j, c in enumerate(head) if _TIME.match(c)]
    if len(times) != 1:
        what = "no time column" if not times else f"{len(times)} time columns"
        raise ValueError(f"{label}, line {line}: header {shown!r} has {what}; allowed: time (us), time (ms), time (s), "
                         "time (Blackbox Explorer, us)")
    match = _TIME.match(head[times[0]])
    unit = ((match.group(1) if match else None) or "us").lower()

    def find(name: str) -> int | None:
        return lower.index(name.lower()) if name.lower() in lower else None

    gyro = [find(f"gyroADC[{k}]") for k in range(3)]
    if None in gyro:
        k = gyro.index(None)
        raise ValueError(f"{label}, line {line}: header {shown!r} has no gyroADC[{k}] column; a blackbox CSV needs "
                         "gyroADC[0], gyroADC[1], gyroADC[2]")
    rotor = find(f"eRPM[{motor}]")
    if rotor is None:
        others = [c for c in head if re.match(r"^erpm\[\d\]$", c, re.IGNORECASE)]
        has = f"; it has {', '.join(others)}: name the rotor's motor with motor_index in the device file" if others \
            else "; log the motors' speed (bidirectional DShot telemetry, dshot_bidir = ON)"
        raise ValueError(f"{label}, line {line}: header {shown!r} has no eRPM[{motor}] column (the rotor's speed, "
                         f"motor_index = {motor}){has}")
    acc = [find(f"accSmooth[{k}]") for k in range(3)]
    if any(a is not None for a in acc) and None in acc:
        k = acc.index(None)
        raise ValueError(f"{label}, line {line}: header {shown!r} has no accSmooth[{k}] column; allowed: "
                         "accSmooth[0], accSmooth[1], accSmooth[2] together, or none (no accelerometer)")
    columns = [times[0], *(g for g in gyro if g is not None), rotor] + [a for a in acc if a is not None]
    return columns, _PER_SECOND[unit], unit, acc[0] is not None


def _refuse_first(bad: BoolArray, lines: list[tuple[int, str]], sep: str | None, head: list[str], columns: list[int],
                  label: str, rule: str) -> None:
    """One line for the first ``bad`` entry of the ``(n, m)`` values (their columns ``columns`` of the
    data lines): its line, column, name and the value as written."""
    if not bad.any():
        return
    k, i = (int(x) for x in np.argwhere(bad)[0])
    no, line = lines[k]
    cell = _split(line, sep)[columns[i]]
    raise ValueError(f"{label}, line {no}, column {columns[i] + 1}: {head[columns[i]]} = {cell[:40]} {rule}")


#: Fewest counts (x 100 eRPM) the rotor's motor reaches in a throw: below, it never turned.
TURNING_COUNTS = 5


def _other_motor(counts: np.ndarray, lines: list[tuple[int, str]], sep: str | None, head: list[str], rotor: int,
                 label: str, motor: int) -> None:
    """Refuse a log whose ``eRPM[motor]`` never turns while another motor's does: Betaflight logs every
    motor's eRPM, so the column is there and stays 0 with the flywheel on another motor (a walkthrough,
    2026-12-03: "the rotor did not spin up", with eRPM[2] at 900 counts and no word of motor_index)."""
    if counts.size == 0 or float(counts.max()) >= TURNING_COUNTS:
        return
    others = [j for j, c in enumerate(head) if re.match(r"^erpm\[\d\]$", c, re.IGNORECASE) and j != rotor]
    if not others:
        return
    tops = _rows(lines, sep, others, len(head), label, head=head, decimal_comma=False, expected=" as the header").max(axis=0)
    turning = [(head[j], float(top)) for j, top in zip(others, tops) if top >= TURNING_COUNTS]
    if turning:
        name, top = max(turning, key=lambda item: item[1])
        raise ValueError(f"{label}: eRPM[{motor}] (the rotor's, motor_index = {motor}) never turns while {name} reaches "
                         f"{top:.0f} counts ({100 * top:.0f} eRPM): the flywheel on that motor? Set motor_index = "
                         f"{name[5:-1]} in the device file")


#: A throw's gyroscope passes this (rad/s) somewhere in its log: the device is thrown spinning at
#: 10-18 rad/s. A log that never does was most likely read at the wrong gyro_resolution.
SLOWEST_THROW = 2.0


class GyroResolutionWarning(UserWarning):
    """A blackbox log whose gyroscope never turns as fast as a throw does at the ``gyro_resolution``
    it was read with (:func:`parse_blackbox_csv`); a command prints it in one line.

    Examples
    --------
    >>> from tumble.io.blackbox import GyroResolutionWarning
    >>> GyroResolutionWarning.cli_one_line
    True
    """

    cli_one_line = True


def _slow_gyroscope(omega: np.ndarray, lsb: float, label: str) -> None:
    """Warn where the log's rates never pass :data:`SLOWEST_THROW`: Betaflight 4.x logs ``gyroADC`` in
    whole deg/s, which read at the sensor's 16-bit counts (the default, 0.061 deg/s) are 16.4 times
    too slow; the fit then failed as "a gyroscope bias of 0.742 rad/s" or "rates in another unit", the
    key never named (a walkthrough, 2026-12-03)."""
    top = float(np.max(np.linalg.norm(omega, axis=1))) if omega.size else 0.0  # |omega|, rad/s
    if top >= SLOWEST_THROW:
        return
    warnings.warn(f"{label}: the gyroscope reads at most {top:.3g} rad/s in the whole log, slower than a throw spins "
                  f"(10 rad/s and more) at gyro_resolution = {lsb:.6g} deg/s per count: a log in whole deg/s "
                  "(Betaflight 4.x's gyroADC) needs gyro_resolution = 1.0 in the device file", GyroResolutionWarning,
                  stacklevel=4)


def parse_blackbox_csv(raw: bytes, label: str, device: Device | None = None
                       ) -> tuple[dict[str, np.ndarray | None], ThrowRead]:
    """The samples of a blackbox CSV already read (``label`` names it), in SI and the sensor
    frame, and what was read (module docstring).

    Parameters
    ----------
    raw : bytes
        The file's contents.
    label : str
        The file, for messages.
    device : Device, optional
        Its ``motor_poles``, ``motor_index``, ``gyro_full_scale``, ``gyro_resolution`` and
        ``sensor_axes``; without it their defaults (14 poles, ``eRPM[0]``, 2000 deg/s in 16-bit
        counts, the log's axes).

    Returns
    -------
    samples : dict
        ``t`` (n,) s, ``omega`` (n, 3) rad/s, ``rotor`` (n,) rad/s, ``accel`` (n, 3) m/s^2 or None.
    read : ThrowRead
        The columns taken, the units they were in, the columns ignored, the axes.

    Raises
    ------
    ValueError
        One line naming the file, the line and the column (module docstring).

    Examples
    --------
    >>> from tumble.analysis.tensor import Device
    >>> from tumble.io.blackbox import parse_blackbox_csv
    >>> raw = (b"loopIteration, time (us), axisP[0], gyroADC[0], gyroADC[1], gyroADC[2], accSmooth[0], "
    ...        b"accSmooth[1], accSmooth[2], motor[0], eRPM[0]\\n"
    ...        b"0, 1000000, 3, 16384, -8192, -32768, 1024, -512, 2048, 1200, 0\\n"
    ...        b"1, 1000250, 2, 16384, -8192, -32768, 1024, -512, 2048, 1250, 1000\\n")
    >>> samples, read = parse_blackbox_csv(raw, "b1.csv", Device(0.1, [0, 0, -1], sensor_axes=["x", "-y", "-z"]))
    >>> samples["t"].tolist(), samples["omega"][0].round(4).tolist()   # 1000, -500, -2000 deg/s; y, z turned
    ([1.0, 1.00025], [17.4533, 8.7266, 34.9066])
    >>> samples["rotor"].round(3).tolist(), samples["accel"][0].tolist()   # 100000 eRPM / 7 pole pairs; 0.5, -0.25, 1 g
    ([0.0, 1495.997], [4.903325, 2.4516625, -9.80665])
    >>> read.brief()
    'time (us), gyroADC[0], gyroADC[1], gyroADC[2] (0.0610352 deg/s), eRPM[0] (100 eRPM, 14 poles), accSmooth[0], accSmooth[1], accSmooth[2] (1/2048 g), sensor axes x, -y, -z, 3 ignored, 2 rows'
    >>> parse_blackbox_csv(raw.replace(b"1000250", b"999999"), "b1.csv")   # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: b1.csv, line 3: time 0.999999 s goes back before the time 1 s of line 2; times must increase
    """
    from ..analysis.fit.single import MAX_TIME

    poles, motor, full_scale, lsb, R, axes = _reading(device)
    lines = _data_lines(raw, label)
    k0 = _header(lines, label)
    header_no, header_line = lines[k0]
    sep = _separator(header_line)
    head = _split(header_line, sep)
    while len(head) > 1 and head[-1] == "":
        head.pop()
    columns, per_second, time_unit, has_acc = _columns(head, label, header_no, motor)
    raw_lines, lines = lines, _without_a_cut_last_line(lines[k0 + 1:], sep, len(head), label)  # a log stopped in flight
    values = _rows(lines, sep, columns, len(head), label, head=head, decimal_comma=False, expected=" as the header")
    if len(values) < 2:
        raise ValueError(f"{label}: {len(values)} data rows after the header; a throw needs many samples")

    def refuse(bad: BoolArray, rule: str, where: slice = slice(None)) -> None:
        """Refuse the first ``bad`` of the values' columns ``where``."""
        full = np.zeros(values.shape, dtype=bool)
        full[:, where] = bad
        _refuse_first(full, lines, sep, head, columns, label, rule)

    refuse(~np.isfinite(values), "is not a finite number; a blackbox log holds whole numbers")
    counts = values.copy()
    if time_unit != "us":
        counts[:, 0] = 0.0  # times in ms or s need not be whole
    refuse(counts != np.round(counts), "is not a whole number; a blackbox CSV is read in the log's counts "
           "(blackbox_decode without unit options)")
    refuse(np.abs(values[:, :1]) / per_second > MAX_TIME, f"is beyond {MAX_TIME:g} s: not a flight controller's "
           "clock", slice(0, 1))
    limit = full_scale / lsb
    refuse(np.abs(values[:, 1:4]) > limit * (1 + 1e-12),
           f"is beyond the gyroscope's full scale; allowed: -{limit:.6g} to {limit:.6g} counts ({full_scale:g} deg/s "
           f"at {lsb:.6g} deg/s per count: gyro_full_scale, gyro_resolution in the device file)", slice(1, 4))
    refuse((values[:, 4:5] < 0) | (values[:, 4:5] > _UINT16), f"is beyond an eRPM count's range; allowed: 0 to "
           f"{_UINT16:.0f} (unsigned 16 bits of eRPM / 100)", slice(4, 5))
    if has_acc:
        refuse(np.abs(values[:, 5:8]) > _INT16, f"is beyond the accelerometer's range; allowed: -{_INT16:.0f} to "
               f"{_INT16:.0f} (16 bits)", slice(5, 8))

    _other_motor(values[:, 4], lines, sep, head, columns[4], label, motor)
    t = values[:, 0] / per_second
    _check_order(t, lines, label)
    take = np.argmax(np.abs(R), axis=1)   # R a signed permutation: v = R v_log exactly, a component each
    sign = R[np.arange(3), take]
    omega = values[:, 1:4][:, take] * (sign * math.radians(lsb))
    rotor = values[:, 4] * (ERPM_PER_COUNT / (poles / 2) * 2.0 * math.pi / 60.0)
    per_g = acc_counts_per_g(raw_lines, k0, label)
    accel = values[:, 5:8][:, take] * (sign * (STANDARD_GRAVITY / per_g)) if has_acc else None
    _slow_gyroscope(omega, lsb, label)
    names = tuple(head[c] for c in columns)
    units = (time_unit, *(f"{lsb:.6g} deg/s",) * 3, f"{ERPM_PER_COUNT:g} eRPM, {poles} poles",
             *(f"1/{per_g:g} g",) * (3 if has_acc else 0))
    ignored = tuple(h for j, h in enumerate(head) if j not in columns)
    read = ThrowRead(label, names, units, ignored, len(t), axes=tuple(axes))
    return {"t": t, "omega": omega, "rotor": rotor, "accel": accel}, read
