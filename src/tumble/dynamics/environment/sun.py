"""The Sun: a low-precision ephemeris and the Earth's shadow (cylindrical, and conical with the penumbra).

**Ephemeris** (*The Astronomical Almanac*, section C, "Low-precision formulas for the Sun";
the same in Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed., 2013, sec. 5.1,
algorithm 29): with ``n = JD - 2451545.0`` days,

``L = 280.460 deg + 0.9856474 deg n`` (mean longitude, aberration included),
``g = 357.528 deg + 0.9856003 deg n`` (mean anomaly),
``lambda = L + 1.915 deg sin g + 0.020 deg sin 2g`` (ecliptic longitude; latitude 0),
``epsilon = 23.439 deg - 0.0000004 deg n`` (obliquity),
``R = 1.00014 - 0.01671 cos g - 0.00014 cos 2g`` AU,

and the geocentric position ``R (cos lambda, cos epsilon sin lambda, sin epsilon sin lambda)``
in the mean equator and equinox of date, which this module takes for ECI (the precession since
J2000 is 0.36 deg in 2026, beside the formula's stated 0.01 deg for 1950-2050: a Sun direction
good to about 0.4 deg, ample for the sensors and the shadow).

**Shadow** (Montenbruck & Gill, *Satellite Orbits*, Springer 2000, sec. 3.4.2):

- *cylindrical*: the satellite at ``r`` is in shadow when it is behind the Earth
  (``r . s < 0``, ``s`` the unit Sun direction) and within ``R_EARTH`` of the Earth-Sun line;
  fraction 0 or 1;
- *conical*: the apparent radii of the Sun and the Earth seen from the satellite,
  ``a = asin(R_SUN / |r_sun - r|)`` and ``b = asin(R_EARTH / |r|)``, and their apparent
  separation ``c = acos(-r . (r_sun - r) / (|r| |r_sun - r|))`` (eqs. 3.85-3.86). Full light if
  ``c >= a + b``; total eclipse if ``c < b - a``; annular (``1 - b^2 / a^2``) if ``c < a - b``;
  otherwise the penumbra, where the hidden area of the Sun's disc is
  ``A = a^2 acos(x / a) + b^2 acos((c - x) / b) - c y`` with ``x = (c^2 + a^2 - b^2) / (2 c)``
  and ``y = sqrt(a^2 - x^2)`` (eq. 3.87), and the fraction of sunlight ``1 - A / (pi a^2)``.

Examples
--------
At J2000.0 the Sun is near ecliptic longitude 280.4 deg, below the equator (declination -23 deg):

>>> import numpy as np
>>> from tumble.dynamics.environment.sun import sun_position_eci, AU
>>> r = sun_position_eci(2451545.0)
>>> round(float(np.linalg.norm(r)) / AU, 4), round(float(np.degrees(np.arcsin(r[2] / np.linalg.norm(r)))), 1)
(0.9833, -23.0)
"""

from __future__ import annotations

import datetime as _dt
import math
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...typing import ArrayLike, FloatArray
from .earth import R_EARTH
from .sidereal import julian_date

__all__ = ["AU", "R_SUN", "EphemerisSpanWarning", "Sunlight", "shadow_fraction", "sun_direction_eci", "sun_position_eci"]

class EphemerisSpanWarning(UserWarning):
    """An epoch outside 1950-2050, the span the Sun's low-precision formulas state their 0.01 deg for;
    the message says how far the precession moves the Sun's direction there. The command line says
    it in one line.

    Examples
    --------
    >>> import warnings
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> from tumble.dynamics.environment.sun import EphemerisSpanWarning, Sunlight
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     _ = Sunlight(CircularOrbit(altitude=500e3), "2300-03-20T14:46:00")
    >>> caught[0].category is EphemerisSpanWarning, str(caught[0].message)[-47:]
    (True, "adds about 4.2 deg to the Sun's direction there")
    """

    cli_one_line = True


#: The astronomical unit, m (IAU 2012 resolution B2, exact).
AU = 149597870700.0
#: The Sun's nominal radius, m (IAU 2015 resolution B3).
R_SUN = 6.957e8


