"""Write a phyphox export: a gyroscope's record (and an accelerometer's) as phyphox's "CSV"
export writes it, a folder or a ``.zip``, which ``tumble fit`` and
:func:`tumble.io.gyrodata.load_recording` read as they read the app's.

The export of phyphox's "Gyroscope (rotation rate)" experiment holds ``Raw Data.csv`` (the time
and the three rates, and their magnitude) and ``meta/time.csv`` (the START/PAUSE events); an
export with the accelerometer too holds ``Gyroscope.csv`` and ``Accelerometer.csv`` ("Acceleration
(with g)": the specific force and its magnitude) instead of ``Raw Data.csv``, as phyphox names them in an experiment
of several sensors (:mod:`tumble.io.phyphox` reads these). The numbers are written as phyphox
writes them, ``1.234567890E-03``: ten significant digits.

Made for the synthetic recordings of :func:`tumble.analysis.fit.synthetic.synthetic_recording`
(its ``t``, ``omega``, ``events`` and ``accel.f``) and for any record of samples; it formats the
data it is given and computes nothing.
"""

from __future__ import annotations

import io
import os
import zipfile
from collections.abc import Sequence
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from ..typing import ArrayLike
from .atomic import atomic_folder, atomic_write_bytes
from .phyphox import ACCEL_CSV, TIME_CSV

__all__ = ["GYRO_CSV", "MULTI_GYRO_CSV", "phyphox_files", "write_phyphox"]

#: The gyroscope's CSV in the export of phyphox's "Gyroscope (rotation rate)" experiment.
GYRO_CSV = "Raw Data.csv"
#: The gyroscope's CSV in the export of an experiment of several sensors, beside ``Accelerometer.csv``.
MULTI_GYRO_CSV = "Gyroscope.csv"
_GYRO_HEADER = '"Time (s)","Gyroscope x (rad/s)","Gyroscope y (rad/s)","Gyroscope z (rad/s)","Absolute (rad/s)"'
_ACCEL_HEADER = ('"Time (s)","Acceleration x (m/s^2)","Acceleration y (m/s^2)","Acceleration z (m/s^2)",'
                 '"Absolute acceleration (m/s^2)"')
_TIME_HEADER = '"event","experiment time","system time","system time text"'


def _table(header: str, columns: list[np.ndarray]) -> bytes:
    rows = np.column_stack(columns)
    return ("\n".join([header, *(",".join(f"{x:.9E}" for x in row) for row in rows)]) + "\n").encode("utf-8")


