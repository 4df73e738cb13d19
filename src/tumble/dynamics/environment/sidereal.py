"""Dates and the Earth's rotation for the orbit and field models: Julian dates of UTC instants
and the Greenwich mean sidereal angle.

**Sidereal angle.** Greenwich mean sidereal time, IAU 1982 (Vallado, *Fundamentals of
Astrodynamics and Applications*, 4th ed., sec. 3.5.2, eq. 3-45):
``theta = 67310.54841 s + (876600 h + 8640184.812866 s) T + 0.093104 s T^2 - 6.2e-6 s T^3``,
``T`` Julian centuries of UT1 from J2000.0 (UTC is used for UT1: within 0.9 s, 4e-3 deg).
"""

from __future__ import annotations

import datetime as _dt
import math

import numpy as np

from ...typing import ArrayLike, FloatArray

__all__ = ["J2000", "greenwich_sidereal_angle", "julian_date", "utc_datetime"]

#: J2000.0, the epoch of Julian date 2451545.0 (UTC).
J2000 = _dt.datetime(2000, 1, 1, 12, 0, 0, tzinfo=_dt.UTC)


def julian_date(when: _dt.datetime | str) -> float:
    """The Julian date of a UTC instant (a ``datetime``, naive read as UTC, or an ISO 8601 string).

    Counted from J2000.0 = JD 2451545.0 (2000-01-01 12:00 UTC) in days of 86,400 s; leap seconds
    are not counted (the Julian date of UTC, as SGP4 uses it).

    Examples
    --------
    >>> from tumble.dynamics.environment.sidereal import julian_date
    >>> julian_date("2000-01-01T12:00:00")
    2451545.0
    >>> julian_date("2026-11-25T00:00:00+00:00")
    2461369.5
    """
    t = utc_datetime(when, "epoch")
    return 2451545.0 + (t - J2000).total_seconds() / 86400.0


def utc_datetime(when: object, name: str) -> _dt.datetime:
    """``when`` (a ``datetime``, naive read as UTC, or an ISO 8601 string) as an aware UTC datetime;
    a ValueError names ``name`` otherwise.

    Examples
    --------
    >>> from tumble.dynamics.environment.sidereal import utc_datetime
    >>> utc_datetime("2026-11-25T01:00:00+01:00", "epoch").isoformat()
    '2026-11-25T00:00:00+00:00'
    >>> utc_datetime(3, "epoch")
    Traceback (most recent call last):
    ...
    ValueError: epoch = 3 must be a datetime or an ISO 8601 string (UTC)
    """
    if isinstance(when, str):
        try:
            when = _dt.datetime.fromisoformat(when)
        except ValueError:
            raise ValueError(f"{name} = {when!r} is not an ISO 8601 date and time, e.g. 2026-11-25T00:00:00") from None
    if not isinstance(when, _dt.datetime):
        raise ValueError(f"{name} = {when!r} must be a datetime or an ISO 8601 string (UTC)")  # noqa: TRY004 - one error type for bad input
    return when.replace(tzinfo=_dt.UTC) if when.tzinfo is None else when.astimezone(_dt.UTC)


def greenwich_sidereal_angle(jd_ut1: ArrayLike) -> FloatArray:
    """Greenwich mean sidereal angle (IAU 1982) at Julian date(s) ``jd_ut1``, rad in [0, 2 pi).

    Examples
    --------
    Vallado's example 3-5 (1992-08-20 12:14 UT1): 152.578787810 deg:

    >>> import math
    >>> from tumble.dynamics.environment.sidereal import greenwich_sidereal_angle, julian_date
    >>> jd = julian_date("1992-08-20T12:14:00")
    >>> round(math.degrees(float(greenwich_sidereal_angle(jd))), 6)
    152.578788
    """
    T = (np.asarray(jd_ut1, float) - 2451545.0) / 36525.0
    seconds = 67310.54841 + (876600.0 * 3600.0 + 8640184.812866) * T + 0.093104 * T**2 - 6.2e-6 * T**3
    return np.asarray(np.mod(seconds, 86400.0) * (2.0 * math.pi / 86400.0), float)