def sun_position_eci(jd: ArrayLike) -> FloatArray:
    """The Sun's geocentric position at Julian date(s) ``jd`` (UTC for TT: 69 s, 0.0008 deg), m, shape (..., 3).

    The Astronomical Almanac's low-precision formula (module docstring); mean equator and
    equinox of date taken as ECI.

    Examples
    --------
    Vallado's example 5-1 (2006-04-02 00:00 UTC): ``0.9771945 I + 0.1924424 J + 0.0834308 K`` AU:

    >>> import numpy as np
    >>> from tumble.dynamics.environment.sidereal import julian_date
    >>> from tumble.dynamics.environment.sun import sun_position_eci, AU
    >>> np.round(sun_position_eci(julian_date("2006-04-02T00:00:00")) / AU, 4).tolist()
    [0.9772, 0.1924, 0.0834]

    Dates broadcast:

    >>> sun_position_eci([2451545.0, 2451545.0 + 182.6]).shape
    (2, 3)
    """
    n = np.asarray(jd, float) - 2451545.0
    L = np.radians(280.460 + 0.9856474 * n)
    g = np.radians(357.528 + 0.9856003 * n)
    lam = L + np.radians(1.915) * np.sin(g) + np.radians(0.020) * np.sin(2.0 * g)
    eps = np.radians(23.439 - 0.0000004 * n)
    R = (1.00014 - 0.01671 * np.cos(g) - 0.00014 * np.cos(2.0 * g)) * AU
    return np.asarray(np.stack([R * np.cos(lam), R * np.cos(eps) * np.sin(lam), R * np.sin(eps) * np.sin(lam)],
                               axis=-1), float)


def sun_direction_eci(jd: ArrayLike) -> FloatArray:
    """The unit vector from the Earth's centre to the Sun at Julian date(s) ``jd``, shape (..., 3).

    Examples
    --------
    At the March equinox of 2026 (20 March, 14:46 UTC) the Sun crosses the equator at right
    ascension 0:

    >>> import numpy as np
    >>> from tumble.dynamics.environment.sidereal import julian_date
    >>> from tumble.dynamics.environment.sun import sun_direction_eci
    >>> s = sun_direction_eci(julian_date("2026-03-20T14:46:00"))
    >>> bool(abs(s[2]) < 2e-3 and s[0] > 0.999)
    True
    """
    r = sun_position_eci(jd)
    return np.asarray(r / np.linalg.norm(r, axis=-1, keepdims=True), float)


def shadow_fraction(r_sat: ArrayLike, r_sun: ArrayLike, model: str = "conical") -> FloatArray:
    """The fraction of the Sun's light that reaches a satellite, 0 (umbra) to 1 (full Sun).

    Parameters
    ----------
    r_sat : array_like, shape (..., 3)
        The satellite's geocentric position, m (any inertial frame).
    r_sun : array_like, shape (..., 3)
        The Sun's geocentric position in the same frame, m (:func:`sun_position_eci`).
    model : {"conical", "cylindrical"}
        Conical with the penumbra, or the cylindrical shadow (0 or 1); module docstring.

    Returns
    -------
    ndarray, shape (...)

    Examples
    --------
    At 7,000 km on the Earth-Sun line, behind the Earth: umbra; on the sunny side: full Sun;
    at the shadow's edge the conical model has a penumbra between:

    >>> import numpy as np
    >>> from tumble.dynamics.environment.sun import shadow_fraction, AU
    >>> sun = np.array([AU, 0.0, 0.0])
    >>> shadow_fraction([[-7e6, 0.0, 0.0], [7e6, 0.0, 0.0]], sun).tolist()
    [0.0, 1.0]
    >>> from tumble.dynamics.environment.earth import R_EARTH
    >>> f = float(shadow_fraction([-7e6, R_EARTH, 0.0], sun))
    >>> 0.0 < f < 1.0, float(shadow_fraction([-7e6, R_EARTH - 1.0, 0.0], sun, "cylindrical"))
    (True, 0.0)
    """
    r = np.asarray(r_sat, float)
    rs = np.asarray(r_sun, float)
    if model == "cylindrical":
        s = rs / np.linalg.norm(rs, axis=-1, keepdims=True)
        along = np.sum(r * s, axis=-1)
        across = np.linalg.norm(r - along[..., None] * s, axis=-1)
        return np.asarray(np.where((along < 0.0) & (across < R_EARTH), 0.0, 1.0), float)
    if model != "conical":
        raise ValueError(f"model = {model!r} is unknown; allowed: conical, cylindrical")
    d = rs - r
    rn, dn = np.linalg.norm(r, axis=-1), np.linalg.norm(d, axis=-1)
    a = np.arcsin(np.minimum(R_SUN / dn, 1.0))
    b = np.arcsin(np.minimum(R_EARTH / rn, 1.0))
    c = np.arccos(np.clip(-np.sum(r * d, axis=-1) / (rn * dn), -1.0, 1.0))
    cs = np.maximum(c, 1e-12)  # c = 0 is full light or umbra, never the penumbra's formula
    x = (cs * cs + a * a - b * b) / (2.0 * cs)
    y = np.sqrt(np.maximum(a * a - x * x, 0.0))
    hidden = a * a * np.arccos(np.clip(x / a, -1.0, 1.0)) + b * b * np.arccos(np.clip((c - x) / b, -1.0, 1.0)) - c * y
    partial = 1.0 - hidden / (math.pi * a * a)
    out = np.where(c >= a + b, 1.0, np.where(c < b - a, 0.0, np.where(c < a - b, 1.0 - (b / a) ** 2, partial)))
    return np.asarray(np.clip(out, 0.0, 1.0), float)


