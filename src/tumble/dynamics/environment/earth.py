"""The Earth's constants, in one place: its gravitational parameter, equatorial radius, rotation rate
and standard gravity; and the Earth's turn, the angle of the Earth-fixed frame at a time.

Every orbit, field and torque model of tumble reads them from here (``tests/test_architecture.py``
checks that their values are written nowhere else in the package):

- :data:`MU_EARTH`, the gravitational parameter ``GM`` (IERS Conventions 2010, Technical Note
  36, table 1.1; the WGS 84 value);
- :data:`R_EARTH`, the equatorial radius (IERS Conventions 2010, table 1.1: 6378136.6 m,
  rounded to 0.1 km);
- :data:`OMEGA_EARTH`, the mean angular velocity of the Earth's rotation (IERS Conventions
  2010, sec. 1.2), the rate at which the Earth-fixed frame turns about ECI z;
- :data:`STANDARD_GRAVITY`, the conventional ``g_n`` (3rd CGPM, 1901; ISO 80000-3), the unit
  ``g`` of an accelerometer's readings.

:func:`earth_angle` is the one writing of the Earth's turn, ``theta = theta0 + OMEGA_EARTH t``:
the fields (:mod:`~tumble.dynamics.environment.magnetic`, :mod:`~tumble.dynamics.environment.igrf`)
call it, over floats or arrays.

Examples
--------
A circular orbit of one sidereal day's period (2 pi / OMEGA_EARTH) lies at the geostationary
radius, Kepler's third law ``r^3 = mu / n^2``:

>>> import math
>>> from tumble.dynamics.environment.earth import MU_EARTH, OMEGA_EARTH
>>> round(math.cbrt(MU_EARTH / OMEGA_EARTH**2) / 1e3)   # km
42164
"""

from __future__ import annotations

from typing import Any

import math

from ...jit import formula
from ...validation import check_positive

__all__ = ["EARTH_MU_TOLERANCE", "MU_EARTH", "OMEGA_EARTH", "R_EARTH", "STANDARD_GRAVITY", "check_mu", "earth_angle",
           "is_earth"]

#: The Earth's gravitational parameter GM, m^3/s^2 (IERS Conventions 2010, table 1.1; WGS 84).
MU_EARTH = 3.986004418e14
#: The Earth's equatorial radius, m (IERS Conventions 2010: 6378136.6 m, rounded): with
#: ``mu = MU_EARTH`` an orbit must have a larger radius.
R_EARTH = 6.3781e6
#: The Earth's rotation rate, rad/s (IERS Conventions 2010, sec. 1.2).
OMEGA_EARTH = 7.292115e-5
#: Standard gravity ``g_n``, m/s^2, exact by definition (3rd CGPM, 1901; ISO 80000-3): the unit
#: ``g`` in which accelerometers report, not the local gravity.
STANDARD_GRAVITY = 9.80665
#: How near :data:`MU_EARTH` (relative) a gravitational parameter is the Earth's: the rounded values in
#: use (3.986e14, SGP4's WGS 72 3.986008e14) are, and an orbit about them must then lie above :data:`R_EARTH`
#: (an orbit check keyed to the exact value let ``mu = 3.986e14`` put one 930 km underground).
EARTH_MU_TOLERANCE = 0.01


def is_earth(mu: float) -> bool:
    """Whether ``mu`` (m^3/s^2) is the Earth's gravitational parameter, to within :data:`EARTH_MU_TOLERANCE`.

    Examples
    --------
    >>> from tumble.dynamics.environment.earth import is_earth
    >>> is_earth(3.986004418e14), is_earth(3.986e14), is_earth(4.9048695e12)   # the Moon's is not
    (True, True, False)
    """
    return math.isclose(mu, MU_EARTH, rel_tol=EARTH_MU_TOLERANCE)


def check_mu(value: object, field: str = "mu") -> float:
    """A gravitational parameter, m^3/s^2: a positive finite number, and not the Earth's written in
    km^3/s^2 (398600.4418: an orbit 31,600 times slower, a gravity-gradient torque 1e9 times weaker).

    Examples
    --------
    >>> from tumble.dynamics.environment.earth import check_mu
    >>> check_mu(3.986e14)
    398600000000000.0
    >>> check_mu(398600.4418)
    Traceback (most recent call last):
    ...
    ValueError: mu = 398600.4418 m^3/s^2 is the Earth's in km^3/s^2; give m^3/s^2 (3.986004418e+14)
    """
    mu = check_positive(field, value, "m^3/s^2")
    if math.isclose(mu, MU_EARTH / 1e9, rel_tol=EARTH_MU_TOLERANCE):
        raise ValueError(f"{field} = {value!r} m^3/s^2 is the Earth's in km^3/s^2; give m^3/s^2 ({MU_EARTH:.10g})")
    return mu


@formula
def earth_angle(theta0: Any, t: Any) -> Any:
    """The Earth's angle about ECI z at ``t`` (s), rad: ``theta0 + OMEGA_EARTH t``.

    The Earth-fixed frame (ECEF) turns at :data:`OMEGA_EARTH` about ECI z; ``theta0`` is its
    angle at t = 0 (the Greenwich sidereal angle of the epoch,
    :func:`~tumble.dynamics.environment.sidereal.greenwich_sidereal_angle`), and
    ``r_ecef = R3(theta) r_eci`` (Vallado, *Fundamentals of Astrodynamics and Applications*,
    4th ed., sec. 3.5). Floats (a compiled kernel) or arrays that broadcast: the one writing of
    the Earth's turn.

    Examples
    --------
    >>> import math
    >>> from tumble.dynamics.environment.earth import OMEGA_EARTH, earth_angle
    >>> math.isclose(earth_angle(0.5, 2 * math.pi / OMEGA_EARTH), 0.5 + 2 * math.pi)   # one sidereal day: a turn
    True
    """
    return theta0 + OMEGA_EARTH * t