def _samples(t: ArrayLike, values: ArrayLike, what: str) -> tuple[np.ndarray, np.ndarray]:
    """``t`` (n,) increasing and ``values`` (n, 3), finite, or a ValueError naming ``what``."""
    t, values = np.asarray(t, float), np.asarray(values, float)
    if t.ndim != 1 or len(t) < 2 or values.shape != (len(t), 3):
        raise ValueError(f"{what}: times of shape (n,) with n >= 2 and values of shape (n, 3) needed; got "
                         f"{t.shape} and {values.shape}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(values))):
        raise ValueError(f"{what}: a time or a value is not a finite number")
    if np.any(np.diff(t) <= 0):
        raise ValueError(f"{what}: the times must increase (sample {int(np.argmax(np.diff(t) <= 0)) + 1} does not)")
    return t, values


def phyphox_files(t: ArrayLike, omega: ArrayLike, *, accel: ArrayLike | None = None,
                  accel_t: ArrayLike | None = None, events: Sequence[tuple[str, float]] | None = None,
                  started: float = 1.7e9) -> dict[str, bytes]:
    """The files of a phyphox export (module docstring) of a gyroscope's record: name -> content.

    Parameters
    ----------
    t : array_like, shape (n,)
        The sample times, phyphox's experiment time, s (increasing).
    omega : array_like, shape (n, 3)
        The gyroscope's rates, sensor axes, rad/s.
    accel : array_like, shape (n, 3) or (m, 3), optional
        The accelerometer's specific force (gravity included), sensor axes, m/s^2: at the times
        ``t``, or at ``accel_t``. With it the export is an experiment of several sensors
        (``Gyroscope.csv`` and ``Accelerometer.csv``).
    accel_t : array_like, shape (m,), optional
        The accelerometer's own sample times, s (default ``t``).
    events : sequence of (str, float), optional
        phyphox's ``START`` and ``PAUSE`` events at their experiment times, s, for
        ``meta/time.csv`` (default one ``START`` at 0 s).
    started : float
        The system time of the experiment time 0, s since 1970 (UTC), for ``meta/time.csv``'s
        "system time" columns (no reader uses them).

    Returns
    -------
    dict of str to bytes
        ``"Raw Data.csv"`` (or ``"Gyroscope.csv"`` and ``"Accelerometer.csv"``) and
        ``"meta/time.csv"``.

    Raises
    ------
    ValueError
        Shapes that do not match, a value that is not finite, times that do not increase, an
        event other than ``START`` or ``PAUSE``.

    Examples
    --------
    >>> from tumble.io.phyphoxwrite import phyphox_files
    >>> files = phyphox_files([0.0, 0.01], [[1.0, 0.0, 0.0], [1.0, 0.5, 0.0]])
    >>> sorted(files)
    ['Raw Data.csv', 'meta/time.csv']
    >>> print(files["Raw Data.csv"].decode())
    "Time (s)","Gyroscope x (rad/s)","Gyroscope y (rad/s)","Gyroscope z (rad/s)","Absolute (rad/s)"
    0.000000000E+00,1.000000000E+00,0.000000000E+00,0.000000000E+00,1.000000000E+00
    1.000000000E-02,1.000000000E+00,5.000000000E-01,0.000000000E+00,1.118033989E+00
    <BLANKLINE>
    >>> files["meta/time.csv"].decode().splitlines()[1]
    '"START",0.000000000E+00,1700000000.000,"2023-11-14 22:13:20.000 UTC+00:00"'
    """
    t, omega = _samples(t, omega, "the gyroscope's record")
    events = [("START", 0.0)] if events is None else [(str(name), float(te)) for name, te in events]
    for name, te in events:
        if name not in ("START", "PAUSE") or not np.isfinite(te):
            raise ValueError(f"event ({name!r}, {te}): phyphox's events are START and PAUSE at finite times")
    magnitude = np.linalg.norm(omega, axis=1)
    files = {}
    if accel is None:
        files[GYRO_CSV] = _table(_GYRO_HEADER, [t, omega, magnitude])
    else:
        files[MULTI_GYRO_CSV] = _table(_GYRO_HEADER, [t, omega, magnitude])
        ta, f = _samples(t if accel_t is None else accel_t, accel, "the accelerometer's record")
        files[ACCEL_CSV] = _table(_ACCEL_HEADER, [ta, f, np.linalg.norm(f, axis=1)])
    lines = [_TIME_HEADER]
    for name, te in events:
        stamp = datetime.fromtimestamp(started + te, tz=timezone.utc)
        lines.append(f'"{name}",{te:.9E},{started + te:.3f},'
                     f'"{stamp:%Y-%m-%d %H:%M:%S}.{stamp.microsecond // 1000:03d} UTC+00:00"')
    files[TIME_CSV] = ("\n".join(lines) + "\n").encode("utf-8")
    return files


def write_phyphox(path: str | os.PathLike[str], t: ArrayLike, omega: ArrayLike, *, accel: ArrayLike | None = None,
                  accel_t: ArrayLike | None = None, events: Sequence[tuple[str, float]] | None = None) -> Path:
    """Write a phyphox export (:func:`phyphox_files`): a ``.zip``, or else a folder; whole or not at all.

    A zip is written beside and renamed into place (:mod:`tumble.io.atomic`; an existing file of
    that name is replaced). A folder is built in a temporary folder beside it and renamed into
    place: it must not exist, or be empty.

    Parameters
    ----------
    path : str or os.PathLike
        ``NAME.zip`` for a zip (as phyphox's "share" writes it), any other name for a folder.
    t, omega, accel, accel_t, events
        As :func:`phyphox_files`.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ValueError
        As :func:`phyphox_files`; a folder ``path`` that exists and is not empty (nothing is
        written then).

    Examples
    --------
    A synthetic phone recording of three tosses of a box-shaped phone, with its accelerometer
    and a pause, as phyphox's zip; ``tumble fit toss.zip`` reads it as the app's:

    >>> import tempfile
    >>> from pathlib import Path
    >>> import numpy as np
    >>> from tumble.analysis.fit.synthetic import synthetic_recording
    >>> from tumble.io.gyrodata import load_recording
    >>> from tumble.io.phyphoxwrite import write_phyphox
    >>> rec = synthetic_recording(2, body="phone", tosses=3, accel=True, pauses=1)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_phyphox(Path(folder) / "toss.zip", rec.t, rec.omega, accel=rec.accel.f, events=rec.events)
    ...     again = load_recording(path)
    >>> bool(np.allclose(again.omega, rec.omega, rtol=1e-9, atol=1e-12)), [name for name, _ in again.events]
    (True, ['START', 'PAUSE', 'START'])
    >>> bool(np.allclose(again.accel, rec.accel.f, rtol=1e-9, atol=1e-9))   # the accelerometer's, at the same times
    True
    >>> again.read.brief().startswith("Time (s), Gyroscope x, Gyroscope y, Gyroscope z (rad/s)")
    True
    """
    files = phyphox_files(t, omega, accel=accel, accel_t=accel_t, events=events)
    path = Path(path)
    if path.suffix.lower() == ".zip":
        buffer = io.BytesIO()
        with zipfile.ZipFile(buffer, "w", compression=zipfile.ZIP_DEFLATED) as archive:
            for name, data in files.items():
                archive.writestr(name, data)
        return atomic_write_bytes(path, buffer.getvalue())
    if path.exists() and not (path.is_dir() and not any(path.iterdir())):
        raise ValueError(f"{path}: exists and is not an empty folder; write_phyphox never overwrites a folder")
    with atomic_folder(path) as stage:
        for name, data in files.items():
            (stage / name).parent.mkdir(parents=True, exist_ok=True)
            (stage / name).write_bytes(data)
    return path