@dataclass(frozen=True)
class Sunlight:
    """The Sun seen along an orbit: its direction in the run's world frame and the light that reaches the body.

    Parameters
    ----------
    orbit : CircularOrbit, KeplerOrbit or TLEOrbit
        Anything with ``position_eci(t)`` (m) and ``eci_from_world`` (a scipy Rotation).
    epoch : datetime or str
        The UTC instant of t = 0 (ISO 8601 string or datetime).
    shadow : {"conical", "cylindrical", "none"}
        The Earth's shadow (:func:`shadow_fraction`), or none.

    Examples
    --------
    A 500 km equatorial orbit at the March equinox: the Sun lies along ECI x, and the body is in
    the Earth's shadow half an orbit after it starts on the sunward side:

    >>> import numpy as np
    >>> from tumble.dynamics.environment.orbit import CircularOrbit
    >>> from tumble.dynamics.environment.sun import Sunlight
    >>> orbit = CircularOrbit(altitude=500e3)
    >>> light = Sunlight(orbit, "2026-03-20T14:46:00")
    >>> (np.round(light.world(0.0), 2) + 0.0).tolist(), light.fraction([0.0, orbit.period / 2]).tolist()
    ([1.0, 0.0, 0.0], [1.0, 0.0])
    """

    orbit: Any
    epoch: _dt.datetime | str
    shadow: str = "conical"

    def __post_init__(self) -> None:
        jd0 = julian_date(self.epoch)
        object.__setattr__(self, "_jd0", jd0)
        years = (float(jd0) - 2451545.0) / 365.25  # from J2000
        # the formulas' stated span; past it the general precession in longitude, 5028.796"/century (IAU 2006,
        # Capitaine, Wallace & Chapront, A&A 412 (2003) 567, eq. 39), which this ECI of date leaves in, grows
        if not -50.0 <= years <= 50.0:
            warnings.warn(f"epoch = {self.epoch!s} lies outside 1950-2050, the span of the Sun's low-precision formulas "
                          f"(0.01 deg); the precession of the equinoxes, which this ECI leaves in, adds about "
                          f"{abs(years) * 50.29 / 3600.0:.2g} deg to the Sun's direction there", EphemerisSpanWarning, stacklevel=3)
        if self.shadow not in ("conical", "cylindrical", "none"):
            raise ValueError(f"shadow = {self.shadow!r} is unknown; allowed: conical, cylindrical, none")
        for name in ("position_eci", "eci_from_world"):
            if not hasattr(self.orbit, name):
                raise ValueError(f"orbit = {self.orbit!r} has no {name}: give a CircularOrbit, KeplerOrbit or TLEOrbit")

    def _sun_eci(self, t: ArrayLike) -> FloatArray:
        return sun_position_eci(getattr(self, "_jd0") + np.asarray(t, float) / 86400.0)

    def world(self, t: ArrayLike) -> FloatArray:
        """The unit vector to the Sun in the world frame at ``t`` (s), shape ``t.shape + (3,)``
        (from the body's place: the parallax of the orbit, 5e-5 rad in LEO, neglected).

        Examples
        --------
        A circular orbit's world frame is its orbit plane; turned back into ECI the direction is
        :func:`sun_direction_eci`'s ten minutes after the epoch:

        >>> import numpy as np
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> from tumble.dynamics.environment.sun import Sunlight, sun_direction_eci
        >>> from tumble.dynamics.environment.sidereal import julian_date
        >>> orbit = CircularOrbit(altitude=500e3, raan=np.pi / 2)
        >>> light = Sunlight(orbit, "2026-03-20T14:46:00")
        >>> s = sun_direction_eci(julian_date("2026-03-20T14:46:00") + 600.0 / 86400.0)
        >>> bool(np.allclose(orbit.eci_from_world.apply(light.world(600.0)), s))
        True
        """
        s = self._sun_eci(t)
        return np.asarray(self.orbit.eci_from_world.inv().apply(s.reshape(-1, 3)).reshape(s.shape)
                          / np.linalg.norm(s, axis=-1, keepdims=True), float)

    def fraction(self, t: ArrayLike) -> FloatArray:
        """The fraction of the Sun's light reaching the body at ``t`` (s): 0 in the umbra, 1 in full Sun.

        Examples
        --------
        Over one orbit with the Sun in its plane, the body is in the umbra for about 36 minutes:

        >>> import numpy as np
        >>> from tumble.dynamics.environment.orbit import CircularOrbit
        >>> from tumble.dynamics.environment.sun import Sunlight
        >>> orbit = CircularOrbit(altitude=500e3)
        >>> f = Sunlight(orbit, "2026-03-20T14:46:00").fraction(np.arange(0.0, orbit.period, 1.0))
        >>> round(float(np.sum(f == 0.0)) / 60)   # min
        36
        """
        if self.shadow == "none":
            return np.ones(np.shape(t))
        return shadow_fraction(self.orbit.position_eci(t), self._sun_eci(t), self.shadow)
